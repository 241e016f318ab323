#version 450
// The viewer's depth-only prepass: scene mesh vertices in world space and one MVP, built in double
// on the host and cast to float. Compiled as GLSL 4.30 for OpenGL (the version line is replaced)
// and to SPIR-V with -DSAO_VIEWER_VULKAN for Vulkan.
layout(location = 0) in vec3 position;
#ifdef SAO_VIEWER_VULKAN
layout(push_constant) uniform Prepass {
  mat4 mvp;
} pc;
#define MVP pc.mvp
#else
layout(location = 0) uniform mat4 mvp;
#define MVP mvp
#endif

void main() { gl_Position = MVP * vec4(position, 1.0); }
