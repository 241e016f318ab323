#version 450
// The prepass vertex stage (samples/prepass). One vertex stream of three vertices per triangle:
// the world-space position and the triangle's world-space face normal (computed in double on the
// host, identical on the three vertices). The matrices are built in double on the host and handed
// over as float. Compiled as it is for OpenGL 4.5 and to SPIR-V with -DSAO_PREPASS_VULKAN.
layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;

#ifdef SAO_PREPASS_VULKAN
layout(set = 0, binding = 0, std140) uniform PrepassBlock {
#else
layout(binding = 0, std140) uniform PrepassBlock {
#endif
  mat4 mvp;         // clip from world, frustum widened by the guard band
  mat4 model_view;  // camera (view units) from world
  vec4 clip_info;   // eq. 2: (c0, c1, c2, perspective ? 1 : 0)
  vec4 peel;        // (far_dir, far_lim, minimum separation in view units, cull back faces ? 1 : 0)
} u;

layout(location = 0) out vec3 camera_position;
layout(location = 1) flat out vec3 camera_normal;

// m * (v, 1) with the operations in this order and no FMA contraction (`precise`), so that every
// compiler (GLSL or SPIR-V front end, any driver) rounds the same way: the OpenGL and Vulkan
// prepasses then store the same depth bits.
vec4 transform_point(mat4 m, vec3 v) {
  precise vec4 r = ((m[0] * v.x + m[1] * v.y) + m[2] * v.z) + m[3];
  return r;
}
vec3 transform_vector(mat4 m, vec3 v) {
  precise vec3 r = (m[0].xyz * v.x + m[1].xyz * v.y) + m[2].xyz * v.z;
  return r;
}

void main() {
  camera_position = transform_point(u.model_view, world_position).xyz;
  camera_normal = transform_vector(u.model_view, world_normal);
  gl_Position = transform_point(u.mvp, world_position);
}
