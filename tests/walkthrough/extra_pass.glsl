#version 450
#extension GL_GOOGLE_include_directive : require
// The walkthrough's extended effect (docs/adding-a-pass.md): the real effect, unchanged, plus one
// image and one pass. Built by tests/walkthrough/CMakeLists.txt with sao_generate_effect; the
// backends are compiled again from their unchanged sources against what it generates.
#include "../../effect/sao.glsl"

// An effect-owned image: r32f holds A * 0.5 exactly (A is a binary16 value in [0, 1]).
#pragma sao resource ao_half kind=image format=r32f "walkthrough: the final visibility A times 0.5"

// Passes never read an output (codegen refuses it), so this pass computes blur_v's A again from
// blur_v's own input with the same library function, then halves it. blur_h is skipped when
// blur_radius == 0, so reading its image needs the same alias blur_v declares.
#pragma sao pass ao_halve entry=walkthrough_ao_halve_main local=8x8 reads=ao_blur_h writes=ao_half alias_when=blur_radius==0:ao_blur_h=ao_raw "walkthrough: the final A times 0.5, into ao_half"
void walkthrough_ao_halve_main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(out_ao_half))))
        return;
    vec2 r = sao_bilateral_blur(in_ao_blur_h, p, ivec2(0, 1), blur_radius, blur_stride,
                                blur_edge_sharpness, blur_weights_1_4, blur_weights_5_8);
    imageStore(out_ao_half, p, vec4(sao_round_to_half(r.x) * 0.5, 0.0, 0.0, 0.0));
}
#pragma sao end
