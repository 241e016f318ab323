// sao_visibility.glsl -- the visibility estimator (ESTIMATOR 1): cosine-weighted visibility of the
// hemisphere around n with a finite thickness, sampled in slices (the plane through the eye that
// holds V and a screen direction u: marching the screen line c + h u tests every ray of the slice)
// with a 32-bit visibility bitmask per slice (Therrien et al. 2023) over the cosine-weighted measure.
// Library code: depends on sao_depth.glsl, sao_position.glsl, sao_zmip.glsl and sao_spiral.glsl; the
// taps read csz_share (each texel's z and the width passes' shares of thickness) instead of csz where the
// variant THICKNESS_FROM_WIDTH is 1.
// Math: docs/effect-math.md, "The visibility estimator"; the definition it samples is reference (d)'s.
#ifndef SAO_VISIBILITY_GLSL
#define SAO_VISIBILITY_GLSL
#ifndef THICKNESS_FROM_WIDTH  // a pass without the variant: every slab thickness deep
#define THICKNESS_FROM_WIDTH 0
#endif

const float SAO_PI = 3.14159265;
const float SAO_HALF_PI = 1.57079633;

// atan(y, x) in (-pi, pi] from basic arithmetic only, so that every backend and the CPU reference
// compute the same floats (built-in atan differs between implementations, and a tap's angle that
// lands on a bit boundary would flip the bit): t = min/max of |x|, |y| in [0, 1], reduced to
// [0, tan(pi/8)] by atan(t) = pi/4 + atan((t - 1)/(t + 1)), then Cephes' atanf polynomial (error
// below 2e-7 rad), the octant's reflections exact. `precise`: no fused multiply-add. (0, 0) is
// never passed (sao_slab_bits' caller skips the centre's own texel; a slice's n_p with L = 0 is
// not evaluated).
float sao_atan2(float y, float x)
{
    precise float ax = abs(x);
    precise float ay = abs(y);
    precise float t = min(ax, ay) / max(ax, ay);
    bool reduce = t > 0.414213562;
    precise float r = reduce ? (t - 1.0) / (t + 1.0) : t;
    precise float z = r * r;
    precise float p = (((0.0805374449538 * z - 0.138776856032) * z + 0.199777106478) * z - 0.333329491539) * z * r + r;
    precise float a = reduce ? 0.785398163 + p : p;
    precise float b = (ay > ax) ? 1.57079633 - a : a;
    precise float c = (x < 0.0) ? 3.14159265 - b : b;
    return (y < 0.0) ? -c : c;
}

// One slice of a pixel: e (in the slice, perpendicular to V), the hemisphere [lo, hi] = gamma -+ pi/2
// around the projected normal's angle gamma (from V, signed towards e), G(lo), 1/(G(hi) - G(lo)) and
// the slice's weight L*(G(hi) - G(lo)) times its azimuth rate (L = length of the projected normal).
struct SaoSlice {
    vec3 n;      // the pixel's normal (sao_slab's below-the-tangent-plane test)
    vec3 e;
    vec3 a;      // the slice plane's normal
    vec3 shear;  // (a - n (n.a)) / L^2: moves a point into the slice along the surface's tangent plane
    float gamma;
    float cos_gamma;
    float sin_gamma;
    float lo;
    float hi;
    float g_lo;
    float inv_range;
    float weight;
};

// G(x) = s*(cos(gamma) - cos(2x - gamma) + 2x sin(gamma))/4, s = sign(x) (+1 at 0): the integral of
// cos(theta - gamma)*|sin(theta)| from 0 to x, the cosine-weighted measure of the slice's angles;
// c2 = cos(2x - gamma), which the caller has (sao_slice_position).
float sao_slice_g(float x, float c2, float cos_gamma, float sin_gamma)
{
    float s = (x >= 0.0) ? 1.0 : -1.0;
    precise float g = s * (((cos_gamma - c2) + (2.0 * x) * sin_gamma) * 0.25);
    return g;
}

// The pixel's share of its slices' azimuth rates d(psi)/d(phi) = |f1 x f2| / |f|^2 (f = cos(phi) f1 +
// sin(phi) f2, the screen direction's 3D step projected off V; sao_slice_setup divides by |f|^2):
// uniform screen angles are not uniform azimuths off the image centre or with non-square pixels, and
// weighting each slice by its rate makes the slices sample the hemisphere as reference (d) integrates
// it (the rate's mean over a half turn of phi is 1). |f1 x f2| depends on the pixel alone: once a pixel.
float sao_azimuth_rate_scale(vec3 V, vec4 proj_info)
{
    precise vec3 f1 = vec3(proj_info.x, 0.0, 0.0) - V * (V.x * proj_info.x);
    precise vec3 f2 = vec3(0.0, proj_info.y, 0.0) - V * (V.y * proj_info.y);
    precise float scale = length(cross(f1, f2));
    return scale;
}

// The slice through the eye holding V and screen direction u (csz pixels), for the normal n;
// azimuth_rate_scale = sao_azimuth_rate_scale(V, proj_info).
// gamma is clamped to [-pi/2, pi/2]: a normal facing away from the eye (n.V < 0: silhouettes, noisy
// or supplied normals) keeps the hemisphere inside (-pi, pi], where the taps' angles lie.
SaoSlice sao_slice_setup(vec2 u, vec3 V, vec3 n, vec4 proj_info, float azimuth_rate_scale)
{
    SaoSlice sl;
    precise vec3 D = vec3(u.x * proj_info.x, u.y * proj_info.y, 0.0);
    precise vec3 f = D - V * dot(D, V);
    precise vec3 e = normalize(f);
    precise vec3 a = normalize(cross(e, V));
    precise float na = dot(n, a);
    precise vec3 np = n - a * na;
    precise float L = length(np);
    sl.n = n;
    sl.e = e;
    sl.a = a;
    precise vec3 shear = (a - n * na) * (1.0 / (L * L));
    sl.shear = (L > 0.0) ? shear : vec3(0.0);
    // gamma, cos(gamma) = n_p.V / L and sin(gamma) = n_p.e / L; clamped: cos 0, sin +-1.
    precise float npe = dot(np, sl.e);
    precise float npv = dot(np, V);
    bool facing = npv > 0.0;
    sl.gamma = (L > 0.0) ? clamp(sao_atan2(npe, npv), -SAO_HALF_PI, SAO_HALF_PI) : 0.0;
    sl.cos_gamma = (L > 0.0) ? (facing ? npv / L : 0.0) : 1.0;
    sl.sin_gamma = (L > 0.0) ? (facing ? npe / L : (npe >= 0.0 ? 1.0 : -1.0)) : 0.0;
    sl.lo = sl.gamma - SAO_HALF_PI;
    sl.hi = sl.gamma + SAO_HALF_PI;
    // cos(2 lo - gamma) = cos(gamma - pi) = -cos(gamma), and the same at hi.
    sl.g_lo = sao_slice_g(sl.lo, -sl.cos_gamma, sl.cos_gamma, sl.sin_gamma);
    precise float range = sao_slice_g(sl.hi, -sl.cos_gamma, sl.cos_gamma, sl.sin_gamma) - sl.g_lo;
    sl.inv_range = 1.0 / range;
    precise float rate = azimuth_rate_scale / dot(f, f);
    sl.weight = L * range * rate;
    return sl;
}

// G of the angle theta (from V) of the in-slice vector (pe, pv) = (x.e, x.V), theta clamped to the
// hemisphere. cos(2 theta - gamma) comes from the vector itself, (pv^2 - pe^2) cos(gamma) +
// 2 pv pe sin(gamma) over its squared length (no cos per tap); at a clamped end it is -cos(gamma).
float sao_slice_position(SaoSlice sl, float theta, float pe, float pv)
{
    precise float c2 = ((pv * pv - pe * pe) * sl.cos_gamma + (2.0 * pv * pe) * sl.sin_gamma) / (pe * pe + pv * pv);
    bool inside = theta > sl.lo && theta < sl.hi;
    return sao_slice_g(clamp(theta, sl.lo, sl.hi), inside ? c2 : -sl.cos_gamma, sl.cos_gamma, sl.sin_gamma);
}

// Bits [0, b) of a 32-bit mask, b in [0, 32] (a shift by 32 is undefined).
uint sao_bits_below(int b)
{
    return (b >= 32) ? 0xFFFFFFFFu : ((1u << uint(b)) - 1u);
}

// The bits of slice positions [u1, u2] (u in [0, 1], uniform in the cosine-weighted measure): bit
// range [floor(32 u1 + 0.5), floor(32 u2 + 0.5)), clamped to [0, 32] before the conversion (a NaN,
// from a degenerate slice, gives 0).
uint sao_bits_between(float u1, float u2)
{
    precise float x1 = 32.0 * u1 + 0.5;
    precise float x2 = 32.0 * u2 + 0.5;
    int b1 = int(floor(x1 > 0.0 ? min(x1, 32.0) : 0.0));
    int b2 = int(floor(x2 > 0.0 ? min(x2, 32.0) : 0.0));
    return sao_bits_below(b2) & ~sao_bits_below(b1);
}

// A stored sample's slab seen from C: its angles in the slice as slice positions [u1, u2] (clamped
// to the hemisphere) and its front point's in-slice vector (fe, fv) = (f.e, f.V). valid = false
// (blocks nothing) for sky, a front point farther than r from C, and a slab that would subtend more
// than pi (only a sample on the pixel's own view ray, behind C).
struct SaoSlab {
    bool valid;
    float u1;
    float u2;
    float fe;
    float fv;
    float t;  // its thickness (sao_joined_bits bridges up to the smaller of two)
};

// A slab that blocks nothing (and starts no join).
SaoSlab sao_no_slab(float thickness)
{
    return SaoSlab(false, 0.0, 0.0, 0.0, 0.0, thickness);
}

// The slab along a stored sample's view ray from depth d(1 + tol) to d(1 + tol) + T (S at pixel
// centre q_pixel, z: perspective S scaled by (1 + tol) and (1 + tol) + T/d; ortho S's z moved). The
// caller never passes the centre's own texel (f = 0 would leave the angle undefined).
SaoSlab sao_slab(SaoSlice sl, vec3 C, vec3 V, vec2 q_pixel, float z, vec4 proj_info, int ortho, float radius2,
                 float tolerance, float thickness)
{
    SaoSlab s = sao_no_slab(thickness);
    if (sao_is_sky(z))
        return s;
    // `precise` from here to the bits: no fused multiply-add, so that the backends and the CPU round
    // alike (an angle on a bit boundary would flip the bit).
    precise vec3 S = sao_position(q_pixel, z, proj_info, ortho);
    precise float k = 1.0 + tolerance;
    precise vec3 F;
    precise vec3 B;
    if (ortho != 0) {
        F = vec3(S.xy, z * k);
        B = vec3(S.xy, z * k - thickness);
    } else {
        F = S * k;
        B = S * (k + thickness / -z);
    }
    precise vec3 f = F - C;
    if (dot(f, f) > radius2)
        return s;
    precise vec3 b = B - C;
    // A slab wholly on or below the tangent plane blocks nothing (most taps on open ground): its
    // angles would clamp to the hemisphere's end on its side of V (theta > hi where f.e > 0, else
    // theta < lo), u1 = u2 = 1 or 0, so the two atans are skipped. It stays valid (with its front
    // point) for joining: a continuous surface rising from it covers the angles from that horizon
    // up. Its two ends on opposite sides of V subtend more than pi, invalid as below.
    bool below = dot(f, sl.n) <= 0.0 && dot(b, sl.n) <= 0.0;
    // Into the slice plane along the tangent plane (a truncated tap lies up to a pixel beside the
    // slice; dropping its a component would lift a point of the surface's own plane above it).
    f -= sl.shear * dot(f, sl.a);
    b -= sl.shear * dot(b, sl.a);
    precise float fe = dot(f, sl.e);
    precise float fv = dot(f, V);
    precise float be = dot(b, sl.e);
    if (below) {
        bool beyond_hi = fe > 0.0;
        s.valid = beyond_hi == (be > 0.0);
        s.u1 = beyond_hi ? 1.0 : 0.0;
        s.u2 = s.u1;
        s.fe = fe;
        s.fv = fv;
        return s;
    }
    precise float bv = dot(b, V);
    float tf = sao_atan2(fe, fv);
    float tb = sao_atan2(be, bv);
    if (abs(tf - tb) > SAO_PI)
        return s;
    // G is increasing on the hemisphere: the smaller G is the smaller angle's.
    precise float gf = sao_slice_position(sl, tf, fe, fv);
    precise float gb = sao_slice_position(sl, tb, be, bv);
    s.valid = true;
    s.u1 = (min(gf, gb) - sl.g_lo) * sl.inv_range;
    s.u2 = (max(gf, gb) - sl.g_lo) * sl.inv_range;
    s.fe = fe;
    s.fv = fv;
    return s;
}

// The bits a stored sample's slab blocks on its own (the second layer's samples).
uint sao_slab_bits(SaoSlice sl, vec3 C, vec3 V, vec2 q_pixel, float z, vec4 proj_info, int ortho, float radius2,
                   float tolerance, float thickness)
{
    SaoSlab s = sao_slab(sl, C, V, q_pixel, z, proj_info, ortho, radius2, tolerance, thickness);
    return s.valid ? sao_bits_between(s.u1, s.u2) : 0u;
}

// The largest depth slope (along V, per unit across it in the slice) of a surface between two
// consecutive taps of a slice side that the estimator still takes as continuous (docs/effect-math.md
// 5.9, "Joining taps"): two taps are joined when |dv| <= T + SAO_JOIN_SLOPE*|de|.
const float SAO_JOIN_SLOPE = 4.0;

// The first layer's bits of a tap: its slab's interval, or, when the previous tap of the same side
// is on a continuous surface with it, the interval from the previous slab's angles to this one's
// (the surface between them taken as linear: the quad of the two slabs subtends the hull of their
// angles).
uint sao_joined_bits(SaoSlab s, SaoSlab prev)
{
    precise float dv = abs(s.fv - prev.fv);
    precise float de = abs(s.fe - prev.fe);
    bool same_side = (s.fe > 0.0) == (prev.fe > 0.0);  // a truncated tap may cross C's view line
    bool joined = prev.valid && same_side && dv <= min(s.t, prev.t) + SAO_JOIN_SLOPE * de;
    float u1 = joined ? min(s.u1, prev.u1) : s.u1;
    float u2 = joined ? max(s.u2, prev.u2) : s.u2;
    return s.valid ? sao_bits_between(u1, u2) : 0u;
}

// The csz level-0 texel whose z level-m texel t holds: the rotated grid (Table 1) walked down, in
// closed form. A tap's point is placed there, on the surface its z belongs to (SAO places it at the
// tap pixel, up to 2^m pixels from where that z was seen: beside a receding floor, above it). Each
// step of the walk appends one bit to x, alternately not(y0) and x0, and one to y, alternately
// not(x0) and y0 (x0, y0: t's low bits; the parities alternate), so m steps append the m-bit words
// `first` (bits m-1, m-3, ...) and `second` (the others). Exact where both sides of the image are
// at least 2^m texels; on a side under that (images under 2^max_mip <= 128 texels) the walk's clamp
// is not followed and the result is clamped to the image instead: a point up to 2^m texels from
// its z's, as SAO's own taps. No loop: llvmpipe would run a walk's body masked on every tap.
ivec2 sao_mip_source(ivec2 t, int m, ivec2 size0)
{
    uint first = (m == 0) ? 0u : (0xAAAAAAAAu >> uint(32 - m));
    uint second = ((1u << uint(m)) - 1u) ^ first;
    uint x0 = uint(t.x) & 1u;
    uint y0 = uint(t.y) & 1u;
    uint sx = (uint(t.x) << uint(m)) | ((y0 ^ 1u) * first) | (x0 * second);
    uint sy = (uint(t.y) << uint(m)) | ((x0 ^ 1u) * first) | (y0 * second);
    return min(ivec2(sx, sy), size0 - 1);
}

// thickness_model 1 (docs/effect-math.md 5.9, "Thickness from width"), the width pass's half: the
// share of thickness of a texel (z) whose run of continuous depth along x (x_axis) or y ends at
// level-0 texels e0 and e1 (z0, z1): SAO_WIDTH_SCALE times its width (the distance between the end
// texels' points plus one texel's footprint along the axis, `span` level-0 texels: 2^m for a
// texel of level m), clamped to [thickness_min, thickness], over thickness (> 0); 1 for a wide run
// (one that went on through SAO_WIDTH_REACH texels on either side or reached the image's edge; the
// width pass finds the ends, sao.glsl).
float sao_run_share_of(ivec2 e0, float z0, ivec2 e1, float z1, bool wide, float z, bool x_axis, vec4 proj_info,
                       int ortho, float thickness, float thickness_min, float span)
{
    precise vec3 a = sao_position(vec2(e0) + 0.5, z0, proj_info, ortho);
    precise vec3 b = sao_position(vec2(e1) + 0.5, z1, proj_info, ortho);
    float scale = x_axis ? abs(proj_info.x) : abs(proj_info.y);
    precise float footprint = scale * ((ortho != 0) ? 1.0 : abs(z)) * span;
    precise float width = length(a - b) + footprint;
    precise float t = min(thickness, max(thickness_min, SAO_WIDTH_SCALE * width));
    return wide ? 1.0 : t / thickness;
}

// A texel's shares along x and y (binary16 values, as the width pass rounds them) as one float of
// csz_share: packHalf2x16's bits, x in the low half. Each share is at least SAO_WIDTH_MIN_M over
// thickness's largest value (2e-4, a normal binary16) and at most 1, so y's bits 7..14, the float's
// exponent, lie in 8 .. 120: a normal positive float, which storage and texelFetch keep bit for bit
// (a denormal could be flushed, a NaN canonicalised).
float sao_pack_shares(vec2 share) { return uintBitsToFloat(packHalf2x16(share)); }
vec2 sao_unpack_shares(float code) { return unpackHalf2x16(floatBitsToUint(code)); }

// thickness_model 1, the tap's half: the thickness of the surface a tap sees along its slice's
// screen direction dir (unit), from the width pass's shares of thickness along x and y (its texel
// of csz_share at the tap's level, beside its z). A slice crossing an axis'
// run at an angle crosses 1/|cos| as much of it: thickness times the smaller of share.x/|dir.x|
// and share.y/|dir.y|, at most thickness (the max() keeps an axis the slice runs along out of it).
float sao_tap_thickness(vec2 share, vec2 dir, float thickness)
{
    precise float fx = share.x / max(abs(dir.x), 1.0e-6);
    precise float fy = share.y / max(abs(dir.y), 1.0e-6);
    precise float t = thickness * min(1.0, min(fx, fy));
    return t;
}

// The pixel's radial jitter: a hash of the AO pixel, 24 bits, in [0, 1) (exact as a float, so
// every backend has the same value). Decorrelated from eq. 8's rotation hash.
float sao_pixel_jitter(uvec2 p)
{
    uint h = (p.x * 0x8DA6B343u) ^ (p.y * 0xD8163841u);
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    return float(h >> 8) * 5.96046448e-08;  // 2^-24
}

// The occlusion 1 - V of the pixel at csz level-0 texel c (position C, normal n, projected radius
// r_px): `slices` slices at angles phase + k*slice_turn (2^-32 turns; slice_turn = half a turn over
// slices), m = max(1, tap_count/(2*slices)) steps on each side at h_j = r_px*((j + xi)/m)^2, each
// tap read from the z MIP level for its distance (hierarchy), with THICKNESS_FROM_WIDTH its
// z and thickness from csz_share's texel instead, and with two_layer the second layer's slab
// too (thickness deep). V = sum_k w_k (1 - bits_k/32) / sum_k w_k; 0 when every weight is 0. Nested
// loops, so that a slice's setup runs once per slice (llvmpipe runs a branch's body masked on every
// trip: in one flat loop it ran per tap); the trip counts come from tap_count and slices alone (the
// caller passes SAO_TAP_COUNT and SAO_SLICE_COUNT: on Vulkan push constants, see sao.glsl). With
// `bent` (a constant: BENT_NORMALS) `moment` sums the slices' first moments of their unoccluded
// rays (sao_bent.glsl, included after this file: declared here); otherwise it is left 0.
vec3 sao_slice_bent_moment(SaoSlice sl, vec3 V, uint bits);
float sao_visibility_occlusion(sampler2D csz, sampler2D csz2, sampler2D csz_share, bool two_layer, bool hierarchy,
                               ivec2 c, vec3 C, vec3 n, float r_px, uint phase, float xi, int tap_count, int slices,
                               uint slice_turn, vec4 proj_info, int ortho, float radius2, float tolerance,
                               float thickness, int log_q, int max_mip, bool bent, out vec3 moment)
{
    moment = vec3(0.0);
    ivec2 size0 = textureSize(csz, 0);
    precise vec3 V = (ortho != 0) ? vec3(0.0, 0.0, 1.0) : normalize(-C);
    int ns = clamp(slices, 1, SAO_MAX_SLICES);
    int m = max(1, tap_count / (2 * ns));
    float inv_m = 1.0 / float(m);
    precise float occluded = 0.0;
    precise float weights = 0.0;
    float azimuth_rate_scale = sao_azimuth_rate_scale(V, proj_info);
    for (int k = 0; k < ns; ++k) {
        vec2 u = sao_turn_direction(phase + uint(k) * slice_turn);
        SaoSlice sl = sao_slice_setup(u, V, n, proj_info, azimuth_rate_scale);
        uint bits = 0u;
        for (int side = 0; side < 2; ++side) {
            vec2 dir = (side == 0) ? u : -u;
            SaoSlab prev = sao_no_slab(thickness);  // the side's previous tap's slab, for sao_joined_bits
            for (int j = 0; j < m; ++j) {
                float t = (float(j) + xi) * inv_m;
                float h = r_px * (t * t);
                ivec2 tap = c + ivec2(h * dir);  // conversion truncates toward zero
                if (tap != c) {
                    int lvl = hierarchy ? sao_mip_level(h, log_q, max_mip) : 0;
                    ivec2 tt = sao_mip_texel(tap, lvl, size0);
                    ivec2 src = sao_mip_source(tt, lvl, size0);
                    if (src != c) {  // a coarse texel may hold the centre's own z
                        vec2 q = vec2(src) + 0.5;
#if THICKNESS_FROM_WIDTH
                        vec2 zs = texelFetch(csz_share, tt, lvl).rg;
                        float z = zs.x;
                        float t = sao_tap_thickness(sao_unpack_shares(zs.y), dir, thickness);
#else
                        float z = texelFetch(csz, tt, lvl).r;
                        float t = thickness;
#endif
                        SaoSlab s = sao_slab(sl, C, V, q, z, proj_info, ortho, radius2, tolerance, t);
                        bits |= sao_joined_bits(s, prev);
                        prev = s;  // sky or a sample beyond r breaks the chain
                        if (two_layer)
                            bits |= sao_slab_bits(sl, C, V, q, texelFetch(csz2, tt, lvl).r, proj_info, ortho,
                                                  radius2, tolerance, thickness);
                    }
                }
            }
        }
        occluded += sl.weight * (float(bitCount(bits)) * 0.03125);
        weights += sl.weight;
        if (bent)
            moment += sao_slice_bent_moment(sl, V, bits);
    }
    return (weights > 0.0) ? occluded / weights : 0.0;
}

#endif // SAO_VISIBILITY_GLSL
