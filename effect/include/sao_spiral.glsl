// sao_spiral.glsl -- spiral tap pattern (SAO paper eq. 6-7) with the per-pixel rotation of eq. 8:
// the pixel's angle in 32-bit fixed-point turns, so it is exact at any resolution, and the taps'
// directions walked from it by a rotation of 2*pi*tau/s each.
// Library code: pure functions. Math: docs/effect-math.md, "Spiral".
#ifndef SAO_SPIRAL_GLSL
#define SAO_SPIRAL_GLSL

// Eq. 8, phi, as a fraction of a turn in units of 2^-32. The AlchemyAO/G3D hash
// ((3x) ^ (y + x*y)) * 10 radians is reduced modulo 2*pi exactly in integers:
// phi / (2*pi) = frac(hash * 10 / (2*pi)), and 10/(2*pi) mod 1 = 2 * SAO_PHASE_MUL / 2^32
// (to 5.5e-11). uint arithmetic wraps modulo 2^32, which is what a turn does.
uint sao_pixel_phase(uvec2 p)
{
    uint h = (3u * p.x) ^ (p.y + p.x * p.y);
    return (h * SAO_PHASE_MUL) << 1u;
}

// Eq. 7: the unit direction of a turn fraction, from basic arithmetic only, so that every backend
// and the CPU reference compute the same bits (built-in cos and sin differ between implementations,
// and every tap's direction is walked from this one): the nearest quarter turn q and the rest x in
// [-pi/4, pi/4], in units of 2^-26 turns (exact as a float); cos and sin of x by their Taylor
// polynomials to x^10 and x^9 (truncation below 2e-9 there), each operation rounded on its own
// (`precise`: no fused multiply-add); the quarter turn swaps and negates them exactly.
const float SAO_TURN26_TO_RADIANS = 9.36267597e-08;  // float(2*pi) * 2^-26
vec2 sao_turn_direction(uint turn)
{
    uint q = (turn + 0x20000000u) >> 30;  // nearest quarter turn (wrapping)
    precise float x = float(int(turn - (q << 30)) >> 6) * SAO_TURN26_TO_RADIANS;
    precise float x2 = x * x;
    precise float s = x + x * x2 * (-0.166666672 + x2 * (0.00833333377 + x2 * (-0.000198412701
                                    + x2 * 2.75573188e-06)));
    precise float c = 1.0 + x2 * (-0.5 + x2 * (0.0416666679 + x2 * (-0.00138888892 + x2 * (2.48015876e-05
                                    + x2 * -2.755732e-07))));
    vec2 d = (q & 1u) != 0u ? vec2(-s, c) : vec2(c, s);
    return (q & 2u) != 0u ? -d : d;
}

// Eq. 6-7 for tap i at csz texel c: alpha = (i + alpha_offset) * inv_s (alpha_offset 0.5 is the
// paper's; other frames move the taps radially, sao::frameSpiral), h = r_px * alpha, and u the
// tap's direction (sao_spiral_step). Returns the full-resolution tap pixel c + ivec2(h * u)
// (conversion truncates toward zero) and h.
ivec2 sao_spiral_tap(ivec2 c, int i, float inv_s, float alpha_offset, vec2 u, float r_px, out float h)
{
    float alpha = (float(i) + alpha_offset) * inv_s;
    h = r_px * alpha;
    return c + ivec2(h * u);
}

// The next tap's direction: tap i's angle is tap 0's plus i*tau/s turns (eq. 6 with the paper's
// (2i+1)/(2s) positions), so each direction is the previous one rotated by step = (cos, sin) of
// 2*pi*tau/s (the host's). Tap 0's comes from sao_turn_direction(the block's tap_turn0 + the
// pixel's phase). One rotation a tap instead of a cos and a sin (polynomials on llvmpipe, whose
// per-tap cost sao-bench --sections per_tap measures); `precise` keeps every product and sum
// rounded on its own (no fused multiply-add), so that every backend and the CPU reference walk the
// same floats.
vec2 sao_spiral_step(vec2 u, vec2 step)
{
    precise vec2 v = vec2(step.x * u.x - step.y * u.y, step.y * u.x + step.x * u.y);
    return v;
}

#endif // SAO_SPIRAL_GLSL
