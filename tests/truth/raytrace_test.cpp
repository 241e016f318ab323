// The ray-traced reference against the analytic case, and primary rays against the camera.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sao/raytrace/analytic.h"
#include "sao/raytrace/raytrace.h"

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
