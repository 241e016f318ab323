// The visibility estimator's bent normal (issue 40, docs/effect-math.md 5.10): the cosine-weighted
// mean direction of the unoccluded rays, from the same slices and bitmasks as its A. In a slice the
// rays are w(theta) = sin(theta) e + cos(theta) V, weighted by the slice's measure
// L cos(theta - gamma) |sin(theta)| (the one whose integral G the bitmask's 32 bits split evenly);
// a visible run of bits is an arc [theta0, theta1] (its ends' slice positions through G inverted),
// and the arc's first moment has a closed form. The bent normal is the sum of the slices' moments,
// normalised. Templated on T like sao_visibility.h (double is the reference); the shader's
// sao_bent.glsl, function for function. visibilityOcclusion (sao_visibility.h, which includes this
// file at its end) sums sliceBentMoment over the slices under BENT_NORMALS.
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

#include "sao_visibility.h"

namespace sao::cpu::detail {

// G(theta) (sao_slice_g) with cos(2 theta - gamma) computed from theta.
template <typename T>
T sliceGAt(const Slice<T>& sl, T theta) {
  return sliceG(theta, std::cos(T(2) * theta - sl.gamma), sl.cosGamma, sl.sinGamma);
}

// The angle theta in [lo, hi] at slice position u (G(theta) = G(lo) + u (G(hi) - G(lo))): G rises
// on [lo, hi], so SAO_BENT_BISECTIONS halvings of it (pi / 2^16 = 5e-5 rad). u <= 0 and u >= 1 are
// the ends themselves (a run that starts or ends at the hemisphere's edge needs no search).
template <typename T>
T sliceAngle(const Slice<T>& sl, T u) {
  if (!(u > T(0))) return sl.lo;
  if (u >= T(1)) return sl.hi;
  const T g = sl.gLo + u / sl.invRange;
  T a = sl.lo, b = sl.hi;
  for (int i = 0; i < gen::SAO_BENT_BISECTIONS; ++i) {
    const T mid = (a + b) * T(0.5);
    if (sliceGAt(sl, mid) < g) a = mid;
    else b = mid;
  }
  return (a + b) * T(0.5);
}

// H(theta), the first moment from 0 to theta of w(theta) cos(theta - gamma) |sin(theta)| as its
// (e, V) components: for theta >= 0 the antiderivatives
//   e: cos(gamma) sin^3/3 + sin(gamma) (cos^3/3 - cos),   V: -cos(gamma) cos^3/3 + sin(gamma) sin^3/3
// less their value at 0 (-2 sin(gamma)/3, -cos(gamma)/3); |sin| = -sin below 0 flips the sign, so
// H(theta) = sign(theta) (F(theta) - F(0)) and an arc's moment is H(theta1) - H(theta0) on either
// side of V or across it.
template <typename T>
void arcMomentFromZero(const Slice<T>& sl, T theta, T& e, T& v) {
  const T s = std::sin(theta), c = std::cos(theta);
  const T s3 = s * s * s, c3 = c * c * c;
  const T sign = theta >= T(0) ? T(1) : T(-1);
  e = sign * (sl.cosGamma * s3 / T(3) + sl.sinGamma * (c3 / T(3) - c + T(2) / T(3)));
  v = sign * (sl.cosGamma * (T(1) - c3) / T(3) + sl.sinGamma * s3 / T(3));
}

// Calls run(b0, b1) for each run [b0, b1) of clear bits of `bits` (at most 16), lowest first.
template <typename Run>
void forEachVisibleRun(std::uint32_t bits, Run run) {
  std::uint32_t visible = ~bits;
  while (visible != 0u) {
    const int b0 = std::countr_zero(visible);
    const std::uint32_t above = ~visible & ~bitsBelow(b0);  // occluded bits from b0 up
    const int b1 = above != 0u ? std::countr_zero(above) : 32;
    run(b0, b1);
    visible &= ~bitsBelow(b1);
  }
}

// The first moment of one slice's unoccluded rays (the bits not set in `bits`), in camera space,
// times the slice's L and azimuth rate (weight over range: slices add as the estimator's weights do);
// zero when every bit is set.
template <typename T>
Vec3<T> sliceBentMoment(const Slice<T>& sl, Vec3<T> V, std::uint32_t bits) {
  T me = T(0), mv = T(0);
  forEachVisibleRun(bits, [&](int b0, int b1) {
    T e0, v0, e1, v1;
    arcMomentFromZero(sl, sliceAngle(sl, T(b0) * T(0.03125)), e0, v0);
    arcMomentFromZero(sl, sliceAngle(sl, T(b1) * T(0.03125)), e1, v1);
    me += e1 - e0;
    mv += v1 - v0;
  });
  const T w = sl.weight * sl.invRange;
  return {(sl.e.x * me + V.x * mv) * w, (sl.e.y * me + V.y * mv) * w, (sl.e.z * me + V.z * mv) * w};
}

// The bent normal from the slices' summed moments: their direction, or the normal n where nothing
// is visible (a fully occluded pixel has no mean unoccluded direction).
template <typename T>
Vec3<T> bentNormal(Vec3<T> moments, Vec3<T> n) {
  const T l2 = dot(moments, moments);
  return l2 > T(0) ? scale(moments, inverseSqrt(l2)) : n;
}

}  // namespace sao::cpu::detail
