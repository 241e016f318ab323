// raytrace::castSecondLayer: the first surface at least the minimum separation behind the first
// layer, back faces included, the clear value where there is none.
#include <gtest/gtest.h>

#include <cmath>

#include "sao/raytrace/raytrace.h"

namespace {

using namespace sao;

// Two walls facing the eye at the origin: a slab 0.1 m thick at z = -10 and another at z = -12.
struct TwoWalls {
  scenes::Scene scene;
  std::unique_ptr<raytrace::RayScene> rays;
  Camera camera;
  DepthModel model;
  TwoWalls() {
    scenes::MeshBuilder b;
    b.box({-50, -50, -10.1}, {50, 50, -10});
    b.box({-80, -80, -12.1}, {80, 80, -12});
    scene = {"walls", b.build(), {{"front", {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.0, 0.1}}};
    EXPECT_TRUE(raytrace::RayScene::create(scene.mesh, rays).ok());
    camera = scenes::makeCamera(scene.views[0], 32, 24, INFINITY, ClipDepth::ZeroToOne, true, 2);
    EXPECT_TRUE(analyze(camera, model).ok());
  }
  raytrace::Primary layer(double separation) {
    raytrace::Primary out;
    EXPECT_TRUE(raytrace::castSecondLayer(*rays, scene.views[0], camera, DepthFormat::D32F, separation, out).ok());
    return out;
  }
};

TEST(SecondLayer, FindsTheFirstSurfaceBeyondTheSeparation) {
  TwoWalls w;
  // (separation, expected z): the slab's own back face, then the far wall.
  for (auto [separation, z] : {std::pair{0.05, -10.1}, std::pair{0.5, -12.0}, std::pair{2.05, -12.1}}) {
    const raytrace::Primary second = w.layer(separation);
    ASSERT_EQ(second.depth.extent, (Extent{36, 28}));
    for (std::uint32_t y : {0u, 13u, 27u})
      for (std::uint32_t x : {0u, 17u, 35u}) {
        EXPECT_NEAR(linearZ(w.model, w.camera.kind, second.depth.value(x, y)), z, 1e-4) << separation;
        EXPECT_NEAR(second.position.at(x, y, 2), float(z), 1e-4f);
        EXPECT_EQ(second.position.at(x, y, 3), 1.0f);
        EXPECT_NEAR(second.normal.at(x, y, 2), 1.0f, 1e-6f) << "faces the camera, back face or not";
      }
  }
}

TEST(SecondLayer, IsClearWhereNothingLiesBehind) {
  TwoWalls w;
  const raytrace::Primary second = w.layer(5.0);
  const std::uint32_t clear = encodeDepth(DepthFormat::D32F, 0.0);  // reversed-Z clears to 0
  for (std::size_t i = 0; i < second.depth.texels.size(); ++i) ASSERT_EQ(second.depth.texels[i], clear);
  for (std::size_t i = 3; i < second.position.data.size(); i += 4) ASSERT_EQ(second.position.data[i], 0.0f);
}

TEST(SecondLayer, IsClearWhereThereIsNoFirstLayer) {
  scenes::MeshBuilder b;
  b.box({0, -50, -10.1}, {50, 50, -10});  // the right half of the view only
  b.box({-80, -80, -12.1}, {80, 80, -12});
  scenes::Scene s{"half", b.build(), {{"front", {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.0, 0.1}}};
  std::unique_ptr<raytrace::RayScene> rays;
  ASSERT_TRUE(raytrace::RayScene::create(s.mesh, rays).ok());
  const Camera cam = scenes::makeCamera(s.views[0], 32, 24, INFINITY, ClipDepth::ZeroToOne, false);
  raytrace::Primary first, second;
  ASSERT_TRUE(raytrace::castPrimary(*rays, s.views[0], cam, DepthFormat::D32F, first).ok());
  ASSERT_TRUE(raytrace::castSecondLayer(*rays, s.views[0], cam, DepthFormat::D32F, 1.0, second).ok());
  // Left half: the first layer is the far wall, with nothing behind it. Right half: the far wall is the second layer.
  EXPECT_NEAR(first.position.at(3, 12, 2), -12.0f, 1e-4f);
  EXPECT_EQ(second.position.at(3, 12, 3), 0.0f);
  EXPECT_NEAR(first.position.at(28, 12, 2), -10.0f, 1e-4f);
  EXPECT_NEAR(second.position.at(28, 12, 2), -12.0f, 1e-4f);
}

TEST(SecondLayer, RejectsABadSeparation) {
  TwoWalls w;
  raytrace::Primary out;
  for (double bad : {0.0, -1.0, double(NAN), double(INFINITY)})
    EXPECT_EQ(raytrace::castSecondLayer(*w.rays, w.scene.views[0], w.camera, DepthFormat::D32F, bad, out).code,
              StatusCode::InvalidInput)
        << bad;
}

}  // namespace
