// sao_bent.glsl -- the visibility estimator's bent normal: the cosine-weighted mean direction of the
// unoccluded rays, from the slices and bitmasks of sao_visibility.glsl. In a slice the rays are
// w(theta) = sin(theta) e + cos(theta) V under the measure L cos(theta - gamma) |sin(theta)|, whose
// integral G the 32 bits split evenly; a visible run of bits is an arc whose ends' angles come from
// G inverted by bisection, and whose first moment has a closed form. Library code: depends on
// sao_visibility.glsl, whose sao_visibility_occlusion declares sao_slice_bent_moment ahead and sums
// it over the slices under BENT_NORMALS. Math: docs/effect-math.md 5.10; CPU: effect/cpu/sao_bent.h.
#ifndef SAO_BENT_GLSL
#define SAO_BENT_GLSL

// G(theta) with cos(2 theta - gamma) from theta.
float sao_slice_g_at(SaoSlice sl, float theta)
{
    return sao_slice_g(theta, cos(2.0 * theta - sl.gamma), sl.cos_gamma, sl.sin_gamma);
}

// The angle in [lo, hi] at slice position u: SAO_BENT_BISECTIONS halvings (G rises on [lo, hi]).
float sao_slice_angle(SaoSlice sl, float u)
{
    if (!(u > 0.0))
        return sl.lo;
    if (u >= 1.0)
        return sl.hi;
    float g = sl.g_lo + u / sl.inv_range;
    float a = sl.lo;
    float b = sl.hi;
    for (int i = 0; i < SAO_BENT_BISECTIONS; ++i) {
        float mid = (a + b) * 0.5;
        bool below = sao_slice_g_at(sl, mid) < g;
        a = below ? mid : a;
        b = below ? b : mid;
    }
    return (a + b) * 0.5;
}

// H(theta): the first moment from 0 to theta of w cos(theta - gamma) |sin(theta)| as (e, V)
// components, sign(theta) (F(theta) - F(0)) with F the antiderivatives for theta >= 0.
vec2 sao_arc_moment_from_zero(SaoSlice sl, float theta)
{
    float s = sin(theta);
    float c = cos(theta);
    float s3 = s * s * s;
    float c3 = c * c * c;
    float sgn = (theta >= 0.0) ? 1.0 : -1.0;
    float e = sgn * (sl.cos_gamma * s3 / 3.0 + sl.sin_gamma * (c3 / 3.0 - c + 2.0 / 3.0));
    float v = sgn * (sl.cos_gamma * (1.0 - c3) / 3.0 + sl.sin_gamma * s3 / 3.0);
    return vec2(e, v);
}

// The first moment of a slice's unoccluded rays (bits not set), camera space, times its L and azimuth
// rate (weight over range: slices add as the estimator's weights do).
vec3 sao_slice_bent_moment(SaoSlice sl, vec3 V, uint bits)
{
    vec2 m = vec2(0.0);
    uint visible = ~bits;
    for (int run = 0; run < 16 && visible != 0u; ++run) {  // at most 16 runs in 32 bits
        int b0 = findLSB(visible);
        uint above = ~visible & ~sao_bits_below(b0);
        int b1 = (above != 0u) ? findLSB(above) : 32;
        m += sao_arc_moment_from_zero(sl, sao_slice_angle(sl, float(b1) * 0.03125)) -
             sao_arc_moment_from_zero(sl, sao_slice_angle(sl, float(b0) * 0.03125));
        visible &= ~sao_bits_below(b1);
    }
    float w = sl.weight * sl.inv_range;
    return (sl.e * m.x + V * m.y) * w;
}

// The bent normal from the slices' summed moments, or n where nothing is visible.
vec3 sao_bent_normal(vec3 moments, vec3 n)
{
    float l2 = dot(moments, moments);
    return (l2 > 0.0) ? moments * inversesqrt(l2) : n;
}

#endif // SAO_BENT_GLSL
