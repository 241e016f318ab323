// The ray-traced reference against the analytic case, its determinism, and primary rays against
// the camera.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "sao/raytrace/analytic.h"
#include "sao/raytrace/raytrace.h"
#include "traced_view.h"

namespace {

using namespace sao;

// The analytic sphere case (raytrace::traceAnalyticSphere): cos(theta) (R/D)^2 of the
// cosine-weighted hemisphere. sao-bench runs the same check every run (reference_check.csv).
TEST(Reference, MatchesTheAnalyticSphere) {
  for (double theta : {0.0, 45.0, 60.0}) {
    raytrace::SphereCheck c;
    ASSERT_TRUE(raytrace::traceAnalyticSphere({theta, 1.0, 3.0}, 40000, 7, c).ok());
    EXPECT_NEAR(c.analytic, std::cos(theta * std::numbers::pi / 180) / 9.0, 1e-12);
    EXPECT_NEAR(c.traced, c.analytic, 0.01) << "theta " << theta;
    std::printf("theta %.0f: reference %.4f analytic %.4f\n", theta, c.traced, c.analytic);
  }
  raytrace::SphereCheck c;
  EXPECT_EQ(raytrace::traceAnalyticSphere({80.0, 1.0, 3.0}, 100, 7, c).code, StatusCode::InvalidInput)
      << "partly below the horizon: the formula does not hold";
}

TEST(Reference, RadiusLimitsTheOcclusion) {
  scenes::MeshBuilder b;
  b.sphere({0, 3, 0}, 1.0, 48, 96);
  std::unique_ptr<raytrace::RayScene> scene;
  ASSERT_TRUE(raytrace::RayScene::create(b.build(), scene).ok());
  EXPECT_EQ(raytrace::visibilityAt(*scene, {0, 0, 0}, {0, 1, 0}, 1.5, 2000, 1, 0.0), 1.0) << "sphere beyond r";
}

// The bent normal (raytrace::bentNormalAt), the reference for the effect's bent_normals: the open
// hemisphere's mean clear direction is n; a wall through the point that stops every ray with x > 0
// leaves the cosine-weighted mean of the half hemisphere, (-4/(3 pi), 2/3) in (x, n) (atan(2/pi) =
// 32.48 deg from n, docs/effect-math.md 5.10); a point shut in keeps n. 40,000 rays: the mean's
// noise is about 0.15 deg.
TEST(Reference, BentNormalOfTheOpenAndTheHalfHemisphere) {
  const auto degreesBetween = [](glm::dvec3 a, glm::dvec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180 / std::numbers::pi;
  };
  const glm::dvec3 n(0, 1, 0);
  scenes::MeshBuilder open;
  open.box({-50, -1, -50}, {50, -0.5, 50});  // below the point: no ray reaches it
  std::unique_ptr<raytrace::RayScene> openScene;
  ASSERT_TRUE(raytrace::RayScene::create(open.build(), openScene).ok());
  const glm::dvec3 b0 = raytrace::bentNormalAt(*openScene, {0, 0, 0}, n, 2.0, 40000, 5, 0.0);
  EXPECT_LT(degreesBetween(b0, n), 0.5) << "open hemisphere";

  scenes::MeshBuilder wall;
  wall.box({1e-6, -1, -50}, {1, 50, 50});  // every ray with x > 0 hits it within 1 m
  std::unique_ptr<raytrace::RayScene> wallScene;
  ASSERT_TRUE(raytrace::RayScene::create(wall.build(), wallScene).ok());
  const glm::dvec3 b1 = raytrace::bentNormalAt(*wallScene, {0, 0, 0}, n, 2.0, 40000, 5, 0.0);
  const glm::dvec3 half(-4.0 / (3.0 * std::numbers::pi), 2.0 / 3.0, 0.0);
  EXPECT_LT(degreesBetween(b1, half), 0.5) << "half hemisphere: (" << b1.x << ", " << b1.y << ", " << b1.z << ")";
  EXPECT_NEAR(degreesBetween(b1, n), std::atan(2.0 / std::numbers::pi) * 180 / std::numbers::pi, 0.5);

  scenes::MeshBuilder shut;
  shut.box({-0.5, 0.001, -0.5}, {0.5, 0.5, 0.5});  // a lid just above the point: every ray hits it within 0.4 m
  std::unique_ptr<raytrace::RayScene> shutScene;
  ASSERT_TRUE(raytrace::RayScene::create(shut.build(), shutScene).ok());
  EXPECT_EQ(raytrace::bentNormalAt(*shutScene, {0, 0, 0}, n, 0.4, 1000, 5, 0.0), n) << "nothing clear within 0.4 m";
}

// The near-field AO image is a pure function of (scene, view, options): the same seed gives the
// same bits, and so does any thread count (rows run in any order, each pixel has its own seed).
TEST(Reference, IsDeterministicAndIndependentOfThreads) {
  truthtest::TracedView t;
  truthtest::traceCrease(1.0, t);
  if (HasFatalFailure()) return;
  raytrace::ReferenceOptions o;
  o.rays = 48;
  auto image = [&](unsigned threads, std::uint64_t seed) {
    o.threads = threads;
    o.seed = seed;
    FloatImage ao;
    EXPECT_TRUE(raytrace::referenceAmbientOcclusion(*t.rays, t.camera, t.primary, t.scene.views[0], o, ao).ok());
    return ao;
  };
  const FloatImage one = image(1, 1);
  ASSERT_EQ(one.extent, (Extent{48, 32}));
  float darkest = 1;
  for (float v : one.data) darkest = std::min(darkest, v);
  EXPECT_LT(darkest, 0.8f) << "the corner is occluded";
  auto same = [&](const FloatImage& a) {
    return a.data.size() == one.data.size() &&
           std::memcmp(a.data.data(), one.data.data(), one.data.size() * sizeof(float)) == 0;
  };
  EXPECT_TRUE(same(image(1, 1))) << "same seed, one thread";
  for (unsigned threads : {2u, 5u}) EXPECT_TRUE(same(image(threads, 1))) << threads << " threads";
  EXPECT_FALSE(same(image(2, 2))) << "the seed matters";
}

TEST(Primary, DepthOfAFacingWallRoundTripsThroughTheCamera) {
  scenes::MeshBuilder b;
  b.box({-50, -50, -10.1}, {50, 50, -10});  // a wall 10 m in front of the eye
  scenes::Scene s{"wall", b.build(), {{"front", {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.0, 0.1}}};
  std::unique_ptr<raytrace::RayScene> scene;
  ASSERT_TRUE(raytrace::RayScene::create(s.mesh, scene).ok());
  for (bool reversed : {false, true}) {
    Camera cam = scenes::makeCamera(s.views[0], 64, 48, INFINITY, ClipDepth::ZeroToOne, reversed, 4);
    raytrace::Primary primary;
    ASSERT_TRUE(raytrace::castPrimary(*scene, s.views[0], cam, DepthFormat::D32F, primary).ok());
    EXPECT_EQ(primary.depth.extent, (Extent{72, 56}));
    DepthModel m;
    ASSERT_TRUE(analyze(cam, m).ok());
    for (std::uint32_t y : {0u, 20u, 55u})
      for (std::uint32_t x : {0u, 36u, 71u}) {
        EXPECT_NEAR(linearZ(m, cam.kind, primary.depth.value(x, y)), -10.0, 1e-4);
        EXPECT_NEAR(primary.position.at(x, y, 2), -10.0f, 1e-4f);
        EXPECT_NEAR(primary.normal.at(x, y, 2), 1.0f, 1e-6f) << "normal faces the camera";
      }
  }
}

TEST(Primary, RejectsEmptyScenes) {
  std::unique_ptr<raytrace::RayScene> scene;
  EXPECT_EQ(raytrace::RayScene::create(scenes::Mesh{}, scene).code, StatusCode::InvalidInput);
}

TEST(Scenes, EveryBuiltinSceneBuildsWithViews) {
  for (auto name : scenes::builtinSceneNames()) {
    scenes::Scene s;
    ASSERT_TRUE(scenes::makeBuiltinScene(name, s).ok()) << name;
    EXPECT_GT(s.mesh.triangleCount(), 10u) << name;
    EXPECT_FALSE(s.views.empty()) << name;
    scenes::Scene again;
    ASSERT_TRUE(scenes::makeBuiltinScene(name, again).ok());
    EXPECT_EQ(s.mesh.positions, again.mesh.positions) << "deterministic";
  }
  scenes::Scene s;
  EXPECT_EQ(scenes::makeBuiltinScene("nope", s).code, StatusCode::InvalidInput);
}

}  // namespace
