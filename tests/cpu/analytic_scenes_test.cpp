// The analytic scene helpers: rays, window depth and the scenes' geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "analytic_scenes.h"

namespace sao::test {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Camera camera(ClipDepth clip, bool reversed, double farDistance, std::uint32_t guard = 4) {
  Camera c = perspectiveCamera(std::numbers::pi / 3.0, 160, 90, 0.1, farDistance, clip, reversed);
  c.guardBand = guard;
  return c;
}

TEST(Scenes, WindowDepthInvertsTheCoreDepthModel) {
  std::vector<Camera> cams;
  for (ClipDepth clip : {ClipDepth::NegativeOneToOne, ClipDepth::ZeroToOne})
    for (bool reversed : {false, true})
      for (double f : {100.0, kInfinity}) cams.push_back(camera(clip, reversed, f));
  cams.push_back(orthographicCamera(2.0, 160, 90, 0.5, 50.0, ClipDepth::ZeroToOne, true));
  cams.push_back(orthographicCamera(2.0, 160, 90, 0.5, 50.0, ClipDepth::NegativeOneToOne, false));
  for (const Camera& c : cams) {
    DepthModel m;
    ASSERT_TRUE(analyze(c, m).ok());
    EXPECT_NEAR(windowDepth(c, -m.nearDistance), m.depthAtNear, 1e-12);
    EXPECT_EQ(clearDepth(c), m.depthAtFar);
    for (double z : {-0.7, -3.0, -42.0}) EXPECT_NEAR(linearZ(m, c.kind, windowDepth(c, z)), z, 1e-9 * -z);
  }
}

TEST(Scenes, PlaneIsAtItsDistanceEverywhere) {
  const Camera c = camera(ClipDepth::ZeroToOne, false, 1000.0);
  for (double d : {1.0, 10.0, 100.0})
    for (double z : renderZ(planeScene(d), c)) ASSERT_DOUBLE_EQ(z, -d);
  for (std::uint32_t t : renderDepth(skyScene(), c, DepthFormat::D24).texels) ASSERT_EQ(t, 0xFFFFFFu);
  for (std::uint32_t t : renderDepth(skyScene(), camera(ClipDepth::ZeroToOne, true, 1000.0), DepthFormat::D32F).texels)
    ASSERT_EQ(t, 0u);
  // Beyond the far plane is clipped away: clear value.
  for (std::uint32_t t : renderDepth(planeScene(200.0), camera(ClipDepth::ZeroToOne, false, 100.0), DepthFormat::D24)
                             .texels)
    ASSERT_EQ(t, 0xFFFFFFu);
}

TEST(Scenes, CreaseIsMirrorSymmetricAndRightAngled) {
  const Camera c = camera(ClipDepth::NegativeOneToOne, false, 1000.0);
  const Extent e = inputExtent(c);
  const std::vector<double> z = renderZ(creaseScene(2.0), c);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      const double zl = z[std::size_t(y) * e.width + x], zr = z[std::size_t(y) * e.width + (e.width - 1 - x)];
      ASSERT_LT(zl, 0.0);
      ASSERT_NEAR(zl, zr, 1e-12);
      Vec3 o, d;
      viewRay(c, x, y, o, d);
      const double t = zl / d.z;
      ASSERT_NEAR(zl, -2.0 + std::abs(t * d.x), 1e-12) << "on z = -2 + |x|";
    }
  const FloatImage n = renderNormals(creaseScene(2.0), c);
  EXPECT_NEAR(n.at(0, 40, 0), std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(n.at(e.width - 1, 40, 0), -std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(n.at(0, 40, 2), std::sqrt(0.5), 1e-6);
}

TEST(Scenes, LayersAndNormalsOfTheSphere) {
  const Camera c = camera(ClipDepth::ZeroToOne, true, kInfinity, 0);
  const Extent e = inputExtent(c);
  const Scene s = sphereOnPlaneScene();
  const std::vector<double> z0 = renderZ(s, c, 0), z1 = renderZ(s, c, 1);
  // Row 32 (NDC y = -0.28) looks at the middle of the sphere (centre (0, -0.5, -3), r 0.5).
  const std::uint32_t row = 32;
  const std::size_t i = std::size_t(row) * e.width + e.width / 2;
  EXPECT_GT(z0[i], -3.0);
  EXPECT_LT(z0[i], -2.5);
  EXPECT_LT(z1[i], -3.0) << "second layer: the back of the sphere";
  EXPECT_GT(z1[i], -3.5);
  const FloatImage n = renderNormals(s, c);
  EXPECT_GT(n.at(e.width / 2, row, 2), 0.9f) << "faces the camera";
  EXPECT_NEAR(n.at(e.width / 2, 0, 1), 1.0f, 1e-6) << "the floor's normal is +y";
  // Rows follow the API's order: flipping the target mirrors them.
  Camera flipped = c;
  flipped.flipY = true;
  const std::vector<double> zf = renderZ(s, flipped);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x)
      ASSERT_NEAR(zf[std::size_t(y) * e.width + x], z0[std::size_t(e.height - 1 - y) * e.width + x], 1e-12);
}

TEST(Scenes, ThinRodsAndStairs) {
  const Camera c = camera(ClipDepth::ZeroToOne, false, 1000.0, 0);
  const Extent e = inputExtent(c);
  const std::vector<double> z = renderZ(rodsScene(), c);
  int rodTexels = 0;
  for (double v : z) {
    ASSERT_LT(v, 0.0);
    rodTexels += v > -3.5;
  }
  EXPECT_GT(rodTexels, 5 * 45) << "each rod covers at least half a pixel column";
  EXPECT_LE(rodTexels, 5 * 2 * int(e.height)) << "and at most two";
  const std::vector<double> zs = renderZ(stairsScene(), c);
  for (double v : zs) ASSERT_LT(v, 0.0);
}

}  // namespace
}  // namespace sao::test
