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

// sao_atan2: atan(y, x) from basic arithmetic, operation for operation (Float: the shader's
// constants; Double: the same polynomial, error below 2e-7 rad, in double).
template <typename T>
T atan2Poly(T y, T x) {
  const T ax = std::abs(x), ay = std::abs(y);
  const T t = glslMin(ax, ay) / glslMax(ax, ay);
  const bool reduce = t > T(0.414213562f);
  const T r = reduce ? (t - T(1)) / (t + T(1)) : t;
  const T z = r * r;
  const T p = (((T(0.0805374449538f) * z - T(0.138776856032f)) * z + T(0.199777106478f)) * z - T(0.333329491539f)) * z * r + r;
  const T a = reduce ? T(0.785398163f) + p : p;
  const T b = (ay > ax) ? T(1.57079633f) - a : a;
  const T c = (x < T(0)) ? T(3.14159265f) - b : b;
  return (y < T(0)) ? -c : c;
}

// SaoSlice.
template <typename T>
struct Slice {
  Vec3<T> n{T(0), T(0), T(0)}, e{T(0), T(0), T(0)}, a{T(0), T(0), T(0)}, shear{T(0), T(0), T(0)};
  T gamma = T(0), cosGamma = T(1), sinGamma = T(0), lo = T(0), hi = T(0), gLo = T(0), invRange = T(0), weight = T(0);
};

// sao_slice_g (c2 = cos(2x - gamma)).
template <typename T>
T sliceG(T x, T c2, T cosGamma, T sinGamma) {
  const T s = (x >= T(0)) ? T(1) : T(-1);
  return s * (((cosGamma - c2) + (T(2) * x) * sinGamma) * T(0.25));
}

// sao_azimuth_rate_scale: |f1 x f2|, once a pixel.
template <typename T>
T azimuthRateScale(Vec3<T> V, const Block<T>& P) {
  const Vec3<T> f1 = Vec3<T>{P.proj_info.x, T(0), T(0)} - scale(V, V.x * P.proj_info.x);
  const Vec3<T> f2 = Vec3<T>{T(0), P.proj_info.y, T(0)} - scale(V, V.y * P.proj_info.y);
  const Vec3<T> c = cross(f1, f2);
  return std::sqrt(dot(c, c));
}

// sao_slice_setup.
template <typename T>
Slice<T> sliceSetup(T ux, T uy, Vec3<T> V, Vec3<T> n, const Block<T>& P, T azimuthRateScale) {
  Slice<T> sl;
  sl.n = n;
  const Vec3<T> D{ux * P.proj_info.x, uy * P.proj_info.y, T(0)};
  const Vec3<T> f = D - scale(V, dot(D, V));
  sl.e = normalize(f);
  const Vec3<T> a = normalize(cross(sl.e, V));
  const T na = dot(n, a);
  const Vec3<T> np = n - scale(a, na);
  const T L = std::sqrt(dot(np, np));
  sl.a = a;
  sl.shear = (L > T(0)) ? scale(a - scale(n, na), T(1) / (L * L)) : Vec3<T>{T(0), T(0), T(0)};
  const T npe = dot(np, sl.e), npv = dot(np, V);
  const bool facing = npv > T(0);
  sl.gamma = (L > T(0)) ? std::clamp(atan2Poly(npe, npv), -kVisHalfPi<T>, kVisHalfPi<T>) : T(0);
  sl.cosGamma = (L > T(0)) ? (facing ? npv / L : T(0)) : T(1);
  sl.sinGamma = (L > T(0)) ? (facing ? npe / L : (npe >= T(0) ? T(1) : T(-1))) : T(0);
  sl.lo = sl.gamma - kVisHalfPi<T>;
  sl.hi = sl.gamma + kVisHalfPi<T>;
  sl.gLo = sliceG(sl.lo, -sl.cosGamma, sl.cosGamma, sl.sinGamma);
  const T range = sliceG(sl.hi, -sl.cosGamma, sl.cosGamma, sl.sinGamma) - sl.gLo;
  sl.invRange = T(1) / range;
  const T rate = azimuthRateScale / dot(f, f);
  sl.weight = L * range * rate;
  return sl;
}

// sao_slice_position.
template <typename T>
T slicePosition(const Slice<T>& sl, T theta, T pe, T pv) {
  const T c2 = ((pv * pv - pe * pe) * sl.cosGamma + (T(2) * pv * pe) * sl.sinGamma) / (pe * pe + pv * pv);
  const bool inside = theta > sl.lo && theta < sl.hi;
  return sliceG(std::clamp(theta, sl.lo, sl.hi), inside ? c2 : -sl.cosGamma, sl.cosGamma, sl.sinGamma);
}

// sao_bits_below, sao_bits_between.
inline std::uint32_t bitsBelow(int b) { return b >= 32 ? 0xFFFFFFFFu : ((1u << unsigned(b)) - 1u); }

template <typename T>
std::uint32_t bitsBetween(T u1, T u2) {
  const T x1 = T(32) * u1 + T(0.5), x2 = T(32) * u2 + T(0.5);
  const int b1 = static_cast<int>(std::floor(x1 > T(0) ? glslMin(x1, T(32)) : T(0)));  // NaN: 0
  const int b2 = static_cast<int>(std::floor(x2 > T(0) ? glslMin(x2, T(32)) : T(0)));
  return bitsBelow(b2) & ~bitsBelow(b1);
}

// SaoSlab.
template <typename T>
struct Slab {
  bool valid = false;
  T u1 = T(0), u2 = T(0), fe = T(0), fv = T(0);
  T t = T(0);  // its thickness
};

// sao_slab.
template <typename T>
Slab<T> slab(const Slice<T>& sl, Vec3<T> C, Vec3<T> V, T qx, T qy, T z, T thickness, const Block<T>& P) {
  Slab<T> s;
  s.t = thickness;
  if (isSky(z)) return s;
  const Vec3<T> S = position(qx, qy, z, P);
  const T k = T(1) + P.depth_tolerance;
  Vec3<T> F, B;
  if (P.ortho != 0) {
    F = {S.x, S.y, z * k};
    B = {S.x, S.y, z * k - thickness};
  } else {
    F = scale(S, k);
    B = scale(S, k + thickness / -z);
  }
  Vec3<T> f = F - C;
  if (dot(f, f) > P.radius2) return s;
  Vec3<T> b = B - C;
  const bool below = dot(f, sl.n) <= T(0) && dot(b, sl.n) <= T(0);  // blocks nothing (sao_slab)
  f = f - scale(sl.shear, dot(f, sl.a));  // into the slice along the tangent plane
  b = b - scale(sl.shear, dot(b, sl.a));
  const T fe = dot(f, sl.e), fv = dot(f, V);
  if (below) {
    const bool beyondHi = fe > T(0);
    s.valid = beyondHi == (dot(b, sl.e) > T(0));
    s.u1 = s.u2 = beyondHi ? T(1) : T(0);
    s.fe = fe;
    s.fv = fv;
    return s;
  }
  const T be = dot(b, sl.e), bv = dot(b, V);
  const T tf = atan2Poly(fe, fv);
  const T tb = atan2Poly(be, bv);
  if (std::abs(tf - tb) > kVisPi<T>) return s;
  const T gf = slicePosition(sl, tf, fe, fv);
  const T gb = slicePosition(sl, tb, be, bv);
  s.valid = true;
  s.u1 = (glslMin(gf, gb) - sl.gLo) * sl.invRange;
  s.u2 = (glslMax(gf, gb) - sl.gLo) * sl.invRange;
  s.fe = fe;
  s.fv = fv;
  return s;
}

// sao_slab_bits.
template <typename T>
std::uint32_t slabBits(const Slice<T>& sl, Vec3<T> C, Vec3<T> V, T qx, T qy, T z, const Block<T>& P) {
  const Slab<T> s = slab(sl, C, V, qx, qy, z, P.thickness, P);
  return s.valid ? bitsBetween(s.u1, s.u2) : 0u;
}

// SAO_JOIN_SLOPE.
template <typename T>
constexpr T kJoinSlope = T(4);

// sao_joined_bits.
template <typename T>
std::uint32_t joinedBits(const Slab<T>& s, const Slab<T>& prev) {
  const T dv = std::abs(s.fv - prev.fv);
  const T de = std::abs(s.fe - prev.fe);
  const bool sameSide = (s.fe > T(0)) == (prev.fe > T(0));  // a truncated tap may cross C's view line
  const bool joined = prev.valid && sameSide && dv <= glslMin(s.t, prev.t) + kJoinSlope<T> * de;
  const T u1 = joined ? glslMin(s.u1, prev.u1) : s.u1;
  const T u2 = joined ? glslMax(s.u2, prev.u2) : s.u2;
  return s.valid ? bitsBetween(u1, u2) : 0u;
}

// The rotated-grid walk sao_mip_source's closed form replaces (tests compare the two).
inline void mipSourceWalk(int& x, int& y, int m, int w0, int h0) {
  for (int k = m; k >= 1; --k) {
    int sx, sy;
    rotatedGridSource(x, y, std::max(w0 >> (k - 1), 1), std::max(h0 >> (k - 1), 1), sx, sy);
    x = sx;
    y = sy;
  }
}

// sao_mip_source: the level-0 texel (x, y) whose z level-m texel (x, y) holds, in closed form
// (exact where w0, h0 >= 2^m; clamped to the image otherwise).
inline void mipSource(int& x, int& y, int m, int w0, int h0) {
  const std::uint32_t first = m == 0 ? 0u : (0xAAAAAAAAu >> unsigned(32 - m));
  const std::uint32_t second = ((1u << unsigned(m)) - 1u) ^ first;
  const std::uint32_t x0 = std::uint32_t(x) & 1u, y0 = std::uint32_t(y) & 1u;
  const std::uint32_t sx = (std::uint32_t(x) << unsigned(m)) | ((y0 ^ 1u) * first) | (x0 * second);
  const std::uint32_t sy = (std::uint32_t(y) << unsigned(m)) | ((x0 ^ 1u) * first) | (y0 * second);
  x = std::min(int(sx), w0 - 1);
  y = std::min(int(sy), h0 - 1);
}

// sao_run_share (thickness_model 1, the width pass): the share of thickness of texel (px, py) of csz
// level m (zm; level 0 is w0 x h0) with z (not sky) along axis (ax, ay) = (1, 0) or (0, 1), from
// its run of continuous depth walked on level m: SAO_WIDTH_REACH of the level's texels each side,
// continuity |dz| <= SAO_WIDTH_JUMP * 2^m * |z| (per level-0 texel), the ends at the level-0 texels
// their z came from (mipSource), a texel's footprint 2^m level-0 texels. Level 0 is the width pass's
// bit scans (sao_width_band_share), a level above its walk (sao_width_level_share). onRead(side, k,
// x, y) sees each texel the walk fetches (side 0 towards +axis; k = 1 .. SAO_WIDTH_REACH; x, y
// clamped to the level): the traffic model's trace of the walk (width_trace.h).
struct NoWalkReads {
  void operator()(int, int, int, int) const {}
};
template <typename T, typename OnRead = NoWalkReads>
T runShare(const Image<T>& zm, int m, int w0, int h0, int px, int py, T z, int ax, int ay, const Block<T>& P,
           OnRead&& onRead = {}) {
  const T span = T(1 << m);
  bool wide = false;
  int ex[2], ey[2];
  T ez[2];
  for (int side = 0; side < 2; ++side) {
    const int dx = side == 0 ? ax : -ax, dy = side == 0 ? ay : -ay;
    int lx = px, ly = py;
    T zp = z;
    bool walking = true;
    for (int k = 1; k <= gen::SAO_WIDTH_REACH && walking; ++k) {
      const int qx = px + k * dx, qy = py + k * dy;
      const bool inside = qx >= 0 && qy >= 0 && qx < zm.w && qy < zm.h;
      wide = wide || !inside;
      const int cx = std::clamp(qx, 0, zm.w - 1), cy = std::clamp(qy, 0, zm.h - 1);
      onRead(side, k, cx, cy);
      const T zq = zm.at(cx, cy);
      const T dz = std::abs(zq - zp);
      walking = inside && !isSky(zq) && dz <= T(gen::SAO_WIDTH_JUMP) * span * std::abs(zq);
      if (walking) lx = qx, ly = qy, zp = zq;
    }
    wide = wide || walking;
    mipSource(lx, ly, m, w0, h0);
    ex[side] = lx, ey[side] = ly, ez[side] = zp;
  }
  const Vec3<T> a = position(T(ex[0]) + T(0.5), T(ey[0]) + T(0.5), ez[0], P);
  const Vec3<T> b = position(T(ex[1]) + T(0.5), T(ey[1]) + T(0.5), ez[1], P);
  const Vec3<T> d = a - b;
  const T scale = ax != 0 ? std::abs(P.proj_info.x) : std::abs(P.proj_info.y);
  const T footprint = scale * ((P.ortho != 0) ? T(1) : std::abs(z)) * span;
  const T width = std::sqrt(dot(d, d)) + footprint;
  const T t = glslMin(P.thickness, glslMax(P.thickness_min, T(gen::SAO_WIDTH_SCALE) * width));
  return wide ? T(1) : t / P.thickness;
}

// Level 0's run share (runShare with m = 0).
template <typename T>
T runShare(const Image<T>& z0, int px, int py, T z, int ax, int ay, const Block<T>& P) {
  return runShare(z0, 0, z0.w, z0.h, px, py, z, ax, ay, P);
}

// sao_tap_thickness (thickness_model 1, a tap): the thickness of the surface a tap sees along
// (dx, dy) (unit) from its csz_share texel's shares along x and y.
template <typename T>
T tapThickness(T shareX, T shareY, T dx, T dy, T thickness) {
  const T fx = shareX / glslMax(std::abs(dx), T(1.0e-6f));
  const T fy = shareY / glslMax(std::abs(dy), T(1.0e-6f));
  return thickness * glslMin(T(1), glslMin(fx, fy));
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

// sao_slice_bent_moment (sao_bent.h, included at the end of this file): declared ahead, as the shader does.
template <typename T>
Vec3<T> sliceBentMoment(const Slice<T>& sl, Vec3<T> V, std::uint32_t bits);

// sao_visibility_occlusion: the occlusion 1 - V of the pixel at csz texel (cx, cy). csz2 is read
// only with twoLayer; with cszShare (THICKNESS_FROM_WIDTH: width_resolve's chain, z and the packed
// shares) the taps read their z and shares from it instead of csz; `tapCount` is the block's
// samples (the shader's SAO_TAP_COUNT). With
// `moment` (BENT_NORMALS) the slices' first moments of their unoccluded rays are summed into it.
template <typename T>
T visibilityOcclusion(const std::vector<Image<T>>& csz, const std::vector<Image<T>>& csz2,
                      const std::vector<Image<T>>* cszShare, bool twoLayer, bool hierarchy, int cx, int cy,
                      Vec3<T> C, Vec3<T> n, T r_px, std::uint32_t phase, T xi, int tapCount, const Block<T>& P,
                      Vec3<T>* moment = nullptr) {
  if (moment) *moment = Vec3<T>{T(0), T(0), T(0)};
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
  Slab<T> prev;  // the side's previous tap's slab (first layer)
  T ux = T(1), uy = T(0);
  const T rateScale = azimuthRateScale(V, P);
  for (int i = 0; i < used; ++i) {
    const int k = i / perSlice;
    const int r = i - k * perSlice;
    if (r == 0) {
      turnDirection<T>(phase + std::uint32_t(k) * P.slice_turn, ux, uy);
      sl = sliceSetup(ux, uy, V, n, P, rateScale);
      bits = 0u;
    }
    const bool negative = r >= m;
    const int j = negative ? r - m : r;
    if (j == 0) prev.valid = false;  // a new side: nothing to join to
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
      if (sx != cx || sy != cy) {  // a coarse texel may hold the centre's own z
        const T qx = T(sx) + T(0.5), qy = T(sy) + T(0.5);
        // One fetch: the tap's z from csz, or from csz_share beside its shares.
        const Image<T>& zImage = cszShare ? (*cszShare)[std::size_t(lvl)] : csz[std::size_t(lvl)];
        const T z = zImage.at(mx, my, 0);
        T t = P.thickness;
        if (cszShare) {
          float shareX = 0.0f, shareY = 0.0f;
          unpackShares(float(zImage.at(mx, my, 1)), shareX, shareY);
          t = tapThickness(T(shareX), T(shareY), dx, dy, P.thickness);
        }
        const Slab<T> s = slab(sl, C, V, qx, qy, z, t, P);
        bits |= joinedBits(s, prev);
        prev = s;  // sky or a sample beyond r breaks the chain
        if (twoLayer) bits |= slabBits(sl, C, V, qx, qy, csz2[std::size_t(lvl)].at(mx, my), P);
      }
    }
    if (r == perSlice - 1) {
      occluded += sl.weight * (T(std::popcount(bits)) * T(0.03125));
      weights += sl.weight;
      if (moment) {
        const Vec3<T> b = sliceBentMoment(sl, V, bits);
        *moment = Vec3<T>{moment->x + b.x, moment->y + b.y, moment->z + b.z};
      }
    }
  }
  return (weights > T(0)) ? occluded / weights : T(0);
}

}  // namespace sao::cpu::detail

// The bent normal's functions (sliceBentMoment above): after this file's, which they use.
#include "sao_bent.h"
