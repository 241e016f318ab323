// sao_output.glsl -- the texel the final pass stores into the output: A quantised exactly as the
// output's format holds it, in the channels the host's mask selects. Library code: depends on
// sao_blur.glsl (sao_round_to_half_signed). Math: docs/effect-math.md, "The output texel".
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

// One channel of the stored texel, rounded once as the format holds it (binary16 of either sign, or
// a multiple of 1/255): replace stores A' = clamp(A, 0, 1), multiply the channel's value c times A'
// (an infinite or NaN c is stored back as it is: exponent bits all ones, exact whatever the compiler
// assumes about NaN). Both blends go through the one rounding: a software rasteriser (llvmpipe)
// runs every branch of a shader for every pixel, so a second rounding path is paid in full.
float sao_output_channel(float c, float a, bool unorm8, bool multiply)
{
    if (multiply && (floatBitsToUint(c) & 0x7F800000u) == 0x7F800000u)
        return c;
    float m = clamp(a, 0.0, 1.0);
    if (multiply)
        m = c * m;
    return unorm8 ? sao_round_to_unorm8(m) : sao_round_to_half_signed(m);
}

// The stored RGBA texel: channel c, when bit c of mask is set (bit 0 = R), gets A quantised
// (SAO_OUTPUT_BLEND_REPLACE) or kept.c times A (SAO_OUTPUT_BLEND_MULTIPLY); the others keep `kept`
// (the texel's previous value when the pass loaded it).
vec4 sao_output_texel(float a, bool unorm8, vec4 kept, int mask, int blend)
{
    bool multiply = blend == SAO_OUTPUT_BLEND_MULTIPLY;
    vec4 v = vec4(sao_output_channel(kept.x, a, unorm8, multiply), sao_output_channel(kept.y, a, unorm8, multiply),
                  sao_output_channel(kept.z, a, unorm8, multiply), sao_output_channel(kept.w, a, unorm8, multiply));
    bvec4 take = bvec4((mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0, (mask & 8) != 0);
    return mix(kept, v, take);
}

// The stored single-channel texel (r16f, r8): only R is computed; bit 0 of mask clear keeps it.
vec4 sao_output_texel_r(float a, bool unorm8, float kept, int mask, int blend)
{
    float v = sao_output_channel(kept, a, unorm8, blend == SAO_OUTPUT_BLEND_MULTIPLY);
    return vec4((mask & 1) != 0 ? v : kept, 0.0, 0.0, 1.0);
}

// The bent normal output's texel (BENT_NORMALS; every channel, replace: plan() refuses other masks
// and blends): the bent normal b in R, G, B, as 0.5 + 0.5 b in an rgba8 output (each rounded to a
// multiple of 1/255) or b itself rounded to binary16 in an rgba16f one, and A in A as
// sao_output_channel stores it.
vec4 sao_output_bent_texel(vec3 b, float a, bool unorm8)
{
    vec3 v = unorm8 ? vec3(sao_round_to_unorm8(0.5 + 0.5 * b.x), sao_round_to_unorm8(0.5 + 0.5 * b.y),
                           sao_round_to_unorm8(0.5 + 0.5 * b.z))
                    : vec3(sao_round_to_half_signed(b.x), sao_round_to_half_signed(b.y), sao_round_to_half_signed(b.z));
    return vec4(v, sao_output_channel(0.0, a, unorm8, false));
}

// Multi-bounce (Jimenez et al. 2016, "Practical Real-Time Strategies for Accurate Indirect
// Occlusion"): the visibility after many bounces on a surface of albedo rho, fitted from the
// single-bounce visibility x as max(x, ((a x + b) x + c) x), a, b, c from rho on the host (block
// members bounce_a/b/c). `on` false (albedo 0) returns x itself: the fit at rho = 0 is not exactly
// the identity (it exceeds x by up to ~1e-6 near x = 0.965), so it is skipped, not evaluated.
// Applied once per stored texel, before the channels' clamp to [0, 1] (the fit gives up to 1.0001 at
// x = 1 for rho > 0.8). Math: docs/effect-math.md, "Multi-bounce".
float sao_multi_bounce(float x, bool on, float a, float b, float c)
{
    return on ? max(x, ((a * x + b) * x + c) * x) : x;
}
#define SAO_BOUNCED(a) sao_multi_bounce((a), multi_bounce != 0, bounce_a, bounce_b, bounce_c)

// Stores A (through the multi-bounce fit when it is on) at pixel p of the pass's `out_ao` binding (a macro: each pass declares its own), loading
// (SAO_LOAD_AO, which sao-shaderc defines per target: the image itself, or on GLES a texture of it)
// the texel first only when it is needed: an RGBA output whose mask keeps channels, or a multiply.
// Defined only in the passes that have the OUTPUT_FORMAT variant.
#if defined(OUTPUT_FORMAT) && SAO_OUTPUT_IS_RGBA(OUTPUT_FORMAT)
#define SAO_STORE_BENT_OUTPUT(p, b, a) \
    imageStore(out_ao, (p), sao_output_bent_texel((b), SAO_BOUNCED(a), SAO_OUTPUT_IS_UNORM8(OUTPUT_FORMAT)))
#define SAO_STORE_OUTPUT(p, a) \
    imageStore(out_ao, (p), sao_output_texel(SAO_BOUNCED(a), SAO_OUTPUT_IS_UNORM8(OUTPUT_FORMAT), \
        output_mask == SAO_OUTPUT_ALL_CHANNELS && output_blend == SAO_OUTPUT_BLEND_REPLACE ? vec4(0.0) \
            : SAO_LOAD_AO(p), output_mask, output_blend))
#elif defined(OUTPUT_FORMAT)
#define SAO_STORE_OUTPUT(p, a) \
    imageStore(out_ao, (p), sao_output_texel_r(SAO_BOUNCED(a), SAO_OUTPUT_IS_UNORM8(OUTPUT_FORMAT), \
        output_blend == SAO_OUTPUT_BLEND_REPLACE ? 0.0 : SAO_LOAD_AO(p).x, output_mask, output_blend))
#endif

#endif // SAO_OUTPUT_GLSL
