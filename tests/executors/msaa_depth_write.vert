#version 450
// One triangle covering the whole framebuffer (vertices 0, 1, 2 at (-1,-1), (3,-1), (-1,3)); the
// fragment shader supplies the depth.
void main()
{
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.5, 1.0);
}
