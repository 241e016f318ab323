// The visibility estimator's bent normal on the CPU reference (effect/cpu/sao_bent.h): the arc
// moment's closed form against numeric integration; G inverted by bisection; the visible runs'
// measure against the bits; an open hemisphere's cosine-weighted mean direction is the normal and a
// hemisphere with a wall through V bends by atan(2/pi) = 32.5 degrees from it (closed forms
// integrated over many slice directions); a fully occluded pixel keeps its normal.
#include <cmath>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "sao_bent.h"

namespace sao::test {
namespace {

using cpu::detail::arcMomentFromZero;
using cpu::detail::azimuthRateScale;
using cpu::detail::bentNormal;
using cpu::detail::Block;
using cpu::detail::dot;
using cpu::detail::forEachVisibleRun;
using cpu::detail::Slice;
using cpu::detail::sliceAngle;
using cpu::detail::sliceBentMoment;
using cpu::detail::sliceGAt;
using cpu::detail::sliceSetup;
using cpu::detail::Vec3;

constexpr double kPi = 3.14159265358979323846;

// A block whose slices' screen direction u is their e (V = +z, proj_info x = y = 1).
template <typename T = double>
Block<T> block() {
  gen::SaoParams p{};
  p.proj_info = {1.0f, 1.0f, 0.0f, 0.0f};
  return Block<T>(p);
}

const Vec3<double> kV{0.0, 0.0, 1.0};

Vec3<double> unit(double x, double y, double z) {
  const double l = std::sqrt(x * x + y * y + z * z);
  return {x / l, y / l, z / l};
}

// The slice with e = (cos phi, sin phi, 0) for the normal n.
Slice<double> sliceAt(double phi, Vec3<double> n) {
  return sliceSetup(std::cos(phi), std::sin(phi), kV, n, block(), azimuthRateScale(kV, block()));
}

double angleBetween(Vec3<double> a, Vec3<double> b) {
  return std::acos(std::clamp(dot(a, b), -1.0, 1.0));
}

TEST(BentNormal, ArcMomentIsTheIntegral) {
  for (const Vec3<double> n : {unit(0, 0, 1), unit(0.6, 0.1, 0.8), unit(-0.9, 0.3, 0.2), unit(0.2, -0.5, 0.6)}) {
    const Slice<double> sl = sliceAt(0.3, n);
    for (const auto& [t0, t1] : {std::pair{sl.lo, sl.hi}, std::pair{sl.lo, 0.0}, std::pair{0.2, sl.hi},
                                std::pair{sl.lo + 0.3, sl.hi - 0.4}, std::pair{-0.05, 0.07}}) {
      // Midpoint rule over the slice's measure cos(theta - gamma) |sin(theta)| (cos and sin of
      // gamma as the slice holds them: gamma itself is the polynomial atan's, 1e-7 rad off).
      const int steps = 200000;
      double e = 0, v = 0;
      for (int i = 0; i < steps; ++i) {
        const double t = t0 + (t1 - t0) * (i + 0.5) / steps;
        const double cosToN = std::cos(t) * sl.cosGamma + std::sin(t) * sl.sinGamma;
        const double w = cosToN * std::abs(std::sin(t)) * (t1 - t0) / steps;
        e += std::sin(t) * w;
        v += std::cos(t) * w;
      }
      double e0, v0, e1, v1;
      arcMomentFromZero(sl, t0, e0, v0);
      arcMomentFromZero(sl, t1, e1, v1);
      EXPECT_NEAR(e1 - e0, e, 1e-9) << "gamma " << sl.gamma << " [" << t0 << ", " << t1 << "]";
      EXPECT_NEAR(v1 - v0, v, 1e-9) << "gamma " << sl.gamma << " [" << t0 << ", " << t1 << "]";
    }
  }
}

TEST(BentNormal, SliceAngleInvertsG) {
  for (const Vec3<double> n : {unit(0, 0, 1), unit(0.7, 0.0, 0.7), unit(-0.95, 0.1, 0.1)}) {
    const Slice<double> sl = sliceAt(0.0, n);
    const double range = 1.0 / sl.invRange;
    double previous = sl.lo;
    for (int k = 1; k < 32; ++k) {
      const double u = k / 32.0;
      const double theta = sliceAngle(sl, u);
      EXPECT_NEAR((sliceGAt(sl, theta) - sl.gLo) / range, u, 1e-4) << "gamma " << sl.gamma << " u " << u;
      EXPECT_GT(theta, previous);
      previous = theta;
    }
    EXPECT_EQ(sliceAngle(sl, 0.0), sl.lo);
    EXPECT_EQ(sliceAngle(sl, 1.0), sl.hi);
  }
}

// The visible runs' measure (the arcs' G) is the share of clear bits, for any mask.
TEST(BentNormal, VisibleRunsCoverTheClearBits) {
  std::mt19937 rng(7);
  const Slice<double> sl = sliceAt(1.1, unit(0.4, -0.3, 0.8));
  const double range = 1.0 / sl.invRange;
  for (int trial = 0; trial < 200; ++trial) {
    const std::uint32_t bits = std::uint32_t(rng());
    double measure = 0;
    int covered = 0;  // the runs' bits, which must be exactly the clear ones
    forEachVisibleRun(bits, [&](int b0, int b1) {
      measure += sliceGAt(sl, sliceAngle(sl, b1 / 32.0)) - sliceGAt(sl, sliceAngle(sl, b0 / 32.0));
      covered += b1 - b0;
    });
    EXPECT_EQ(covered, 32 - std::popcount(bits)) << std::hex << bits;
    EXPECT_NEAR(measure / range, (32 - std::popcount(bits)) / 32.0, 1e-4) << std::hex << bits;
  }
}

// Slices at K evenly spread screen directions integrate the hemisphere exactly in phi.
Vec3<double> bentOverSlices(Vec3<double> n, std::uint32_t (*bitsOf)(const Slice<double>&)) {
  const int K = 512;
  Vec3<double> sum{0, 0, 0};
  for (int k = 0; k < K; ++k) {
    const Slice<double> sl = sliceAt((k + 0.5) * kPi / K, n);
    const Vec3<double> m = sliceBentMoment(sl, kV, bitsOf(sl));
    sum = {sum.x + m.x, sum.y + m.y, sum.z + m.z};
  }
  return bentNormal(sum, n);
}

TEST(BentNormal, AnOpenHemisphereBendsToTheNormal) {
  for (const Vec3<double> n : {unit(0, 0, 1), unit(0.5, 0.2, 0.8), unit(-0.3, 0.6, 0.5), unit(0.9, 0.0, 0.3)}) {
    const Vec3<double> b = bentOverSlices(n, [](const Slice<double>&) { return 0u; });
    EXPECT_LT(angleBetween(b, n), 1e-3) << n.x << " " << n.y << " " << n.z;
  }
}

// n = V, a wall through V occluding every ray with x > 0: the cosine-weighted mean of the half
// hemisphere x < 0 is (-4/(3 pi), 0, 2/3) over its weight 1/2, atan(2/pi) = 32.48 degrees from n.
// In each slice (gamma = 0) the wall is at theta = 0, slice position 1/2: bits 16..31 (theta > 0,
// towards e) where e.x > 0, bits 0..15 where e.x < 0.
TEST(BentNormal, AWallThroughTheViewDirectionBendsByAtanTwoOverPi) {
  const Vec3<double> b = bentOverSlices(kV, [](const Slice<double>& sl) {
    return sl.e.x > 0 ? 0xFFFF0000u : 0x0000FFFFu;
  });
  EXPECT_NEAR(angleBetween(b, kV), std::atan(2.0 / kPi), 1e-3);
  EXPECT_LT(b.x, 0.0);
  EXPECT_NEAR(b.y, 0.0, 1e-9);
}

TEST(BentNormal, AFullyOccludedPixelKeepsItsNormal) {
  const Vec3<double> n = unit(0.3, 0.1, 0.9);
  const Slice<double> sl = sliceAt(0.4, n);
  const Vec3<double> m = sliceBentMoment(sl, kV, 0xFFFFFFFFu);
  EXPECT_EQ(m.x, 0.0);
  EXPECT_EQ(m.y, 0.0);
  EXPECT_EQ(m.z, 0.0);
  const Vec3<double> b = bentNormal(m, n);
  EXPECT_EQ(b.x, n.x);
  EXPECT_EQ(b.y, n.y);
  EXPECT_EQ(b.z, n.z);
}

// float follows double to the bisection's precision (the GPU's float path).
TEST(BentNormal, FloatFollowsDouble) {
  const Vec3<double> nd = unit(0.5, 0.2, 0.8);
  const Vec3<float> nf{float(nd.x), float(nd.y), float(nd.z)};
  const Block<float> bf = block<float>();
  for (const std::uint32_t bits : {0u, 0x0000FFF0u, 0xF00F00F0u, 0x7FFFFFFEu}) {
    const double phi = 0.7;
    const Vec3<double> md = sliceBentMoment(sliceAt(phi, nd), kV, bits);
    const Vec3<float> mf = sliceBentMoment(sliceSetup(float(std::cos(phi)), float(std::sin(phi)), Vec3<float>{0, 0, 1}, nf, bf,
                                                                      azimuthRateScale(Vec3<float>{0, 0, 1}, bf)),
                                           Vec3<float>{0, 0, 1}, bits);
    EXPECT_NEAR(mf.x, md.x, 2e-5) << std::hex << bits;
    EXPECT_NEAR(mf.y, md.y, 2e-5) << std::hex << bits;
    EXPECT_NEAR(mf.z, md.z, 2e-5) << std::hex << bits;
  }
}

}  // namespace
}  // namespace sao::test
