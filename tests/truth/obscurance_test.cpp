// The AlchemyAO obscurance reference (raytrace::obscuranceAt, referenceObscurance): exact cases,
// a 90-degree crease against an independent quadrature of the integral, the effect's units,
// the clamp and contrast, determinism and thread-count independence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "sao/raytrace/raytrace.h"
#include "traced_view.h"

namespace {

using namespace sao;

std::unique_ptr<raytrace::RayScene> build(scenes::MeshBuilder& b) {
  std::unique_ptr<raytrace::RayScene> scene;
  EXPECT_TRUE(raytrace::RayScene::create(b.build(), scene).ok());
  return scene;
}

using truthtest::creaseMesh;

struct Quadrature {
  double mean = 0;      // the integral O
  double variance = 0;  // variance of one cosine-weighted ray's contribution c = f pi / cos
};

// O = (sigma/pi) Integral_hemisphere H(r - t) max(0, t cos + zC beta) / (t^2 + eps) dw for the
// point (0, 0, 0), n = +y, next to the wall x = -d, by the midpoint rule in (theta, phi); only
// directions with w.x < 0 can reach the wall. Independent of the ray tracer and its sampling.
Quadrature creaseQuadrature(double d, double r, double sigma, double beta, double eps, double zC) {
  const int nTheta = 3000, nPhi = 6000;
  const double dTheta = 0.5 * std::numbers::pi / nTheta, dPhi = std::numbers::pi / nPhi;
  double first = 0, second = 0;
  for (int i = 0; i < nTheta; ++i) {
    const double theta = (i + 0.5) * dTheta, cosT = std::cos(theta), sinT = std::sin(theta);
    for (int j = 0; j < nPhi; ++j) {
      const double phi = 0.5 * std::numbers::pi + (j + 0.5) * dPhi;  // (pi/2, 3pi/2): w.x < 0
      const double wx = sinT * std::cos(phi);
      const double t = d / -wx;
      if (!(t <= r)) continue;
      const double f = sigma / std::numbers::pi * std::max(0.0, t * cosT + zC * beta) / (t * t + eps);
      const double dw = sinT * dTheta * dPhi;
      first += f * dw;
      second += f * f * std::numbers::pi / cosT * dw;  // E[c^2] = Integral f^2 pi / cos dw
    }
  }
  return {first, second - first * first};
}

TEST(Obscurance, IsExactlyZeroWithNothingWithinTheRadius) {
  scenes::MeshBuilder b;
  b.box({-50, -0.1, -50}, {50, 0, 50});
  b.sphere({0, 3, 0}, 1.0, 32, 64);  // 2 m above the point: beyond r = 1.5
  auto scene = build(b);
  EXPECT_EQ(raytrace::obscuranceAt(*scene, {0, 0, 0}, {0, 1, 0}, -5.0, 1.5, 1.0, 0.02, 1e-4, 4000, 3, 1e-4), 0.0);
  EXPECT_GT(raytrace::obscuranceAt(*scene, {0, 0, 0}, {0, 1, 0}, -5.0, 2.5, 1.0, 0.02, 1e-4, 4000, 3, 1e-4), 0.0)
      << "the sphere counts once r reaches it";
}

TEST(Obscurance, ImageOfAnOpenPlaneIsExactlyOne) {
  scenes::MeshBuilder b;
  b.box({-500, -0.1, -500}, {500, 0, 500});
  truthtest::TracedView t;
  truthtest::traceFirstView({"plane", b.build(), {{"down", {0, 3, 2}, {0, 0, -1}, {0, 1, 0}, 1.0, 0.1}}}, 40, 30, 2,
                            1.0, t);
  if (HasFatalFailure()) return;
  raytrace::ObscuranceOptions o;
  o.radius = 2.0;
  o.rays = 64;
  FloatImage ao;
  ASSERT_TRUE(raytrace::referenceObscurance(*t.rays, t.camera, t.primary, t.scene.views[0], o, ao).ok());
  ASSERT_EQ(ao.extent, (Extent{40, 30}));
  for (float v : ao.data) ASSERT_EQ(v, 1.0f);
}

// A point on the floor 0.25 m from the wall: the ray-cast estimate against the quadrature, within
// 5 standard errors (from the quadrature's own variance) plus the quadrature's discretisation.
TEST(Obscurance, CreaseMatchesAnIndependentQuadrature) {
  const double d = 0.25, r = 1.0, eps = 1e-4, zC = -3.0;
  auto b = creaseMesh(d);
  auto scene = build(b);
  const std::uint32_t rays = 200000;
  for (double sigma : {1.0, 0.5})
    for (double beta : {0.0, 0.02}) {
      const Quadrature q = creaseQuadrature(d, r, sigma, beta, eps, zC);
      const double estimate = raytrace::obscuranceAt(*scene, {0, 0, 0}, {0, 1, 0}, zC, r, sigma, beta, eps, rays, 11, 1e-5);
      const double se = std::sqrt(q.variance / rays);
      std::printf("sigma %.2f beta %.2f: ray cast %.5f quadrature %.5f (standard error %.5f)\n", sigma, beta,
                  estimate, q.mean, se);
      EXPECT_GT(q.mean, 0.05) << "the case is not trivial";
      EXPECT_NEAR(estimate, q.mean, 5 * se + 2e-4 * q.mean) << "sigma " << sigma << " beta " << beta;
    }
  // The bias removes obscurance (the numerator loses |zC| beta), and the obscurance is linear in sigma.
  const Quadrature noBias = creaseQuadrature(d, r, 1.0, 0.0, eps, zC), biased = creaseQuadrature(d, r, 1.0, 0.02, eps, zC);
  EXPECT_LT(biased.mean, noBias.mean);
  EXPECT_NEAR(raytrace::obscuranceAt(*scene, {0, 0, 0}, {0, 1, 0}, zC, r, 2.0, 0.02, eps, 5000, 4, 1e-5),
              2.0 * raytrace::obscuranceAt(*scene, {0, 0, 0}, {0, 1, 0}, zC, r, 1.0, 0.02, eps, 5000, 4, 1e-5), 1e-12);
}

using CreaseImage = truthtest::TracedView;
using truthtest::traceCrease;

FloatImage obscuranceImage(const CreaseImage& c, raytrace::ObscuranceOptions o) {
  FloatImage ao;
  EXPECT_TRUE(raytrace::referenceObscurance(*c.rays, c.camera, c.primary, c.scene.views[0], o, ao).ok());
  return ao;
}

TEST(Obscurance, IsDeterministicAndIndependentOfThreads) {
  CreaseImage c;
  traceCrease(1.0, c);
  raytrace::ObscuranceOptions o;
  o.rays = 48;
  o.threads = 1;
  const FloatImage one = obscuranceImage(c, o);
  float darkest = 1;
  for (float v : one.data) darkest = std::min(darkest, v);
  EXPECT_LT(darkest, 0.8f) << "the corner is obscured";
  for (unsigned threads : {1u, 2u, 3u, 0u}) {
    o.threads = threads;
    const FloatImage again = obscuranceImage(c, o);
    ASSERT_EQ(again.data.size(), one.data.size());
    EXPECT_EQ(std::memcmp(again.data.data(), one.data.data(), one.data.size() * sizeof(float)), 0) << threads << " threads";
  }
  o.seed = 2;
  const FloatImage otherSeed = obscuranceImage(c, o);
  EXPECT_NE(std::memcmp(otherSeed.data.data(), one.data.data(), one.data.size() * sizeof(float)), 0) << "the seed matters";
}

// Settings are metres, the scene is in view units: a crease twice as large with
// metersToViewUnits = 2 gives the same image (up to the float rounding of the hits).
TEST(Obscurance, UsesTheEffectsUnits) {
  CreaseImage metres, halfMetres;
  traceCrease(1.0, metres);
  traceCrease(2.0, halfMetres);
  raytrace::ObscuranceOptions o;
  o.rays = 32;
  o.radius = 0.8;
  const FloatImage a = obscuranceImage(metres, o), b = obscuranceImage(halfMetres, o);
  double maxDiff = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i) maxDiff = std::max(maxDiff, double(std::fabs(a.data[i] - b.data[i])));
  EXPECT_LT(maxDiff, 1e-3);
}

TEST(Obscurance, ClampsTheMeanAndAppliesContrast) {
  CreaseImage c;
  traceCrease(1.0, c);
  raytrace::ObscuranceOptions o;
  o.rays = 32;
  const FloatImage base = obscuranceImage(c, o);
  o.intensity = 10.0;
  const FloatImage strong = obscuranceImage(c, o);
  std::size_t clamped = 0;
  for (std::size_t i = 0; i < base.data.size(); ++i) {
    // 1 - 10 O, clamped: 0 wherever O >= 0.1, i.e. wherever 1 - O <= 0.9.
    const double expected = std::clamp(1.0 - 10.0 * (1.0 - double(base.data[i])), 0.0, 1.0);
    EXPECT_NEAR(strong.data[i], expected, 1e-5) << i;
    clamped += strong.data[i] == 0.0f;
  }
  EXPECT_GT(clamped, 0u) << "some pixels reach the clamp";
  o.intensity = 1.0;
  o.contrast = 2.0;
  const FloatImage squared = obscuranceImage(c, o);
  for (std::size_t i = 0; i < base.data.size(); ++i) EXPECT_NEAR(squared.data[i], base.data[i] * base.data[i], 1e-6);
}

TEST(Obscurance, RejectsBadOptions) {
  CreaseImage c;
  traceCrease(1.0, c);
  FloatImage ao;
  auto code = [&](auto edit) {
    raytrace::ObscuranceOptions o;
    edit(o);
    return raytrace::referenceObscurance(*c.rays, c.camera, c.primary, c.scene.views[0], o, ao).code;
  };
  EXPECT_EQ(code([](auto& o) { o.radius = 0; }), StatusCode::InvalidInput);
  EXPECT_EQ(code([](auto& o) { o.radius = NAN; }), StatusCode::InvalidInput);
  EXPECT_EQ(code([](auto& o) { o.epsilon = 0; }), StatusCode::InvalidInput);
  EXPECT_EQ(code([](auto& o) { o.intensity = -1; }), StatusCode::InvalidInput);
  EXPECT_EQ(code([](auto& o) { o.bias = -0.1; }), StatusCode::InvalidInput);
  EXPECT_EQ(code([](auto& o) { o.contrast = 0; }), StatusCode::InvalidInput);
  EXPECT_EQ(code([](auto& o) { o.rays = 0; }), StatusCode::InvalidInput);
  Camera other = c.camera;
  other.width += 2;
  EXPECT_EQ(raytrace::referenceObscurance(*c.rays, other, c.primary, c.scene.views[0], {}, ao).code, StatusCode::InvalidInput);
}

TEST(Obscurance, OptionsFollowTheEffectSettings) {
  Settings s;
  s.radius = 0.7f;
  s.intensity = 1.5f;
  s.bias = 0.03f;
  s.epsilon = 2e-4f;
  s.contrast = 1.25f;
  const auto o = raytrace::obscuranceOptions(s, 99, 5);
  EXPECT_EQ(o.radius, double(s.radius));
  EXPECT_EQ(o.intensity, double(s.intensity));
  EXPECT_EQ(o.bias, double(s.bias));
  EXPECT_EQ(o.epsilon, double(s.epsilon));
  EXPECT_EQ(o.contrast, double(s.contrast));
  EXPECT_EQ(o.rays, 99u);
  EXPECT_EQ(o.seed, 5u);
}

}  // namespace
