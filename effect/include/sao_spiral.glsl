// sao_spiral.glsl -- spiral tap pattern (SAO paper eq. 6-7) with the per-pixel rotation of eq. 8,
// all angle arithmetic done in 32-bit fixed-point turns, so it is exact at any resolution.
// Library code: pure functions. Math: docs/effect-math.md, "Spiral".
#ifndef SAO_SPIRAL_GLSL
#define SAO_SPIRAL_GLSL

// 2*pi / 2^24: one unit of a 24-bit turn in radians (float bits 0x34C90FDB; exact product of
// float(2*pi) and 2^-24).
const float SAO_TURN24_TO_RADIANS = 6.28318530717958647692 / 16777216.0;

// Eq. 8, phi, as a fraction of a turn in units of 2^-32. The AlchemyAO/G3D hash
// ((3x) ^ (y + x*y)) * 10 radians is reduced modulo 2*pi exactly in integers:
// phi / (2*pi) = frac(hash * 10 / (2*pi)), and 10/(2*pi) mod 1 = 2 * SAO_PHASE_MUL / 2^32
// (to 5.5e-11). uint arithmetic wraps modulo 2^32, which is what a turn does.
uint sao_pixel_phase(uvec2 p)
{
    uint h = (3u * p.x) ^ (p.y + p.x * p.y);
    return (h * SAO_PHASE_MUL) << 1u;
}

// Eq. 7: the unit direction of a turn fraction; the angle is taken in [-pi, pi).
vec2 sao_turn_direction(uint turn)
{
    float theta = float(int(turn) >> 8) * SAO_TURN24_TO_RADIANS;
    return vec2(cos(theta), sin(theta));
}

// Eq. 6-7 for tap i at csz texel c: alpha = (i + alpha_offset) * inv_s (alpha_offset 0.5 is the
// paper's; other frames move the taps radially, sao::frameSpiral), h = r_px * alpha, and the
// direction of `turn` = alpha*tau turns + phi (the block's tap_turns[i] plus the pixel's phase;
// the host computes the first: per tap, an integer % and / by s cost llvmpipe more than the rest of
// the tap, sao-bench --sections per_tap). Returns the full-resolution tap pixel c + ivec2(h * u)
// (conversion truncates toward zero) and h. The angle keeps the paper's (2i+1)/(2s) position.
ivec2 sao_spiral_tap(ivec2 c, int i, float inv_s, float alpha_offset, uint turn, float r_px, out float h)
{
    float alpha = (float(i) + alpha_offset) * inv_s;
    h = r_px * alpha;
    vec2 u = sao_turn_direction(turn);
    return c + ivec2(h * u);
}

#endif // SAO_SPIRAL_GLSL
