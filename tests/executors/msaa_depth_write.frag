#version 450
// Writes sample `sample_index` of every texel of a multisampled depth attachment from a buffer laid
// out like sao::DepthImage::texels (sample s of texel (x, y) at (y * width + x) * samples + s).
// One draw per sample: the shader runs once per pixel and gl_SampleMask keeps the write to that
// sample only, which needs no sampleRateShading (gl_SampleID would, and the headless device does
// not enable it).
layout(std430, set = 0, binding = 0) readonly buffer SaoTestSamples { float sao_values[]; };
layout(push_constant) uniform SaoTestPush {
    int width;
    int samples;
    int sample_index;
};

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);  // framebuffer y = 0 is the image's row 0 (viewport not flipped)
    gl_FragDepth = sao_values[(p.y * width + p.x) * samples + sample_index];
    gl_SampleMask[0] = 1 << sample_index;
}
