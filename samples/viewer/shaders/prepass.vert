#version 450
// The viewer's OpenGL depth-only prepass (Vulkan uses samples/prepass): scene mesh vertices in
// world space and one MVP, built in double on the host and cast to float. Compiled as GLSL 4.30
// (the version line is replaced).
layout(location = 0) in vec3 position;
layout(location = 0) uniform mat4 mvp;

void main() { gl_Position = mvp * vec4(position, 1.0); }
