// sao_position.glsl -- camera-space position from a pixel and z (SAO paper eq. 3) and the
// projected sample radius (eq. 5).
// Library code: pure functions of their parameters. Math: docs/effect-math.md, "Positions".
#ifndef SAO_POSITION_GLSL
#define SAO_POSITION_GLSL

// Eq. 3. `pixel` is a pixel centre in csz level-0 texel units (integer index + 0.5); the guard
// band offset is folded into proj_info.zw by the host. For a perspective camera
//   x_C = z * (pixel.x * proj_info.x + proj_info.z),  y_C = z * (pixel.y * proj_info.y + proj_info.w)
// and for an orthographic one (ortho != 0) the same without the factor z.
vec3 sao_position(vec2 pixel, float z, vec4 proj_info, int ortho)
{
    float w = (ortho != 0) ? 1.0 : z;
    return vec3(w * (pixel.x * proj_info.x + proj_info.z),
                w * (pixel.y * proj_info.y + proj_info.w),
                z);
}

// Eq. 5: r' = r * S' / (-z_C) pixels (perspective) or r * S' (orthographic), clamped to
// SAO_MAX_RADIUS_PX so that the int conversions of the tap offsets cannot overflow.
float sao_screen_radius(float radius, float proj_scale, float z, int ortho)
{
    float r = radius * proj_scale;
    if (ortho == 0)
        r = r / (-z);
    return min(r, float(SAO_MAX_RADIUS_PX));
}

#endif // SAO_POSITION_GLSL
