// sao_visibility.glsl in C++ (the visibility estimator, ESTIMATOR 1), one function each, in the
// shader's order of operations, templated on T like sao_math.h (float mimics the GPU, double is the
// reference). atan, cos and sin are the C library's: GPUs' are not correctly rounded, so float
// agrees with the GPU to the agreement tests' bounds, not bit for bit. Built with -ffp-contract=off.
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sao_math.h"

namespace sao::cpu::detail {

template <typename T>
constexpr T kVisPi = T(3.14159265358979323846);
template <typename T>
constexpr T kVisHalfPi = T(1.57079632679489661923);

template <typename T>
Vec3<T> scale(Vec3<T> v, T s) {
  return {v.x * s, v.y * s, v.z * s};
}
// GLSL normalize: v * inversesqrt(dot(v, v)).
template <typename T>
Vec3<T> normalize(Vec3<T> v) {
  return scale(v, inverseSqrt(dot(v, v)));
}

// SaoSlice.
template <typename T>
struct Slice {
  Vec3<T> e{T(0), T(0), T(0)}, a{T(0), T(0), T(0)}, shear{T(0), T(0), T(0)};
  T gamma = T(0), cosGamma = T(1), sinGamma = T(0), lo = T(0), hi = T(0), gLo = T(0), invRange = T(0), weight = T(0);
};

// sao_slice_g.
template <typename T>
T sliceG(T x, T gamma, T cosGamma, T sinGamma) {
  const T s = (x >= T(0)) ? T(1) : T(-1);
  return s * (((cosGamma - std::cos(T(2) * x - gamma)) + (T(2) * x) * sinGamma) * T(0.25));
}

// sao_slice_setup.
template <typename T>
Slice<T> sliceSetup(T ux, T uy, Vec3<T> V, Vec3<T> n, const Block<T>& P) {
  Slice<T> sl;
  const Vec3<T> D{ux * P.proj_info.x, uy * P.proj_info.y, T(0)};
  sl.e = normalize(D - scale(V, dot(D, V)));
  const Vec3<T> a = normalize(cross(sl.e, V));
  const T na = dot(n, a);
  const Vec3<T> np = n - scale(a, na);
  const T L = std::sqrt(dot(np, np));
  sl.a = a;
  sl.shear = (L > T(0)) ? scale(a - scale(n, na), T(1) / (L * L)) : Vec3<T>{T(0), T(0), T(0)};
  const T g = std::atan2(dot(np, sl.e), dot(np, V));
  sl.gamma = (L > T(0)) ? std::clamp(g, -kVisHalfPi<T>, kVisHalfPi<T>) : T(0);
  sl.cosGamma = std::cos(sl.gamma);
  sl.sinGamma = std::sin(sl.gamma);
  sl.lo = sl.gamma - kVisHalfPi<T>;
  sl.hi = sl.gamma + kVisHalfPi<T>;
  sl.gLo = sliceG(sl.lo, sl.gamma, sl.cosGamma, sl.sinGamma);
  const T range = sliceG(sl.hi, sl.gamma, sl.cosGamma, sl.sinGamma) - sl.gLo;
  sl.invRange = T(1) / range;
  sl.weight = L * range;
  return sl;
}

// sao_bits_below, sao_bits_between.
inline std::uint32_t bitsBelow(int b) { return b >= 32 ? 0xFFFFFFFFu : ((1u << unsigned(b)) - 1u); }

template <typename T>
std::uint32_t bitsBetween(T u1, T u2) {
  const int b1 = std::clamp(static_cast<int>(std::floor(T(32) * u1 + T(0.5))), 0, 32);
  const int b2 = std::clamp(static_cast<int>(std::floor(T(32) * u2 + T(0.5))), 0, 32);
  return bitsBelow(b2) & ~bitsBelow(b1);
}

// sao_slab_bits.
template <typename T>
std::uint32_t slabBits(const Slice<T>& sl, Vec3<T> C, Vec3<T> V, T qx, T qy, T z, const Block<T>& P) {
  if (isSky(z)) return 0u;
  const Vec3<T> S = position(qx, qy, z, P);
  const T k = T(1) + P.depth_tolerance;
  Vec3<T> F, B;
  if (P.ortho != 0) {
    F = {S.x, S.y, z * k};
    B = {S.x, S.y, z * k - P.thickness};
  } else {
    F = scale(S, k);
    B = scale(S, k + P.thickness / -z);
  }
  Vec3<T> f = F - C;
  if (dot(f, f) > P.radius2) return 0u;
  Vec3<T> b = B - C;
  f = f - scale(sl.shear, dot(f, sl.a));  // into the slice along the tangent plane
  b = b - scale(sl.shear, dot(b, sl.a));
  const T tf = std::atan2(dot(f, sl.e), dot(f, V));
  const T tb = std::atan2(dot(b, sl.e), dot(b, V));
  T t1 = glslMin(tf, tb);
  T t2 = glslMax(tf, tb);
  if (t2 - t1 > kVisPi<T>) return 0u;
  t1 = std::clamp(t1, sl.lo, sl.hi);
  t2 = std::clamp(t2, sl.lo, sl.hi);
  const T u1 = (sliceG(t1, sl.gamma, sl.cosGamma, sl.sinGamma) - sl.gLo) * sl.invRange;
  const T u2 = (sliceG(t2, sl.gamma, sl.cosGamma, sl.sinGamma) - sl.gLo) * sl.invRange;
  return bitsBetween(u1, u2);
}

// sao_mip_source: the level-0 texel (x, y) whose z level-m texel (x, y) holds.
inline void mipSource(int& x, int& y, int m, int w0, int h0) {
  for (int k = gen::SAO_MAX_MIP_LEVELS - 1; k >= 1; --k)
    if (k <= m) {
      int sx, sy;
      rotatedGridSource(x, y, std::max(w0 >> (k - 1), 1), std::max(h0 >> (k - 1), 1), sx, sy);
      x = sx;
      y = sy;
    }
}

// sao_pixel_jitter: 24 bits of a hash of the AO pixel, in [0, 1) (exact in float and double).
inline std::uint32_t pixelJitterBits(std::uint32_t x, std::uint32_t y) {
  std::uint32_t h = (x * 0x8DA6B343u) ^ (y * 0xD8163841u);
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  return h >> 8;
}

// The radial jitter xi = fract(frame_alpha_offset + the pixel's jitter), as ao_sample computes it
// (a float sum in the shader: Float rounds the same way, Double keeps it exact).
template <typename T>
T radialJitter(std::uint32_t px, std::uint32_t py, const Block<T>& P) {
  const T x = P.frame_alpha_offset + T(pixelJitterBits(px, py)) * T(5.9604644775390625e-08);
  return x - std::floor(x);
}

// sao_visibility_occlusion: the occlusion 1 - V of the pixel at csz texel (cx, cy). csz2 is read
// only with twoLayer; `tapCount` is the block's samples (the shader's SAO_TAP_COUNT).
template <typename T>
T visibilityOcclusion(const std::vector<Image<T>>& csz, const std::vector<Image<T>>& csz2, bool twoLayer,
                      bool hierarchy, int cx, int cy, Vec3<T> C, Vec3<T> n, T r_px, std::uint32_t phase, T xi,
                      int tapCount, const Block<T>& P) {
  const Image<T>& z0 = csz[0];
  const Vec3<T> V = (P.ortho != 0) ? Vec3<T>{T(0), T(0), T(1)} : normalize(Vec3<T>{-C.x, -C.y, -C.z});
  const int ns = std::clamp(P.slices, 1, gen::SAO_MAX_SLICES);
  const int m = std::max(1, tapCount / (2 * ns));
  const int perSlice = 2 * m;
  const int used = ns * perSlice;
  const T invM = T(1) / T(m);
  T occluded = T(0);
  T weights = T(0);
  Slice<T> sl;
  std::uint32_t bits = 0u;
  T ux = T(1), uy = T(0);
  for (int i = 0; i < used; ++i) {
    const int k = i / perSlice;
    const int r = i - k * perSlice;
    if (r == 0) {
      turnDirection<T>(phase + std::uint32_t(k) * P.slice_turn, ux, uy);
      sl = sliceSetup(ux, uy, V, n, P);
      bits = 0u;
    }
    const bool negative = r >= m;
    const int j = negative ? r - m : r;
    const T t = (T(j) + xi) * invM;
    const T h = r_px * (t * t);
    const T dx = negative ? -ux : ux, dy = negative ? -uy : uy;
    const int tx = cx + static_cast<int>(h * dx);  // truncates toward zero
    const int ty = cy + static_cast<int>(h * dy);
    if (tx != cx || ty != cy) {
      const int lvl = hierarchy ? mipLevel(h, P.log_q, P.max_mip) : 0;
      const int mx = mipTexel(tx, lvl, z0.w), my = mipTexel(ty, lvl, z0.h);
      int sx = mx, sy = my;
      mipSource(sx, sy, lvl, z0.w, z0.h);
      const T qx = T(sx) + T(0.5), qy = T(sy) + T(0.5);
      bits |= slabBits(sl, C, V, qx, qy, csz[std::size_t(lvl)].at(mx, my), P);
      if (twoLayer) bits |= slabBits(sl, C, V, qx, qy, csz2[std::size_t(lvl)].at(mx, my), P);
    }
    if (r == perSlice - 1) {
      occluded += sl.weight * (T(std::popcount(bits)) * T(0.03125));
      weights += sl.weight;
    }
  }
  return (weights > T(0)) ? occluded / weights : T(0);
}

}  // namespace sao::cpu::detail
