// sao_zmip.glsl -- the camera-space z MIP chain: rotated-grid subsampling (SAO paper Table 1) and
// the per-tap MIP level choice (eq. 9-10).
// Library code: pure functions. Math: docs/effect-math.md, "mips" and "Taps".
#ifndef SAO_ZMIP_GLSL
#define SAO_ZMIP_GLSL

// Table 1, rotated grid subsample: z^{m+1}(x, y) = z^m(2x + ((y & 1) ^ 1), 2y + ((x & 1) ^ 1)),
// clamped to the previous level's last texel (only matters where that level is 1 texel wide).
ivec2 sao_rotated_grid_source(ivec2 p, ivec2 prev_size)
{
    ivec2 s = ivec2(2 * p.x + ((p.y & 1) ^ 1), 2 * p.y + ((p.x & 1) ^ 1));
    return min(s, prev_size - 1);
}

// Table 1 read backwards, for walking up a chain: level m - 1 texel `cur` (level m - 1 is
// prev_size) is what level m texel cur >> 1 copies exactly when that texel exists (level m is
// max(prev_size >> 1, 1)) and sao_rotated_grid_source picks cur for it. Then cur and prev_size
// become that texel and level m's size, and the result is true; otherwise both stay.
bool sao_rotated_grid_parent(inout ivec2 cur, inout ivec2 prev_size)
{
    ivec2 parent = cur >> 1;
    ivec2 size = max(prev_size >> 1, ivec2(1));
    if (any(greaterThanEqual(parent, size)) || sao_rotated_grid_source(parent, prev_size) != cur)
        return false;
    cur = parent;
    prev_size = size;
    return true;
}

// Eq. 9: m = clamp(findMSB(int(h)) - log2(q'), 0, max_mip); h >= 0 is the tap distance in pixels
// (findMSB(0) = -1, so taps under 2^log_q pixels read level 0).
int sao_mip_level(float h, int log_q, int max_mip)
{
    return clamp(findMSB(int(h)) - log_q, 0, max_mip);
}

// Eq. 10: the level-m texel holding full-resolution pixel `tap`, clamped to the level (taps
// past the edge read the edge texel). The level size is derived from the level-0 size
// (max(size0 >> m, 1), the GL/Vulkan MIP size rule) rather than queried with
// textureSize(s, m): that is one texture instruction less per tap, and llvmpipe (Mesa 22.3)
// answers a size query whose lod differs between invocations with one invocation's lod.
ivec2 sao_mip_texel(ivec2 tap, int m, ivec2 size0)
{
    ivec2 level_size = max(size0 >> m, ivec2(1));
    return clamp(tap >> m, ivec2(0), level_size - 1);
}

#endif // SAO_ZMIP_GLSL
