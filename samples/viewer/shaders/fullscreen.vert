#version 450
// One triangle covering the viewport (no vertex buffer; GL needs an empty VAO bound).
#ifdef SAO_VIEWER_VULKAN
#define VERTEX_ID gl_VertexIndex
#else
#define VERTEX_ID gl_VertexID
#endif

void main() {
  vec2 p = vec2(float((VERTEX_ID << 1) & 2), float(VERTEX_ID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
