#version 450
#extension GL_GOOGLE_include_directive : require
// The walkthrough's extended effect (docs/adding-a-pass.md): the real effect, unchanged, plus one
// image and one pass. Built by tests/walkthrough/CMakeLists.txt with sao_generate_effect; the
// backends are compiled again from their unchanged sources against what it generates.
#include "../../effect/sao.glsl"

// An effect-owned image: r32f holds A * 0.5 exactly (A is a binary16 value in [0, 1]).
#pragma sao resource ao_half kind=image format=r32f "walkthrough: the final visibility A times 0.5"

// A new input (section 6): a factor per texel of the depth's region, which ao_halve applies when
// the engine gives it. The variant follows the input's presence; formats= is what the backends accept.
#pragma sao variant AO_SCALED values=[0,1] default=0 select=input:ao_scale "walkthrough: 1 when the engine gives ao_scale"
#pragma sao resource ao_scale kind=input format=r32f formats=[r32f] when=AO_SCALED "walkthrough: a factor per texel of the depth's region (the guard band included), applied to ao_half"

// Passes never read an output (codegen refuses it), so this pass reads the output pass's own input:
// at full resolution the output is that image's A, rounded to binary16. The blur is skipped when
// blur_radius == 0, so reading its image needs the same alias the output pass declares; and when
// ao_sample_output writes the output (direct_output: no blur, no temporal) there is no (A, key)
// image at all, so the pass is skipped then.
#pragma sao pass ao_halve entry=walkthrough_ao_halve_main local=8x8 reads=ao_low,ao_scale writes=ao_half variants=AO_SCALED skip_when=direct_output==true alias_when=blur_radius==0:ao_low=ao_raw "walkthrough: the final A times 0.5 (times ao_scale where given), into ao_half"
void walkthrough_ao_halve_main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(out_ao_half))))
        return;
    float a = texelFetch(in_ao_low, p, 0).x;
    float half_a = sao_round_to_half(a) * 0.5;
#if AO_SCALED
    half_a *= texelFetch(in_ao_scale, p + guard + input_offset, 0).x;
#endif
    imageStore(out_ao_half, p, vec4(half_a, 0.0, 0.0, 0.0));
}
#pragma sao end
