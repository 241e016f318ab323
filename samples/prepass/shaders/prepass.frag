#version 450
// The prepass fragment stage (samples/prepass): camera-space position and face normal of the
// nearest surface into two RGBA32F attachments. With -DSAO_PREPASS_PEEL it is the second layer of
// a deep G-buffer: a fragment survives only if it lies more than the minimum separation behind the
// first layer at its pixel, the first layer's camera-space z being reconstructed from its depth
// texel with eq. 2 (the effect's own sao_z_from_depth rules, sky included); the depth test of the
// second depth attachment then keeps the nearest survivor.
layout(location = 0) in vec3 camera_position;
layout(location = 1) flat in vec3 camera_normal;

#ifdef SAO_PREPASS_VULKAN
layout(set = 0, binding = 0, std140) uniform PrepassBlock {
#else
layout(binding = 0, std140) uniform PrepassBlock {
#endif
  mat4 mvp;
  mat4 model_view;
  vec4 clip_info;
  vec4 peel;
} u;

#ifdef SAO_PREPASS_PEEL
#ifdef SAO_PREPASS_VULKAN
layout(set = 0, binding = 1) uniform sampler2D first_layer_depth;
#else
layout(binding = 1) uniform sampler2D first_layer_depth;
#endif

// Camera-space z of a stored depth d, or +0.0 for sky (docs/effect-math.md, 2.1 and 1).
float z_from_depth(float d) {
  if (isnan(d) || isinf(d) || d * u.peel.x >= u.peel.y) return 0.0;
  const float z = (u.clip_info.w != 0.0) ? u.clip_info.x / (d * u.clip_info.y + u.clip_info.z)
                                         : d * u.clip_info.y + u.clip_info.z;
  return (isnan(z) || isinf(z) || !(z < 0.0)) ? 0.0 : z;
}
#endif

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;

void main() {
  const vec3 p = camera_position;
#ifdef SAO_PREPASS_PEEL
  const float z1 = z_from_depth(texelFetch(first_layer_depth, ivec2(gl_FragCoord.xy), 0).r);
  // Nothing in front (sky) means nothing behind either; otherwise keep only what lies more than the
  // separation behind the first layer.
  if (z1 == 0.0 || !(z1 - p.z > u.peel.z)) discard;
#endif
  // The view ray: from the eye through p (perspective) or along -z (orthographic).
  const vec3 view_dir = (u.clip_info.w != 0.0) ? p : vec3(0.0, 0.0, -1.0);
#ifdef SAO_PREPASS_PEEL
  // Optionally only surfaces that face the camera as wound (counter-clockwise seen from outside):
  // a closed object's own far side is not what the second layer is for.
  if (u.peel.w != 0.0 && dot(camera_normal, view_dir) > 0.0) discard;
#endif
  // normalize() spelled out, without contraction: the GLSL and SPIR-V front ends lower normalize()
  // differently, and the OpenGL and Vulkan prepasses should write the same bits.
  precise float l2 = (camera_normal.x * camera_normal.x + camera_normal.y * camera_normal.y) +
                     camera_normal.z * camera_normal.z;
  vec3 n = (l2 > 0.0) ? camera_normal * inversesqrt(l2) : vec3(0.0);
  if (dot(n, view_dir) > 0.0) n = -n;  // face the camera
  out_position = vec4(p, 1.0);
  out_normal = vec4(n, 0.0);
}
