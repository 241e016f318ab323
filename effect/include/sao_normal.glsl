// sao_normal.glsl -- camera-space normals: decoded from the user's normals texture (camera or world
// space, xyz or octahedral; normals_encoding), or the face
// normal of eq. 4 rebuilt from csz level 0 with explicit neighbour fetches (compute shaders have
// no dFdx/dFdy, and their coarse/fine choice differs between drivers anyway).
// Library code: depends on sao_depth.glsl and sao_position.glsl. Math: docs/effect-math.md, "Normals".
#ifndef SAO_NORMAL_GLSL
#define SAO_NORMAL_GLSL

// A user normal (camera space, components in [-1,1]) made unit length. A zero, infinite or NaN
// normal becomes vec3(0): such a pixel then receives no obscurance (every tap term is
// max(0, 0 + z_C*bias) = 0).
vec3 sao_decode_normal(vec3 n)
{
    float l2 = dot(n, n);
    return (sao_is_finite(l2) && l2 > 0.0) ? n * inversesqrt(l2) : vec3(0.0);
}

// The signed octahedral map back to a direction (not unit length: sao_decode_normal normalises).
// e in [-1,1]^2: the upper hemisphere (z >= 0) is the diamond |e.x| + |e.y| <= 1, the lower one
// is folded out into the four corners, mirrored across the diamond's edges.
vec3 sao_octahedral_decode(vec2 e)
{
    vec3 n = vec3(e.x, e.y, (1.0 - abs(e.x)) - abs(e.y));
    if (n.z < 0.0) {
        float sx = e.x >= 0.0 ? 1.0 : -1.0;
        float sy = e.y >= 0.0 ? 1.0 : -1.0;
        n.x = (1.0 - abs(e.y)) * sx;
        n.y = (1.0 - abs(e.x)) * sy;
    }
    return n;
}

// A texel of the normals input as a unit camera-space normal, per normals_encoding: .xyz or the
// octahedral .xy, in camera space or in world space (then rotated into camera space by R, whose
// columns are view_x/y/z; R n = (col0*n.x + col1*n.y) + col2*n.z, in that order).
vec3 sao_supplied_normal(vec4 t, int encoding, vec4 view_x, vec4 view_y, vec4 view_z)
{
    bool octahedral = encoding == SAO_NORMALS_CAMERA_OCTAHEDRAL || encoding == SAO_NORMALS_WORLD_OCTAHEDRAL;
    vec3 v = octahedral ? sao_octahedral_decode(t.xy) : t.xyz;
    if (encoding == SAO_NORMALS_WORLD_XYZ || encoding == SAO_NORMALS_WORLD_OCTAHEDRAL)
        v = (view_x.xyz * v.x + view_y.xyz * v.y) + view_z.xyz * v.z;
    return sao_decode_normal(v);
}

// One axis of eq. 4: the camera-space step to the neighbour on the side with the smaller |dz|.
//   C        the centre point, pc its pixel centre, step (1,0) or (0,1)
//   zm, zp   z of the neighbours at pc - step and pc + step (sky / off the image: any sky value)
// Forward difference when the + side is valid and strictly closer in z (or the - side is not
// valid), else backward difference; with no valid side, the constant-z (camera-facing) step.
vec3 sao_axis_tangent(vec3 C, vec2 pc, vec2 step, float zm, float zp, vec4 proj_info, int ortho)
{
    bool okm = !sao_is_sky(zm);
    bool okp = !sao_is_sky(zp);
    if (okp && (!okm || abs(zp - C.z) < abs(C.z - zm)))
        return sao_position(pc + step, zp, proj_info, ortho) - C;
    if (okm)
        return C - sao_position(pc - step, zm, proj_info, ortho);
    return sao_position(pc + step, C.z, proj_info, ortho) - C;
}

// Eq. 4 face normal at csz level-0 texel c (C = its position). Neighbours outside the texture
// count as sky. The cross product is oriented towards the viewer: the pixel-to-camera map has
// the handedness of sign(proj_info.x * proj_info.y) (a y-flipped target flips it).
// A degenerate result becomes vec3(0, 0, 1).
vec3 sao_reconstruct_normal(sampler2D z_tex, ivec2 c, vec3 C, vec4 proj_info, int ortho)
{
    ivec2 last = textureSize(z_tex, 0) - 1;
    float zl = texelFetch(z_tex, ivec2(max(c.x - 1, 0), c.y), 0).r;
    float zr = texelFetch(z_tex, ivec2(min(c.x + 1, last.x), c.y), 0).r;
    float zd = texelFetch(z_tex, ivec2(c.x, max(c.y - 1, 0)), 0).r;
    float zu = texelFetch(z_tex, ivec2(c.x, min(c.y + 1, last.y)), 0).r;
    if (c.x <= 0)      zl = 0.0;
    if (c.x >= last.x) zr = 0.0;
    if (c.y <= 0)      zd = 0.0;
    if (c.y >= last.y) zu = 0.0;
    vec2 pc = vec2(c) + 0.5;
    vec3 dx = sao_axis_tangent(C, pc, vec2(1.0, 0.0), zl, zr, proj_info, ortho);
    vec3 dy = sao_axis_tangent(C, pc, vec2(0.0, 1.0), zd, zu, proj_info, ortho);
    vec3 n = cross(dx, dy);
    if (proj_info.x * proj_info.y < 0.0)
        n = -n;
    float l2 = dot(n, n);
    return (sao_is_finite(l2) && l2 > 0.0) ? n * inversesqrt(l2) : vec3(0.0, 0.0, 1.0);
}

#endif // SAO_NORMAL_GLSL
