// sao_temporal.glsl -- temporal accumulation (issue [temporal]): this frame's obscurance sum of a
// pixel blended with the history of the same surface, found by reprojecting the pixel's
// camera-space point into the previous frame's camera and rejected where the history's z differs.
// The sum (eq. 1 before the visibility curve) is what accumulates, so that N frames of s taps
// average like one frame of N*s taps (averaging A itself would average the curve: Jensen's
// inequality). Library code: depends on sao_depth.glsl and sao_normal.glsl. Math: docs/effect-math.md, "Temporal".
#ifndef SAO_TEMPORAL_GLSL
#define SAO_TEMPORAL_GLSL

// The rigid transform from this frame's camera space into the previous frame's, by rows (.xyz the
// rotation's row, .w the translation, view units): its rotation alone, for a direction (a normal),
// and the whole, for a point.
vec3 sao_rotate_to_previous(vec3 n, vec4 m_x, vec4 m_y, vec4 m_z)
{
    return vec3(dot(m_x.xyz, n), dot(m_y.xyz, n), dot(m_z.xyz, n));
}

vec3 sao_to_previous(vec3 C, vec4 m_x, vec4 m_y, vec4 m_z)
{
    return sao_rotate_to_previous(C, m_x, m_y, m_z) + vec3(m_x.w, m_y.w, m_z.w);
}

// A normal in one float, exactly: its octahedral map (sao_octahedral_decode's inverse) in [0, 1]^2
// quantised to 12 bits a component, stored as the integer qx * 4096 + qy (below 2^24, so a float
// holds it exactly on every backend).
float sao_pack_normal(vec3 n)
{
    float l1 = (abs(n.x) + abs(n.y)) + abs(n.z);
    vec2 e = n.xy / l1;
    if (n.z < 0.0) {
        float sx = e.x >= 0.0 ? 1.0 : -1.0;
        float sy = e.y >= 0.0 ? 1.0 : -1.0;
        e = vec2((1.0 - abs(e.y)) * sx, (1.0 - abs(e.x)) * sy);
    }
    vec2 q = floor((e * 0.5 + 0.5) * 4095.0 + 0.5);
    return q.x * 4096.0 + q.y;
}

vec3 sao_unpack_normal(float code)
{
    float qx = floor(code / 4096.0);
    float qy = code - qx * 4096.0;
    return sao_octahedral_decode(vec2(qx, qy) / 4095.0 * 2.0 - 1.0);
}

// Whether two normals (any length) lie within acos(SAO_TEMPORAL_NORMAL_COS) of each other, without
// a square root: dot > 0 and dot^2 >= cos^2 |a|^2 |b|^2.
bool sao_normals_agree(vec3 a, vec3 b)
{
    float d = dot(a, b);
    return d > 0.0 && d * d >= (SAO_TEMPORAL_NORMAL_COS * SAO_TEMPORAL_NORMAL_COS) * (dot(a, a) * dot(b, b));
}

// Bilinear weight of corner o (0 or 1 per axis) for the fraction f.
float sao_bilinear_weight(ivec2 o, vec2 f)
{
    return ((o.x == 1) ? f.x : 1.0 - f.x) * ((o.y == 1) ? f.y : 1.0 - f.y);
}

// The csz level-0 texel coordinates (centre = index + 0.5) of a point P of the previous frame's
// camera space in that camera (eq. 3 inverted with prev_proj_info; the guard band folded in).
vec2 sao_previous_pixel(vec3 P, vec4 prev_proj_info, int ortho)
{
    float w = (ortho != 0) ? 1.0 : P.z;
    return vec2((P.x / w - prev_proj_info.z) / prev_proj_info.x, (P.y / w - prev_proj_info.w) / prev_proj_info.y);
}

// This frame's pixel, whose surface was at csz texel coordinates `previous` in the previous frame
// with camera-space z_P there (sao_previous_pixel, or the motion input), its normal n_P turned into
// the previous camera, and its obscurance sum `sum`, against the history (the previous frame's image:
// .x accumulated sum, .y its key z (+0.0 = sky), .z frames accumulated, 0 = none, .w its packed
// normal). With test_normals (supplied normals: rebuilt ones are too noisy at edges and on fine
// geometry, and the test would throw good history away), a history texel whose normal disagrees
// with n_P (sao_normals_agree) weighs 0. The
// history texel q stands for viewport pixel q*d + d/2 (sao_low_representative). The 2x2 texels around `previous` weigh bilinearly (the fraction
// snapped to 1/64 texel, so that a camera that holds still reads its own texel alone) times
// max(0, 1 - depth_k * |z_h - z_P| / -z_P): a texel of another surface (a disocclusion) weighs 0.
// With w the sum of the weights, the history is worth w * (their weighted mean of frames) frames,
// n; this frame takes max(min_blend, 1 / (n + 1)) of the result (a running mean that becomes an
// exponential one). Returns (accumulated sum, frames after this one, at most max_frames).
// valid == 0, or z_P >= 0 (behind the previous camera): no history.
vec2 sao_temporal_accumulate(sampler2D history, vec2 previous, float z_P, vec3 n_P, bool test_normals, float sum,
                             ivec2 guard, int d,
                             float depth_k, float min_blend, float max_frames, int valid)
{
    float h = 0.0;
    float n = 0.0;
    if (valid != 0 && z_P < 0.0) {
        vec2 u = (((previous - 0.5) - vec2(guard)) - float(d >> 1)) / float(d);
        ivec2 size = textureSize(history, 0);
        // Far outside the image (or not a number): the int conversion below must not overflow.
        if (all(greaterThan(u, vec2(-2.0))) && all(lessThan(u, vec2(size) + 1.0))) {
            vec2 i0 = floor(u);
            vec2 f = floor((u - i0) * 64.0 + 0.5) / 64.0;
            ivec2 q0 = ivec2(i0);
            float k = depth_k / -z_P;
            float wsum = 0.0;
            float hsum = 0.0;
            float nsum = 0.0;
            for (int j = 0; j < 4; ++j) {
                ivec2 o = ivec2(j & 1, j >> 1);
                ivec2 q = q0 + o;
                float wb = sao_bilinear_weight(o, f);
                if (wb > 0.0 && all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
                    vec4 t = texelFetch(history, q, 0);
                    if (t.z > 0.0 && !sao_is_sky(t.y) &&
                        (!test_normals || sao_normals_agree(sao_unpack_normal(t.w), n_P))) {
                        float wt = wb * max(0.0, 1.0 - k * abs(t.y - z_P));
                        wsum += wt;
                        hsum += wt * t.x;
                        nsum += wt * t.z;
                    }
                }
            }
            if (wsum > 0.0) {
                h = hsum / wsum;
                n = nsum;
            }
        }
    }
    float a = max(min_blend, 1.0 / (n + 1.0));
    return vec2(h + a * (sum - h), min(n + 1.0, max_frames));
}

#endif // SAO_TEMPORAL_GLSL
