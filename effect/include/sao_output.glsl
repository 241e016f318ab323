// sao_output.glsl -- the texel the final pass stores into the output: A quantised exactly as the
// output's format holds it, in the channels the host's mask selects. Library code: depends on
// sao_blur.glsl (sao_round_to_half). Math: docs/effect-math.md, "The output texel".
#ifndef SAO_OUTPUT_GLSL
#define SAO_OUTPUT_GLSL

// OUTPUT_FORMAT (a pass variant) indexes resource ao's formats=[r16f,r8,rgba8,rgba16f].
#define SAO_OUTPUT_IS_UNORM8(f) ((f) == 1 || (f) == 2)
#define SAO_OUTPUT_IS_RGBA(f) ((f) >= 2)
#define SAO_OUTPUT_ALL_CHANNELS 15

// x clamped to [0, 1] and rounded to the nearest multiple of 1/255 (halves up): the 8-bit UNORM
// value is chosen here, so the store's own float-to-unorm rounding (implementation-defined in GL
// and Vulkan) always lands on it (k/255 is within an ulp of k/255 whatever the division's error).
float sao_round_to_unorm8(float x)
{
    return floor(clamp(x, 0.0, 1.0) * 255.0 + 0.5) / 255.0;
}

// The stored texel: channel c gets the quantised A when bit c of mask is set (bit 0 = R), else
// keeps `kept` (the texel's previous value for an RGBA output; ignored channels of an R output).
vec4 sao_output_texel(float a, bool unorm8, vec4 kept, int mask)
{
    float q = unorm8 ? sao_round_to_unorm8(a) : sao_round_to_half(a);
    bvec4 take = bvec4((mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0, (mask & 8) != 0);
    return mix(kept, vec4(q), take);
}

// Stores A at pixel p of the pass's `out_ao` binding (a macro: each pass declares its own), loading
// the texel first only for an RGBA output whose mask keeps channels. Defined only in the passes
// that have the OUTPUT_FORMAT variant.
#if defined(OUTPUT_FORMAT) && SAO_OUTPUT_IS_RGBA(OUTPUT_FORMAT)
#define SAO_STORE_OUTPUT(p, a) \
    imageStore(out_ao, (p), sao_output_texel((a), SAO_OUTPUT_IS_UNORM8(OUTPUT_FORMAT), \
        output_mask == SAO_OUTPUT_ALL_CHANNELS ? vec4(0.0) : imageLoad(out_ao, (p)), output_mask))
#elif defined(OUTPUT_FORMAT)
#define SAO_STORE_OUTPUT(p, a) \
    imageStore(out_ao, (p), sao_output_texel((a), SAO_OUTPUT_IS_UNORM8(OUTPUT_FORMAT), vec4(0.0, 0.0, 0.0, 1.0), output_mask))
#endif

#endif // SAO_OUTPUT_GLSL
