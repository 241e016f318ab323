// sao_depth.glsl -- hardware depth -> camera-space z (SAO paper eq. 2) and the sky tests.
// Library code: pure functions of their parameters (no block members, no in_*/out_* names).
// Math and host-side constants: docs/effect-math.md, section "csz".
#ifndef SAO_DEPTH_GLSL
#define SAO_DEPTH_GLSL

// True unless x is +-Inf or NaN. A bit test, so that no compiler can fold it away under
// "no NaN / no Inf" assumptions (isnan/isinf may be folded to false).
bool sao_is_finite(float x)
{
    return (floatBitsToUint(x) & 0x7F800000u) != 0x7F800000u;
}

// Camera-space z is geometry only when it is finite, negative and non-zero. As IEEE bits the
// valid values are exactly 0x80000000 (-0.0) < b < 0xFF800000 (-Inf): everything else (+0.0,
// which the csz pass writes as the sky marker, any positive value, -0.0, +-Inf, NaN) is sky.
bool sao_is_sky(float z)
{
    uint b = floatBitsToUint(z);
    return !(b > 0x80000000u && b < 0xFF800000u);
}

// Eq. 2 and its affine (orthographic / linear-z) counterpart, with the sky rules.
//   d          raw texel value of the depth input (.r)
//   clip_info  (c0, c1, c2, unused)
//   depth_mode SAO_DEPTH_MODE_PERSPECTIVE: z = c0 / (d*c1 + c2)
//              SAO_DEPTH_MODE_ORTHOGRAPHIC, SAO_DEPTH_MODE_LINEAR: z = d*c1 + c2
//   far_dir, far_lim: the far/clear test on d: sky when d*far_dir >= far_lim
//              (standard depth: 1, 1 -> d >= 1; reversed: -1, 0 -> d <= 0; off: 0, 1).
// Hardware depth outside [0, 1] is no depth a GPU writes: sky, on either side (-0.0 is 0).
// Returns z < 0 for geometry and +0.0 for sky / no geometry.
float sao_z_from_depth(float d, vec4 clip_info, int depth_mode, float far_dir, float far_lim)
{
    if (!sao_is_finite(d) || d * far_dir >= far_lim)
        return 0.0;
    if (depth_mode != SAO_DEPTH_MODE_LINEAR && (d < 0.0 || d > 1.0))
        return 0.0;
    float z;
    if (depth_mode == SAO_DEPTH_MODE_PERSPECTIVE)
        z = clip_info.x / (d * clip_info.y + clip_info.z);
    else
        z = d * clip_info.y + clip_info.z;
    return sao_is_sky(z) ? 0.0 : z;
}

// The nearer to the camera of two csz values (geometry z < 0 or the sky marker +0.0): the larger
// geometry z; sky only when both are sky.
float sao_nearer_z(float a, float b)
{
    if (sao_is_sky(a))
        return b;
    if (sao_is_sky(b))
        return a;
    return max(a, b);
}

#endif // SAO_DEPTH_GLSL
