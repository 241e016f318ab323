// The GLSL library functions of effect/include/*.glsl, one C++ function each, templated on the
// scalar type T (float mimics the GPU, double is the high-precision reference). Every expression
// keeps the GLSL's order of operations; this file must be compiled with -ffp-contract=off.
// Names follow the shaders (sao_foo -> foo) so that the two can be read side by side.
// It is compiled only inside sao_cpu (backends/cpu/src/reference.cpp includes the effect's CPU
// passes, which include this file), whose flags give that; no public header includes it.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "sao/cpu/reference.h"

namespace sao::cpu::detail {

// ---- sao_depth.glsl: bit tests, never std::isnan (which -ffast-math folds away).

inline bool isFinite(float x) { return (std::bit_cast<std::uint32_t>(x) & 0x7F800000u) != 0x7F800000u; }
inline bool isFinite(double x) {
  return (std::bit_cast<std::uint64_t>(x) & 0x7FF0000000000000ull) != 0x7FF0000000000000ull;
}

// Geometry iff finite, negative and non-zero: -0.0 < bits < -Inf as unsigned integers.
inline bool isSky(float z) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(z);
  return !(b > 0x80000000u && b < 0xFF800000u);
}
inline bool isSky(double z) {
  const std::uint64_t b = std::bit_cast<std::uint64_t>(z);
  return !(b > 0x8000000000000000ull && b < 0xFFF0000000000000ull);
}

// ---- The parameter block with its float components widened to T (ints unchanged), generated
// from the effect's block declaration.

template <typename T>
using Block = gen::ParamBlockAs<T>;

// GLSL: `const float SAO_TURN26_TO_RADIANS = 9.36267597e-08;`, float(2*pi) / 2^26 (float(2*pi)'s
// significand, exactly). Double: 2*pi / 2^26 in double.
template <typename T>
constexpr T turn26ToRadians() {
  return T(6.28318530717958647692) / T(67108864.0);  // float: bits of float(2 pi) * 2^-26, the shader's
}

// ---- Images: one mip level or one 1-/2-channel image, row 0 first.

template <typename T>
struct Image {
  int w = 0, h = 0, ch = 1;
  std::vector<T> v;
  Image() = default;
  Image(int w_, int h_, int ch_) : w(w_), h(h_), ch(ch_), v(std::size_t(w_) * std::size_t(h_) * ch_, T(0)) {}
  T& at(int x, int y, int c = 0) { return v[(std::size_t(y) * w + x) * ch + c]; }
  T at(int x, int y, int c = 0) const { return v[(std::size_t(y) * w + x) * ch + c]; }
};

template <typename T>
struct Vec3 {
  T x, y, z;
};
template <typename T>
Vec3<T> operator-(Vec3<T> a, Vec3<T> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
// dot(a, b) = (a.x*b.x + a.y*b.y) + a.z*b.z
template <typename T>
T dot(Vec3<T> a, Vec3<T> b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
// cross(a, b) = (a.y*b.z - b.y*a.z, a.z*b.x - b.z*a.x, a.x*b.y - b.x*a.y)
template <typename T>
Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}

template <typename T>
T glslMax(T a, T b) {  // GLSL max(a, b) = (a < b) ? b : a
  return (a < b) ? b : a;
}
template <typename T>
T glslMin(T a, T b) {  // GLSL min(a, b) = (b < a) ? b : a
  return (b < a) ? b : a;
}

// ---- sao_depth.glsl: sao_z_from_depth (eq. 2 and the sky rules).

template <typename T>
T zFromDepth(T d, const Block<T>& P) {
  if (!isFinite(d) || d * P.far_dir >= P.far_lim) return T(0);
  if (P.depth_mode != gen::SAO_DEPTH_MODE_LINEAR && (d < T(0) || d > T(1))) return T(0);  // no hardware depth
  T z;
  if (P.depth_mode == gen::SAO_DEPTH_MODE_PERSPECTIVE)
    z = P.clip_info.x / (d * P.clip_info.y + P.clip_info.z);
  else
    z = d * P.clip_info.y + P.clip_info.z;
  return isSky(z) ? T(0) : z;
}

// sao_nearer_z: the nearer to the camera of two csz values (the larger geometry z; sky only when
// both are sky).
template <typename T>
T nearerZ(T a, T b) {
  if (isSky(a)) return b;
  if (isSky(b)) return a;
  return a < b ? b : a;
}

// ---- sao_position.glsl

// Eq. 3: pixel is a csz level-0 pixel centre.
template <typename T>
Vec3<T> position(T px, T py, T z, const Block<T>& P) {
  const T w = (P.ortho != 0) ? T(1) : z;
  return {w * (px * P.proj_info.x + P.proj_info.z), w * (py * P.proj_info.y + P.proj_info.w), z};
}

// Eq. 5, clamped to SAO_MAX_RADIUS_PX.
template <typename T>
T screenRadius(T z, const Block<T>& P) {
  T r = P.radius * P.proj_scale;
  if (P.ortho == 0) r = r / (-z);
  return glslMin(r, T(gen::SAO_MAX_RADIUS_PX));
}

// ---- sao_normal.glsl

template <typename T>
T inverseSqrt(T x) {
  return T(1) / std::sqrt(x);
}

template <typename T>
Vec3<T> decodeNormal(Vec3<T> n) {
  const T l2 = dot(n, n);
  if (isFinite(l2) && l2 > T(0)) {
    const T s = inverseSqrt(l2);
    return {n.x * s, n.y * s, n.z * s};
  }
  return {T(0), T(0), T(0)};
}

template <typename T>
Vec3<T> octahedralDecode(T ex, T ey) {
  Vec3<T> n{ex, ey, (T(1) - std::abs(ex)) - std::abs(ey)};
  if (n.z < T(0)) {
    const T sx = ex >= T(0) ? T(1) : T(-1);
    const T sy = ey >= T(0) ? T(1) : T(-1);
    n.x = (T(1) - std::abs(ey)) * sx;
    n.y = (T(1) - std::abs(ex)) * sy;
  }
  return n;
}

// sao_supplied_normal: t = the texel's (x, y, z) as the shader reads it.
template <typename T>
Vec3<T> suppliedNormal(Vec3<T> t, const Block<T>& P) {
  const int e = P.normals_encoding;
  const bool octahedral = e == gen::SAO_NORMALS_CAMERA_OCTAHEDRAL || e == gen::SAO_NORMALS_WORLD_OCTAHEDRAL;
  Vec3<T> v = octahedral ? octahedralDecode(t.x, t.y) : t;
  if (e == gen::SAO_NORMALS_WORLD_XYZ || e == gen::SAO_NORMALS_WORLD_OCTAHEDRAL)
    v = {(P.view_x.x * v.x + P.view_y.x * v.y) + P.view_z.x * v.z,
         (P.view_x.y * v.x + P.view_y.y * v.y) + P.view_z.y * v.z,
         (P.view_x.z * v.x + P.view_y.z * v.y) + P.view_z.z * v.z};
  return decodeNormal(v);
}

// One axis of eq. 4 (sx, sy: the step (1,0) or (0,1)).
template <typename T>
Vec3<T> axisTangent(Vec3<T> C, T pcx, T pcy, T sx, T sy, T zm, T zp, const Block<T>& P) {
  const bool okm = !isSky(zm);
  const bool okp = !isSky(zp);
  if (okp && (!okm || std::abs(zp - C.z) < std::abs(C.z - zm))) return position(pcx + sx, pcy + sy, zp, P) - C;
  if (okm) return C - position(pcx - sx, pcy - sy, zm, P);
  return position(pcx + sx, pcy + sy, C.z, P) - C;
}

// Eq. 4 face normal at csz level-0 texel (cx, cy).
template <typename T>
Vec3<T> reconstructNormal(const Image<T>& z0, int cx, int cy, Vec3<T> C, const Block<T>& P) {
  const int lastX = z0.w - 1, lastY = z0.h - 1;
  T zl = z0.at(std::max(cx - 1, 0), cy);
  T zr = z0.at(std::min(cx + 1, lastX), cy);
  T zd = z0.at(cx, std::max(cy - 1, 0));
  T zu = z0.at(cx, std::min(cy + 1, lastY));
  if (cx <= 0) zl = T(0);
  if (cx >= lastX) zr = T(0);
  if (cy <= 0) zd = T(0);
  if (cy >= lastY) zu = T(0);
  const T pcx = T(cx) + T(0.5), pcy = T(cy) + T(0.5);
  const Vec3<T> dx = axisTangent(C, pcx, pcy, T(1), T(0), zl, zr, P);
  const Vec3<T> dy = axisTangent(C, pcx, pcy, T(0), T(1), zd, zu, P);
  Vec3<T> n = cross(dx, dy);
  if (P.proj_info.x * P.proj_info.y < T(0)) n = {-n.x, -n.y, -n.z};
  const T l2 = dot(n, n);
  if (isFinite(l2) && l2 > T(0)) {
    const T s = inverseSqrt(l2);
    return {n.x * s, n.y * s, n.z * s};
  }
  return {T(0), T(0), T(1)};
}

// ---- sao_zmip.glsl

// Table 1 rotated grid source texel of level-m texel (x, y) in the previous level.
inline void rotatedGridSource(int x, int y, int prevW, int prevH, int& sx, int& sy) {
  sx = std::min(2 * x + ((y & 1) ^ 1), prevW - 1);
  sy = std::min(2 * y + ((x & 1) ^ 1), prevH - 1);
}

// GLSL findMSB(int) for a non-negative value: -1 for 0.
inline int findMSB(std::int32_t v) { return v <= 0 ? -1 : std::bit_width(std::uint32_t(v)) - 1; }

// Eq. 9.
template <typename T>
int mipLevel(T h, int log_q, int max_mip) {
  return std::clamp(findMSB(static_cast<std::int32_t>(h)) - log_q, 0, max_mip);
}

// Eq. 10 (one axis): clamp(tap >> m, 0, max(size0 >> m, 1) - 1); >> is arithmetic on int32.
inline int mipTexel(int tap, int m, int size0) {
  const int levelSize = std::max(size0 >> m, 1);
  return std::clamp(tap >> m, 0, levelSize - 1);
}

// ---- sao_spiral.glsl

// Eq. 8: phi in 2^-32 turns, from the AO pixel.
inline std::uint32_t pixelPhase(std::uint32_t x, std::uint32_t y) {
  const std::uint32_t h = (3u * x) ^ (y + x * y);
  return (h * std::uint32_t(gen::SAO_PHASE_MUL)) << 1u;
}

// Eq. 7: sao_turn_direction, operation for operation: the nearest quarter turn, the rest x in
// [-pi/4, pi/4] in 2^-26 turns, Taylor polynomials for cos and sin of x, the quarter turn's swap and
// signs. Float: the shader's constants and bits; Double: the exact Taylor coefficients.
template <typename T>
void turnDirection(std::uint32_t turn, T& ux, T& uy) {
  const std::uint32_t q = (turn + 0x20000000u) >> 30;
  const T x = T(static_cast<std::int32_t>(turn - (q << 30)) >> 6) * turn26ToRadians<T>();
  const T x2 = x * x;
  T s, c;
  if constexpr (std::is_same_v<T, float>) {
    s = x + x * x2 * (-0.166666672f + x2 * (0.00833333377f + x2 * (-0.000198412701f + x2 * 2.75573188e-06f)));
    c = 1.0f + x2 * (-0.5f + x2 * (0.0416666679f + x2 * (-0.00138888892f + x2 * (2.48015876e-05f
                                                                             + x2 * -2.755732e-07f))));
  } else {
    s = x + x * x2 * (T(-1) / 6 + x2 * (T(1) / 120 + x2 * (T(-1) / 5040 + x2 * (T(1) / 362880))));
    c = T(1) + x2 * (T(-1) / 2 + x2 * (T(1) / 24 + x2 * (T(-1) / 720 + x2 * (T(1) / 40320 + x2 * (T(-1) / 3628800)))));
  }
  T dx = (q & 1u) ? -s : c, dy = (q & 1u) ? c : s;
  if (q & 2u) {
    dx = -dx;
    dy = -dy;
  }
  ux = dx;
  uy = dy;
}

// The spiral's direction walk (sao_spiral_step): tap 0's direction from the block's tap_turn0 plus
// the pixel's phase, then each tap's the previous one rotated by tap_step, every product and sum
// rounded on its own (the shader's `precise`; this file is built with -ffp-contract=off).
template <typename T>
struct SpiralDirection {
  T ux = T(1), uy = T(0);
  static SpiralDirection start(std::uint32_t phase, const Block<T>& P) {
    SpiralDirection u;
    turnDirection<T>(P.tap_turn0 + phase, u.ux, u.uy);
    return u;
  }
  void step(const Block<T>& P) {
    const T x = P.tap_step.x * ux - P.tap_step.y * uy;
    const T y = P.tap_step.y * ux + P.tap_step.x * uy;
    ux = x;
    uy = y;
  }
};

// Eq. 6-7: tap i's pixel (tx, ty) and its distance h, in direction u (then u steps to tap i + 1's).
template <typename T>
void spiralTap(int cx, int cy, int i, T r_px, const Block<T>& P, SpiralDirection<T>& u, int& tx, int& ty, T& h) {
  const T alpha = (T(i) + P.frame_alpha_offset) * P.inv_samples;  // offset 0.5 at frame 0
  h = r_px * alpha;
  tx = cx + static_cast<int>(h * u.ux);  // conversion truncates toward zero
  ty = cy + static_cast<int>(h * u.uy);
  u.step(P);
}

// ---- sao_estimator.glsl

template <typename T>
T tapObscurance(Vec3<T> C, Vec3<T> n, T qx, T qy, T zq, const Block<T>& P) {
  if (isSky(zq)) return T(0);
  const Vec3<T> v = position(qx, qy, zq, P) - C;
  const T vv = dot(v, v);
  if (vv > P.radius2) return T(0);
  const T vn = dot(v, n);
  return glslMax(T(0), vn + C.z * P.bias) / (vv + P.epsilon);
}

template <typename T>
T visibility(T sum, const Block<T>& P) {
  const T a = glslMax(T(0), T(1) - P.intensity_div_s * sum);
  return (P.contrast == T(1)) ? a : std::pow(a, P.contrast);
}

template <typename T>
T fade(T a, T z, const Block<T>& P) {
  const T d = -z;
  if (P.fade_end <= T(0) || d <= P.fade_start) return a;
  if (d >= P.fade_end) return T(1);
  const T t = (d - P.fade_start) * P.fade_inv_range;
  return a + (T(1) - a) * t;
}

template <typename T>
T quadMix(T a, T z, T an, T zn, T threshold) {
  const bool ok = !isSky(z) && !isSky(zn) && std::abs(z - zn) < threshold;
  return ok ? T(0.5) * (a + an) : a;
}

// ---- sao_blur.glsl

template <typename T>
T blurGauss(int t, const Block<T>& P) {
  const int a = std::abs(t);
  if (a == 0) return T(1);
  return (a <= 4) ? P.blur_weights_1_4[std::clamp(a - 1, 0, 3)] : P.blur_weights_5_8[std::clamp(a - 5, 0, 3)];
}

// sao_blur_slope: the flatter one-sided slope (minmod), 0 at a ridge, a valley or next to sky.
template <typename T>
T blurSlope(T km, T k0, T kp) {
  const T gm = k0 - km, gp = kp - k0;
  const bool none = isSky(km) || isSky(kp) || ((gp > T(0)) != (gm > T(0)));
  return none ? T(0) : (std::abs(gp) < std::abs(gm) ? gp : gm);
}

// Bilateral 1D blur of the 2-channel image src at (x, y) along (dx, dy); writes (A, key).
template <typename T>
void bilateralBlur(const Image<T>& src, int x, int y, int dx, int dy, const Block<T>& P, T& outA, T& outKey) {
  const T centreA = src.at(x, y, 0), centreZ = src.at(x, y, 1);
  if (isSky(centreZ)) {
    outA = T(1);
    outKey = T(0);
    return;
  }
  const int R = std::clamp(P.blur_radius, 0, gen::SAO_MAX_BLUR_RADIUS);
  // sao_blur_sharpness
  const T sharpness = P.blur_edge_sharpness + P.blur_edge_relative / glslMax(std::abs(centreZ), T(1.0e-20f));
  // The centre's plane (blur_edge_slope): its neighbours a stride away, both inside the image. The
  // vertical pass reads the horizontal pass's keys (each the centre's own), as the shader's tile.
  T g = T(0);
  const int mx = x - dx * P.blur_stride, my = y - dy * P.blur_stride;
  const int px = x + dx * P.blur_stride, py = y + dy * P.blur_stride;
  if (P.blur_edge_slope != 0 && mx >= 0 && my >= 0 && px < src.w && py < src.h)
    g = blurSlope(src.at(mx, my, 1), centreZ, src.at(px, py, 1));
  T sum = T(0);
  T wsum = T(0);
  for (int t = -R; t <= R; ++t) {
    T a = centreA, k = centreZ;
    if (t != 0) {
      const int qx = x + dx * (t * P.blur_stride);
      const int qy = y + dy * (t * P.blur_stride);
      if (qx < 0 || qy < 0 || qx >= src.w || qy >= src.h) continue;
      a = src.at(qx, qy, 0);
      k = src.at(qx, qy, 1);
      if (isSky(k)) continue;
    }
    const T w = blurGauss(t, P) * glslMax(T(0), T(1) - sharpness * std::abs(k - (centreZ + T(t) * g)));
    sum += w * a;
    wsum += w;
  }
  outA = sum / wsum;
  outKey = centreZ;
}

// ---- sao_upsample.glsl

// sao_low_representative, one axis: the viewport pixel reduced pixel q stands for.
inline int lowRepresentative(int q, int d, int fullSize) { return std::min(q * d + (d >> 1), fullSize - 1); }

template <typename T>
T upsampleDepthWeight(T z, T zLow, T k) {
  if (isSky(zLow)) return T(0);
  return glslMax(T(0), T(1) - k * std::abs(z - zLow));
}

// sao.glsl's sao_upsample_bilinear and, for a pixel it leaves unmatched, sao_upsample_nearest_z: A
// at viewport pixel (x, y) with csz z from the reduced (A, key) image `low`, whose keys are z times
// 1 / keyToView (sao_upsample_main converts the nine it fetches back); d is 1, 2 or 4 (shifts as in
// the shader).
template <typename T>
T upsample(const Image<T>& low, int x, int y, T z, int d, int fullW, int fullH, T keyToView) {
  if (isSky(z)) return T(1);
  auto lowZ = [&](int qx, int qy) { return low.at(qx, qy, 1) * keyToView; };
  const int sh = findMSB(d);
  const int lastX = low.w - 1, lastY = low.h - 1;
  const int q0x = std::min(std::max(x - (d >> 1), 0) >> sh, lastX);
  const int q0y = std::min(std::max(y - (d >> 1), 0) >> sh, lastY);
  const int q1x = std::min(q0x + 1, lastX), q1y = std::min(q0y + 1, lastY);
  const int r0x = lowRepresentative(q0x, d, fullW), r0y = lowRepresentative(q0y, d, fullH);
  const int r1x = lowRepresentative(q1x, d, fullW), r1y = lowRepresentative(q1y, d, fullH);
  const T tx = std::clamp(T(x - r0x) / T(std::max(r1x - r0x, 1)), T(0), T(1));
  const T ty = std::clamp(T(y - r0y) / T(std::max(r1y - r0y, 1)), T(0), T(1));
  const T k = T(gen::SAO_UPSAMPLE_Z_SHARPNESS) / (-z);
  const T w00 = ((T(1) - tx) * (T(1) - ty)) * upsampleDepthWeight(z, lowZ(q0x, q0y), k);
  const T w10 = (tx * (T(1) - ty)) * upsampleDepthWeight(z, lowZ(q1x, q0y), k);
  const T w01 = ((T(1) - tx) * ty) * upsampleDepthWeight(z, lowZ(q0x, q1y), k);
  const T w11 = (tx * ty) * upsampleDepthWeight(z, lowZ(q1x, q1y), k);
  const T wsum = ((w00 + w10) + w01) + w11;
  if (wsum > T(0))
    return (((w00 * low.at(q0x, q0y, 0) + w10 * low.at(q1x, q0y, 0)) + w01 * low.at(q0x, q1y, 0)) +
            w11 * low.at(q1x, q1y, 0)) /
           wsum;
  // The 3x3 around the texel holding x, within 1/SHARPNESS (relative) of the nearest z, weighted
  // linearly down to 0 (texels of equal z share the pixel).
  const int cx = std::min(x >> sh, lastX), cy = std::min(y >> sh, lastY);
  T best = T(-1);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const T zl = lowZ(std::clamp(cx + dx, 0, lastX), std::clamp(cy + dy, 0, lastY));
      if (!isSky(zl)) best = best < T(0) ? std::abs(z - zl) : glslMin(best, std::abs(z - zl));
    }
  if (best < T(0)) return T(1);
  T sum = T(0), vsum = T(0);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int qx = std::clamp(cx + dx, 0, lastX), qy = std::clamp(cy + dy, 0, lastY);
      const T zl = lowZ(qx, qy);
      if (isSky(zl)) continue;
      const T v = glslMax(T(0), T(1) - k * (std::abs(z - zl) - best));
      sum += v * low.at(qx, qy, 0);
      vsum += v;
    }
  return sum / vsum;
}

// |x| rounded to the nearest binary16 value, ties away from zero (|x| <= 65504): the values of
// sao_round_half_magnitude in sao_blur.glsl, by frexp steps. t = |x| / 2^q holds the spacing's
// multiples; its fraction t - floor(t) is exact, so the tie test is too (floor(t + 0.5) would
// round t + 0.5 up to 1 for the float just below 2^-25).
inline float roundHalfMagnitude(float m) {
  if (m == 0.0f) return m;
  int e = 0;
  (void)std::frexp(m, &e);              // m = f * 2^e, f in [0.5, 1)
  const int q = std::max(e - 11, -24);  // log2 of the binary16 spacing at m
  const float t = std::ldexp(m, -q);
  const float f = std::floor(t);
  return std::ldexp(t - f >= 0.5f ? f + 1.0f : f, q);
}

// sao_round_to_half (float only: the shader's own rounding): x clamped to [0, 1], then rounded.
inline float roundToHalf(float x) { return roundHalfMagnitude(std::clamp(x, 0.0f, 1.0f)); }

// sao_pack_shares / sao_unpack_shares (sao_visibility.glsl): a texel's shares of thickness along
// x and y, each rounded to binary16 (in Float already so), as csz_share's y: packHalf2x16's bits,
// x in the low half, read as a float (a normal positive one for shares in [2^-14, 1]).
// (sao::halfBits and sao::halfToFloat are exact for binary16 values.)
inline float packShares(float sx, float sy) {
  const std::uint32_t x = sao::halfBits(roundToHalf(sx)), y = sao::halfBits(roundToHalf(sy));
  return std::bit_cast<float>(x | (y << 16));
}
inline void unpackShares(float packed, float& sx, float& sy) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(packed);
  sx = sao::halfToFloat(std::uint16_t(b & 0xFFFFu));
  sy = sao::halfToFloat(std::uint16_t(b >> 16));
}

// sao_round_to_half_signed of sao_blur.glsl: |x| rounded, sign kept (±0 too), not clamped.
inline float roundToHalfSigned(float x) {
  const float r = roundHalfMagnitude(std::fabs(x));
  return x < 0.0f ? -r : (x == 0.0f ? x : r);
}

// sao_half_texel of sao_blur.glsl (HALF_INTERMEDIATES): the (A, key) texel an rg16f image holds;
// Float rounds as the shader does, Double keeps the values.
template <typename T>
void halfTexel(T& a, T& key) {
  if constexpr (std::is_same_v<T, float>) {
    a = roundToHalf(a);
    key = roundToHalfSigned(std::max(key, -65504.0f));
  }
}

// sao_round_to_unorm8 of sao_output.glsl: x clamped to [0, 1], rounded to the nearest multiple of
// 1/255 (halves up), each operation one binary32 rounding as the shader does it.
inline float roundToUnorm8(float x) { return std::floor(std::clamp(x, 0.0f, 1.0f) * 255.0f + 0.5f) / 255.0f; }

// sao_output_multiply of sao_output.glsl (output blend multiply): channel c times A clamped to
// [0, 1]; Float rounds it once as the format holds it (unorm8: 1/255 steps; else binary16),
// Double leaves it unrounded; an infinite or NaN channel stays as it is.
template <typename T>
T outputMultiply(T c, T a, bool unorm8) {
  if (!std::isfinite(c)) return c;
  const T m = c * std::clamp(a, T(0), T(1));
  if constexpr (std::is_same_v<T, float>) return unorm8 ? roundToUnorm8(m) : roundToHalfSigned(m);
  return m;
}

// sao_multi_bounce of sao_output.glsl: Jimenez et al. 2016's multi-bounce fit
// max(x, ((a x + b) x + c) x) with the block's coefficients, or x itself when it is off (albedo 0).
template <typename T>
T multiBounce(T x, const Block<T>& P) {
  if (P.multi_bounce == 0) return x;
  return glslMax(x, ((P.bounce_a * x + P.bounce_b) * x + P.bounce_c) * x);
}

// ---- sao_temporal.glsl


// sao_rotate_to_previous / sao_to_previous: the rotation of prev_from_cur_*, then with its translation.
template <typename T>
Vec3<T> rotateToPrevious(Vec3<T> n, const Block<T>& P) {
  auto row = [&](const auto& m) { return dot(Vec3<T>{m.x, m.y, m.z}, n); };
  return {row(P.prev_from_cur_x), row(P.prev_from_cur_y), row(P.prev_from_cur_z)};
}

template <typename T>
Vec3<T> toPrevious(Vec3<T> C, const Block<T>& P) {
  const Vec3<T> r = rotateToPrevious(C, P);
  return {r.x + P.prev_from_cur_x.w, r.y + P.prev_from_cur_y.w, r.z + P.prev_from_cur_z.w};
}

// sao_pack_normal / sao_unpack_normal: octahedral, 12 bits a component, the integer qx*4096 + qy.
template <typename T>
T packNormal(Vec3<T> n) {
  const T l1 = (std::abs(n.x) + std::abs(n.y)) + std::abs(n.z);
  T ex = n.x / l1, ey = n.y / l1;
  if (n.z < T(0)) {
    const T sx = ex >= T(0) ? T(1) : T(-1);
    const T sy = ey >= T(0) ? T(1) : T(-1);
    const T fx = (T(1) - std::abs(ey)) * sx;
    const T fy = (T(1) - std::abs(ex)) * sy;
    ex = fx;
    ey = fy;
  }
  const T qx = std::floor((ex * T(0.5) + T(0.5)) * T(4095) + T(0.5));
  const T qy = std::floor((ey * T(0.5) + T(0.5)) * T(4095) + T(0.5));
  return qx * T(4096) + qy;
}

template <typename T>
Vec3<T> unpackNormal(T code) {
  const T qx = std::floor(code / T(4096));
  const T qy = code - qx * T(4096);
  return octahedralDecode(qx / T(4095) * T(2) - T(1), qy / T(4095) * T(2) - T(1));
}

// sao_normals_agree: within acos(SAO_TEMPORAL_NORMAL_COS), compared squared.
template <typename T>
bool normalsAgree(Vec3<T> a, Vec3<T> b) {
  const T d = dot(a, b);
  const T c = T(gen::SAO_TEMPORAL_NORMAL_COS);
  return d > T(0) && d * d >= (c * c) * (dot(a, a) * dot(b, b));
}

template <typename T>
T bilinearWeight(int ox, int oy, T fx, T fy) {
  return ((ox == 1) ? fx : T(1) - fx) * ((oy == 1) ? fy : T(1) - fy);
}

// sao_previous_pixel: csz texel coordinates of P (previous camera space) in the previous camera.
template <typename T>
void previousPixel(Vec3<T> Q, const Block<T>& P, T& x, T& y) {
  const T w = (P.ortho != 0) ? T(1) : Q.z;
  x = (Q.x / w - P.prev_proj_info.z) / P.prev_proj_info.x;
  y = (Q.y / w - P.prev_proj_info.w) / P.prev_proj_info.y;
}

// sao_temporal_accumulate: (accumulated sum, frames) of this frame's pixel whose surface was at csz
// texel coordinates (px, py) with z zP in the previous frame, from that frame's history (4 channels).
template <typename T>
void temporalAccumulate(const Image<T>& history, T px, T py, T zP, Vec3<T> nP, bool testNormals, T sum,
                        const Block<T>& P, T& outSum, T& outFrames) {
  T h = T(0);
  T n = T(0);
  if (P.history_valid != 0 && zP < T(0)) {
    const int d = P.ao_divisor;
    const T ux = (((px - T(0.5)) - T(P.guard.x)) - T(d >> 1)) / T(d);
    const T uy = (((py - T(0.5)) - T(P.guard.y)) - T(d >> 1)) / T(d);
    if (ux > T(-2) && uy > T(-2) && ux < T(history.w) + T(1) && uy < T(history.h) + T(1)) {
      const T ix = std::floor(ux), iy = std::floor(uy);
      const T fx = std::floor((ux - ix) * T(64) + T(0.5)) / T(64);
      const T fy = std::floor((uy - iy) * T(64) + T(0.5)) / T(64);
      const int qx0 = int(ix), qy0 = int(iy);
      const T k = P.temporal_depth_k / -zP;
      T wsum = T(0), hsum = T(0), nsum = T(0);
      for (int j = 0; j < 4; ++j) {
        const int ox = j & 1, oy = j >> 1;
        const int qx = qx0 + ox, qy = qy0 + oy;
        const T wb = bilinearWeight(ox, oy, fx, fy);
        if (wb > T(0) && qx >= 0 && qy >= 0 && qx < history.w && qy < history.h) {
          const T tx = history.at(qx, qy, 0), ty = history.at(qx, qy, 1), tz = history.at(qx, qy, 2);
          if (tz > T(0) && !isSky(ty) && (!testNormals || normalsAgree(unpackNormal(history.at(qx, qy, 3)), nP))) {
            const T wt = wb * glslMax(T(0), T(1) - k * std::abs(ty - zP));
            wsum += wt;
            hsum += wt * tx;
            nsum += wt * tz;
          }
        }
      }
      if (wsum > T(0)) {
        h = hsum / wsum;
        n = nsum;
      }
    }
  }
  const T a = glslMax(P.temporal_min_blend, T(1) / (n + T(1)));
  outSum = h + a * (sum - h);
  outFrames = glslMin(n + T(1), P.temporal_max_frames);
}

}  // namespace sao::cpu::detail
