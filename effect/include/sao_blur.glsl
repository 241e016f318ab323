// sao_blur.glsl -- the separable depth-aware (bilateral) blur (SAO paper section 2.4) with a
// float z key. Library code: depends on sao_depth.glsl. Math: docs/effect-math.md, "6. Pass blur".
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

// The depth weight's slope at a centre key: sharpness (per key unit) plus relative / |centre key|, the
// part that scales with distance (a scene in millimetres has edges where the same scene in metres
// does). The guard keeps 0 / 0 out for a sky centre (key 0), whose result is (1, 0) anyway; with
// relative = 0 the sum is sharpness exactly.
float sao_blur_sharpness(float centre_key, float sharpness, float relative)
{
    return sharpness + relative / max(abs(centre_key), 1.0e-20);
}

// The centre's slope along the blur direction, key units per tap, from its neighbours' keys km and
// kp a stride before and after it: the flatter of the two one-sided differences (minmod), 0 at a
// ridge or a valley (they differ in sign) and where either neighbour is sky (or off the image).
float sao_blur_slope(float km, float k0, float kp)
{
    float gm = k0 - km, gp = kp - k0;
    bool none = sao_is_sky(km) || sao_is_sky(kp) || ((gp > 0.0) != (gm > 0.0));
    return none ? 0.0 : (abs(gp) < abs(gm) ? gp : gm);
}

// A tap's weight: gauss(t) * max(0, 1 - sharpness * |key - centre key|) (blur's one formula), with
// sharpness from sao_blur_sharpness.
float sao_blur_weight(int t, float key, float centre_key, float sharpness, vec4 w_1_4, vec4 w_5_8)
{
    return sao_blur_gauss(t, w_1_4, w_5_8) * max(0.0, 1.0 - sharpness * abs(key - centre_key));
}

// Bilateral 1D blur of src (.x = A, .y = key z) at texel p along dir ((1,0) or (0,1)):
// taps t = -R..R (ascending) at p + dir*t*stride, weight gauss(t) * max(0, 1 - k*|dz|), k =
// sao_blur_sharpness(centre key, sharpness, relative); with `slope` |dz| is measured from the
// centre's plane, k0 + t * sao_blur_slope (its neighbours a stride away, off the texture: none).
// Taps off the texture or on sky weigh 0; a sky centre gives (1, 0). Returns (A, key).
// Branch-free and a do-while loop (t = 0 always runs): a software rasteriser (llvmpipe) runs every
// branch for every pixel and a for loop's body once more than its largest trip count; a tap
// weighing 0 adds +0.0, so the sums are those of skipping it.
vec2 sao_bilateral_blur(sampler2D src, ivec2 p, ivec2 dir, int radius_taps, int stride,
                        float sharpness, float relative, bool slope, vec4 w_1_4, vec4 w_5_8)
{
    vec2 centre = texelFetch(src, p, 0).xy;
    ivec2 size = textureSize(src, 0);
    float k = sao_blur_sharpness(centre.y, sharpness, relative);
    ivec2 pm = p - dir * stride, pp = p + dir * stride;
    bool both = all(greaterThanEqual(pm, ivec2(0))) && all(lessThan(pp, size));
    float g = (slope && both) ? sao_blur_slope(texelFetch(src, pm, 0).y, centre.y, texelFetch(src, pp, 0).y) : 0.0;
    int R = clamp(radius_taps, 0, SAO_MAX_BLUR_RADIUS);
    float sum = 0.0;
    float wsum = 0.0;
    int t = -R;
    do {
        ivec2 q = p + dir * (t * stride);
        bool inside = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
        vec2 tap = texelFetch(src, clamp(q, ivec2(0), size - 1), 0).xy;
        float w = (inside && !sao_is_sky(tap.y)) ? sao_blur_weight(t, tap.y, centre.y + float(t) * g, k, w_1_4, w_5_8)
                                                   : 0.0;
        sum += w * tap.x;
        wsum += w;
    } while (++t <= R);
    return sao_is_sky(centre.y) ? vec2(1.0, 0.0) : vec2(sum / wsum, centre.y);
}

// |x| rounded to the nearest binary16 value, ties away from zero, for |x| <= 65504, with integer
// and power-of-two operations that are exact on every IEEE GPU: the r16f store that follows then
// converts without rounding, so the stored bits do not depend on the driver's float-to-half
// rounding (llvmpipe truncates, others round). Normal binary16 values keep 10 of binary32's 23
// mantissa bits: adding half of the 13 dropped bits' weight and clearing them rounds half up (a
// carry moves into the exponent); below 2^-14 the spacing is 2^-24, and t - floor(t) is exact, so
// the tie test is (floor(t + 0.5) would round up the float just below 2^-25). The same values as
// the CPU reference's frexp steps (roundHalfMagnitude; docs/effect-math.md 6.3), at a fraction of
// their cost on a CPU rasterizer.
float sao_round_half_magnitude(float m)
{
    if (m < 0.00006103515625) {  // 2^-14: binary16's subnormals
        float t = m * 16777216.0;  // exact: a power of two
        float f = floor(t);
        return (t - f >= 0.5 ? f + 1.0 : f) * 5.9604644775390625e-8;
    }
    return uintBitsToFloat((floatBitsToUint(m) + 0x1000u) & 0xFFFFE000u);
}

// x clamped to [0, 1] and rounded to the nearest binary16 value (ties away from zero).
float sao_round_to_half(float x)
{
    return sao_round_half_magnitude(clamp(x, 0.0, 1.0));
}

// x rounded to the nearest binary16 value (ties away from zero), of either sign and not clamped,
// for |x| <= 65504.
float sao_round_to_half_signed(float x)
{
    float r = sao_round_half_magnitude(abs(x));
    return x < 0.0 ? -r : (x == 0.0 ? x : r);
}

// The (A, key) texel as an rg16f intermediate holds it (HALF_INTERMEDIATES): A rounded to
// binary16, the key (z in metres, <= 0) held to binary16's range and rounded; both exact in
// binary16, so the store does not round again. A texel read from such an image passes unchanged.
vec2 sao_half_texel(vec2 a_key)
{
    return vec2(sao_round_to_half(a_key.x), sao_round_to_half_signed(max(a_key.y, -65504.0)));
}

#endif // SAO_BLUR_GLSL
