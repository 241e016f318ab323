#include "per_tap_shaders.h"

#include "sao/spiral.h"
#include "sao_effect.h"

namespace sao::bench {

const std::vector<LadderStep>& ladderSteps() {
  // clang-format off
  static const std::vector<LadderStep> steps = {
      //  name                    label                                         frag  2x2    mips   normals imgLd  unif   spiral table
      {"a_fragment",             "(a) fragment, texelFetch",                    true, false, false, false, false, false, false},
      {"b_compute",              "(b) (a) as 8x8 compute, imageStore",          false, false, false, false, false, false, false},
      {"c_compute_2x2",          "(c) (b) + 2x2 through shared memory",         false, true,  false, false, false, false, false},
      {"d_compute_mip",          "(d) (b) + per-tap MIP level",                 false, false, true,  false, false, false, false},
      {"e_compute_rebuilt_n",    "(e) (b) + normals rebuilt from z",            false, false, false, true,  false, false, false},
      {"f_compute_imageload",    "(f) (b) + z by imageLoad",                    false, false, false, false, true,  false, false},
      {"g_compute_uniform_taps", "(g) (b) + tap count from a uniform",          false, false, false, false, false, true,  false},
      {"h_compute_exact_spiral", "(h) (b) + fixed-point spiral",                false, false, false, false, false, false, true},
      // Together (g) and (h) divide by a uniform s per tap (sao_spiral_phase's % and /), not by a constant.
      {"i_compute_uniform_spiral", "(i) (b) + uniform count + fixed-point spiral", false, false, false, false, false, true, true},
      {"j_compute_all",          "(j) (b) + 2x2, MIP, uniform, spiral",         false, true,  true,  false, false, true,  true},
      // (i) without the division: what moving sao_spiral_phase's arithmetic to the host would buy.
      {"k_compute_turn_table",   "(k) (i) with the turns from a uniform table",  false, false, false, false, false, true,  true,  true},
  };
  // clang-format on
  return steps;
}

std::vector<unsigned> spiralTurnTable(int samples, int spiralTurns) {
  std::vector<unsigned> turns;
  for (int i = 0; i < samples; ++i) turns.push_back(spiralTapTurn(i, samples, spiralTurns));  // as the effect's block
  return turns;
}

const char* const kLadderVertexShader = R"(#version 450
// One triangle covering the viewport.
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

namespace {

// The body after the switches. Uniform values come from the effect's parameter block
// (sao::computeConstants) for the same settings and camera; pixel p reads csz texel p + guard.
constexpr const char* kBody = R"(
layout(binding = 0) uniform sampler2D z0;       // csz level 0, r32f (+0.0 = sky)
#if ZMIPS
layout(binding = 1) uniform sampler2D zmips;    // the whole csz chain
#endif
#if !REBUILT_NORMALS
layout(binding = 2) uniform sampler2D normals;  // camera-space normals, rgba16f
#endif
#if IMAGE_LOAD
layout(r32f, binding = 1) readonly uniform image2D zimg;  // csz level 0 again, as an image
#endif
#if FRAGMENT
layout(location = 0) out float ao_out;
#else
layout(local_size_x = 8, local_size_y = 8) in;
layout(r16f, binding = 0) writeonly uniform image2D ao_out;
#endif

uniform vec4 proj_info;     // eq. 3, guard folded in
uniform ivec2 guard;
uniform ivec2 ao_size;
uniform float radius_px;    // r * S' (eq. 5 before 1/-z)
uniform float radius2;
uniform float bias;
uniform float epsilon;
uniform float intensity_div_s;
uniform float contrast;
#if ZMIPS
uniform int log_q;
uniform int max_mip;
#endif
#if QUAD
uniform float quad_threshold;
#endif

#if TURN_TABLE
uniform uint turn_table[64];  // sao_spiral_phase(i, s, tau) per tap
#endif
#if UNIFORM_TAPS
uniform int samples;
uniform int spiral_turns;
uniform float inv_samples;
#define TAP_COUNT samples
#define TURNS spiral_turns
#define INV_S inv_samples
#else
#define TAP_COUNT S_CONST
#define TURNS TAU_CONST
#define INV_S (1.0 / float(S_CONST))
#endif

float zAt(ivec2 t)
{
#if IMAGE_LOAD
    return imageLoad(zimg, t).r;
#else
    return texelFetch(z0, t, 0).r;
#endif
}

vec3 position(vec2 pixel, float z)
{
    return vec3((pixel * proj_info.xy + proj_info.zw) * z, z);
}

#if REBUILT_NORMALS
// sao_axis_tangent / sao_reconstruct_normal (effect/include/sao_normal.glsl), perspective only.
bool sky(float z) { return !(z < 0.0); }
vec3 tangent(vec3 C, vec2 pc, vec2 step, float zm, float zp)
{
    if (!sky(zp) && (sky(zm) || abs(zp - C.z) < abs(C.z - zm)))
        return position(pc + step, zp) - C;
    if (!sky(zm))
        return C - position(pc - step, zm);
    return position(pc + step, C.z) - C;
}
vec3 rebuiltNormal(ivec2 c, vec3 C, ivec2 size0)
{
    ivec2 last = size0 - 1;
    float zl = zAt(ivec2(max(c.x - 1, 0), c.y));
    float zr = zAt(ivec2(min(c.x + 1, last.x), c.y));
    float zd = zAt(ivec2(c.x, max(c.y - 1, 0)));
    float zu = zAt(ivec2(c.x, min(c.y + 1, last.y)));
    if (c.x <= 0)      zl = 0.0;
    if (c.x >= last.x) zr = 0.0;
    if (c.y <= 0)      zd = 0.0;
    if (c.y >= last.y) zu = 0.0;
    vec2 pc = vec2(c) + 0.5;
    vec3 n = cross(tangent(C, pc, vec2(1.0, 0.0), zl, zr), tangent(C, pc, vec2(0.0, 1.0), zd, zu));
    if (proj_info.x * proj_info.y < 0.0)
        n = -n;
    float l2 = dot(n, n);
    return l2 > 0.0 ? n * inversesqrt(l2) : vec3(0.0, 0.0, 1.0);
}
#endif

// Eq. 1 at pixel p (csz texel c, z_C = zc < 0).
float visibility(ivec2 p, ivec2 c, float zc, ivec2 size0)
{
    vec3 C = position(vec2(c) + 0.5, zc);
#if REBUILT_NORMALS
    vec3 n = rebuiltNormal(c, C, size0);
#else
    vec3 n = texelFetch(normals, c, 0).xyz;
#endif
    float r_px = radius_px / -zc;
#if EXACT_SPIRAL
    // sao_pixel_phase + sao_spiral_phase + sao_turn_direction: 32-bit fixed-point turns.
    uint phase = (((3u * uint(p.x)) ^ (uint(p.y) + uint(p.x) * uint(p.y))) * SAO_PHASE_MUL) << 1u;
#else
    // G3D's SAO: the hash times 10 radians, angles in float.
    float phi = float((3 * p.x ^ p.y + p.x * p.y) * 10);
#endif
    float sum = 0.0;
    for (int i = 0; i < TAP_COUNT; ++i) {
        float alpha = (float(i) + 0.5) * INV_S;
        float h = r_px * alpha;
#if EXACT_SPIRAL && TURN_TABLE
        uint turn = turn_table[i] + phase;
        float theta = float(int(turn) >> 8) * (6.28318530717958647692 / 16777216.0);
#elif EXACT_SPIRAL
        uint k = (uint(2 * i + 1) * uint(TURNS)) % uint(2 * TAP_COUNT);
        uint turn = (((k << 23u) / uint(TAP_COUNT)) << 8u) + phase;
        float theta = float(int(turn) >> 8) * (6.28318530717958647692 / 16777216.0);
#else
        float theta = alpha * (float(TURNS) * 6.28318530717958647692) + phi;
#endif
        ivec2 tap = c + ivec2(h * vec2(cos(theta), sin(theta)));
#if ZMIPS
        int m = clamp(findMSB(int(h)) - log_q, 0, max_mip);
        float zq = texelFetch(zmips, clamp(tap >> m, ivec2(0), max(size0 >> m, ivec2(1)) - 1), m).r;
#else
        float zq = zAt(clamp(tap, ivec2(0), size0 - 1));
#endif
        vec3 v = position(vec2(tap) + 0.5, zq) - C;
        float vv = dot(v, v);
        float vn = dot(v, n);
        sum += (zq < 0.0 && vv < radius2) ? max(0.0, vn + zc * bias) / (vv + epsilon) : 0.0;
    }
    return pow(max(0.0, 1.0 - intensity_div_s * sum), contrast);
}

#if QUAD
// The 2x2 step of sao_ao_main: sao_quad_mix along x, then along y, two barriers.
shared float quad_a[64];
shared float quad_h[64];
shared float quad_z[64];
float quadMix(float a, float z, float a_n, float z_n)
{
    return (z < 0.0 && z_n < 0.0 && abs(z - z_n) < quad_threshold) ? 0.5 * (a + a_n) : a;
}
#endif

void main()
{
#if FRAGMENT
    ivec2 p = ivec2(gl_FragCoord.xy);
    bool inside = true;
#else
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    bool inside = all(lessThan(p, ao_size));
#endif
    ivec2 size0 = textureSize(z0, 0);
    ivec2 c = p + guard;
    float A = 1.0;
    float key = 0.0;
    if (inside) {
        float zc = zAt(c);
        if (zc < 0.0) {
            A = visibility(p, c, zc, size0);
            key = zc;
        }
    }
#if QUAD
    uint li = gl_LocalInvocationIndex;
    uvec2 l = gl_LocalInvocationID.xy;
    uint lx = l.y * 8u + (l.x ^ 1u);
    uint ly = (l.y ^ 1u) * 8u + l.x;
    quad_a[li] = A;
    quad_z[li] = key;
    memoryBarrierShared();
    barrier();
    float a_h = quadMix(A, key, quad_a[lx], quad_z[lx]);
    quad_h[li] = a_h;
    memoryBarrierShared();
    barrier();
    A = quadMix(a_h, key, quad_h[ly], quad_z[ly]);
#endif
#if FRAGMENT
    ao_out = A;
#else
    if (inside)
        imageStore(ao_out, p, vec4(A, 0.0, 0.0, 0.0));
#endif
}
)";

const char* flag(bool on) { return on ? "1" : "0"; }

}  // namespace

std::string ladderShader(const LadderStep& s, int samples, int spiralTurns) {
  std::string src = "#version 450\n";
  src += std::string("#define FRAGMENT ") + flag(s.fragment) + "\n";
  src += std::string("#define QUAD ") + flag(s.quad2x2) + "\n";
  src += std::string("#define ZMIPS ") + flag(s.zMips) + "\n";
  src += std::string("#define REBUILT_NORMALS ") + flag(s.rebuiltNormals) + "\n";
  src += std::string("#define IMAGE_LOAD ") + flag(s.imageLoad) + "\n";
  src += std::string("#define UNIFORM_TAPS ") + flag(s.uniformTaps) + "\n";
  src += std::string("#define EXACT_SPIRAL ") + flag(s.exactSpiral) + "\n";
  src += std::string("#define TURN_TABLE ") + flag(s.turnTable) + "\n";
  src += "#define S_CONST " + std::to_string(samples) + "\n";
  src += "#define SAO_PHASE_MUL " + std::to_string(gen::SAO_PHASE_MUL) + "u\n";  // eq. 8, the effect's constant
  src += "#define TAU_CONST " + std::to_string(spiralTurns) + "\n";
  return src + kBody;
}

}  // namespace sao::bench
