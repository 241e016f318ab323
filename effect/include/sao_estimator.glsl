// sao_estimator.glsl -- the AlchemyAO estimator (SAO paper eq. 1 = AlchemyAO eq. 10, with the
// radius cut H(r - |v|) of AlchemyAO eq. 9) and the 2x2 bilateral reconstruction step.
// Library code: depends on sao_depth.glsl and sao_position.glsl. Math: docs/effect-math.md, "ao_sample".
#ifndef SAO_ESTIMATOR_GLSL
#define SAO_ESTIMATOR_GLSL

// One term of the eq. 1 sum for a tap read at full-resolution pixel centre q_pixel with depth zq:
//   v = Q - C; 0 if Q is sky or v.v > r^2; else max(0, v.n + z_C*bias) / (v.v + epsilon).
float sao_tap_obscurance(vec3 C, vec3 n, vec2 q_pixel, float zq, vec4 proj_info, int ortho,
                         float radius2, float bias, float epsilon)
{
    if (sao_is_sky(zq))
        return 0.0;
    vec3 v = sao_position(q_pixel, zq, proj_info, ortho) - C;
    float vv = dot(v, v);
    if (vv > radius2)
        return 0.0;
    float vn = dot(v, n);
    return max(0.0, vn + C.z * bias) / (vv + epsilon);
}

// Eq. 1 from the sum of the terms: A = max(0, 1 - (2*sigma*r/s) * sum)^k, with sigma unitless and r
// the radius in view units (intensity_div_s). pow is skipped for k == 1 (GPU pow(x, 1) is not
// always exactly x).
float sao_visibility(float sum, float intensity_div_s, float contrast)
{
    float a = max(0.0, 1.0 - intensity_div_s * sum);
    return (contrast == 1.0) ? a : pow(a, contrast);
}

// The distance fade: A unchanged up to -z = fade_start, 1 from -z >= fade_end on (an explicit test,
// so that rounding of t can never leave it a hair below 1), linear in between: A + (1 - A)*t with
// t = (-z - fade_start)/(fade_end - fade_start). fade_end = 0 turns it off. At t = 0 the result is
// A exactly (with or without a fused multiply-add).
float sao_fade(float a, float z, float fade_start, float fade_end, float fade_inv_range)
{
    float d = -z;
    if (fade_end <= 0.0 || d <= fade_start)
        return a;
    if (d >= fade_end)
        return 1.0;
    float t = (d - fade_start) * fade_inv_range;
    return a + (1.0 - a) * t;
}

// One step of the 2x2 reconstruction: average with the quad neighbour when both are geometry
// and their z differ by less than threshold; sky never mixes.
float sao_quad_mix(float a, float z, float a_n, float z_n, float threshold)
{
    bool ok = !sao_is_sky(z) && !sao_is_sky(z_n) && abs(z - z_n) < threshold;
    return ok ? 0.5 * (a + a_n) : a;
}

#endif // SAO_ESTIMATOR_GLSL
