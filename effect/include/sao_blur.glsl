// sao_blur.glsl -- the separable depth-aware (bilateral) blur (SAO paper section 2.4) with a
// float z key. Library code: depends on sao_depth.glsl. Math: docs/effect-math.md, "blur_h / blur_v".
#ifndef SAO_BLUR_GLSL
#define SAO_BLUR_GLSL

// Gaussian weight of tap t (in taps, not pixels): 1 at t = 0, host-computed weights for
// |t| = 1..8 (w_1_4 = w(1..4), w_5_8 = w(5..8)).
float sao_blur_gauss(int t, vec4 w_1_4, vec4 w_5_8)
{
    int a = abs(t);
    if (a == 0)
        return 1.0;
    return (a <= 4) ? w_1_4[clamp(a - 1, 0, 3)] : w_5_8[clamp(a - 5, 0, 3)];
}

// Bilateral 1D blur of src (.x = A, .y = key z) at texel p along dir ((1,0) or (0,1)):
// taps t = -R..R (ascending) at p + dir*t*stride, weight gauss(t) * max(0, 1 - sharpness*|dz|).
// Taps off the texture or on sky are skipped; a sky centre gives (1, 0). Returns (A, key).
vec2 sao_bilateral_blur(sampler2D src, ivec2 p, ivec2 dir, int radius_taps, int stride,
                        float sharpness, vec4 w_1_4, vec4 w_5_8)
{
    vec2 centre = texelFetch(src, p, 0).xy;
    if (sao_is_sky(centre.y))
        return vec2(1.0, 0.0);
    ivec2 size = textureSize(src, 0);
    int R = clamp(radius_taps, 0, SAO_MAX_BLUR_RADIUS);
    float sum = 0.0;
    float wsum = 0.0;
    for (int t = -R; t <= R; ++t) {
        vec2 tap = centre;
        if (t != 0) {
            ivec2 q = p + dir * (t * stride);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            tap = texelFetch(src, q, 0).xy;
            if (sao_is_sky(tap.y))
                continue;
        }
        float w = sao_blur_gauss(t, w_1_4, w_5_8) * max(0.0, 1.0 - sharpness * abs(tap.y - centre.y));
        sum += w * tap.x;
        wsum += w;
    }
    return vec2(sum / wsum, centre.y);
}

// x clamped to [0, 1] and rounded to the nearest binary16 value (ties away from zero) with
// operations that are exact on every IEEE GPU (frexp, ldexp, a multiply by a power of two,
// floor): the r16f store that follows then converts without rounding, so the stored bits do
// not depend on the driver's float-to-half rounding (llvmpipe truncates, others round).
float sao_round_to_half(float x)
{
    x = clamp(x, 0.0, 1.0);
    if (x == 0.0)
        return 0.0;
    int e;
    frexp(x, e);                  // x = f * 2^e, f in [0.5, 1)
    int q = max(e - 11, -24);     // log2 of the binary16 spacing at x
    return ldexp(floor(ldexp(x, -q) + 0.5), q);
}

// x rounded to the nearest binary16 value (ties away from zero), of either sign and not clamped:
// sao_round_to_half's exact steps on |x|, for |x| <= 65504.
float sao_round_to_half_signed(float x)
{
    float m = abs(x);
    if (m == 0.0)
        return x;
    int e;
    frexp(m, e);
    int q = max(e - 11, -24);
    float r = ldexp(floor(ldexp(m, -q) + 0.5), q);
    return x < 0.0 ? -r : r;
}

// The (A, key) texel as an rg16f intermediate holds it (HALF_INTERMEDIATES): A rounded to
// binary16, the key (z times key_scale, <= 0) held to binary16's range and rounded; both exact in
// binary16, so the store does not round again. A texel read from such an image passes unchanged.
vec2 sao_half_texel(vec2 a_key)
{
    return vec2(sao_round_to_half(a_key.x), sao_round_to_half_signed(max(a_key.y, -65504.0)));
}

#endif // SAO_BLUR_GLSL
