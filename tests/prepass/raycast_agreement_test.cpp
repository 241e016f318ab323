// The rasterised prepass against raytrace::castPrimary on the same view and camera: coverage,
// camera-space z decoded from the stored depth, positions and face normals; three scenes, guard
// bands 0 and 8, D16 / D24 / D32F, standard and reversed depth with finite and infinite far planes;
// and the same for an orthographic view of each scene (parallel primary rays, finite far planes).
#include <cmath>
#include <span>
#include <cstdio>
#include <ostream>

#include "prepass_support.h"

namespace sao::prepasstest {
namespace {

constexpr std::uint32_t kWidth = 160, kHeight = 90;

const Convention kConventions[] = {
    {"standard [-1,1] far 1000", ClipDepth::NegativeOneToOne, false, 1000.0},
    {"standard [0,1] far 1000", ClipDepth::ZeroToOne, false, 1000.0},
    {"reversed [0,1] infinite", ClipDepth::ZeroToOne, true, INFINITY},
    {"reversed [0,1] far 1000", ClipDepth::ZeroToOne, true, 1000.0},
    {"standard [0,1] infinite", ClipDepth::ZeroToOne, false, INFINITY},
};
// Orthographic cameras need a finite far plane: "fitted" is INFINITY to makeCamera, which then
// takes the view's orthoFar (just beyond the scene, scenes::fitOrthoFar).
const Convention kOrthoConventions[] = {
    {"ortho reversed [0,1] fitted", ClipDepth::ZeroToOne, true, INFINITY},
    {"ortho standard [0,1] fitted", ClipDepth::ZeroToOne, false, INFINITY},
    {"ortho standard [-1,1] far 200", ClipDepth::NegativeOneToOne, false, 200.0},
    {"ortho reversed [0,1] far 200", ClipDepth::ZeroToOne, true, 200.0},
};
constexpr DepthFormat kFormats[] = {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F};

struct Case {
  std::string backend, scene;
  std::uint32_t guard;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.backend << " " << c.scene << " guard " << c.guard; }

class RayCastAgreement : public PrepassTest, public ::testing::WithParamInterface<Case> {};

void agreeWithRayCast(const Case& c, prepass::Prepass& prepass, const LoadedScene& ls, const scenes::View& view,
                      std::span<const Convention> conventions) {
  const double scale = worldScale(ls.scene.mesh, view);
  for (const Convention& conv : conventions) {
    if (!prepass.supportsClip(conv.clip)) continue;
    const Camera camera = scenes::makeCamera(view, kWidth, kHeight, conv.farDistance, conv.clip, conv.reversed, c.guard);
    raytrace::Primary ray;
    ASSERT_TRUE(raytrace::castPrimary(*ls.rays, view, camera, DepthFormat::D32F, ray));
    for (DepthFormat format : kFormats) {
      SCOPED_TRACE(std::string(conv.name) + " " + toString(format));
      prepass::PrepassOptions options;
      options.format = format;
      prepass::PrepassResult raster;
      const Status s = prepass.render(ls.scene.mesh, view, camera, options, raster);
      ASSERT_TRUE(s) << s.message;
      ASSERT_EQ(raster.depth.extent, ray.position.extent);
      ASSERT_EQ(raster.depth.format, format);
      EXPECT_TRUE(raster.depth2.texels.empty());
      const RayAgreement a = compareWithRayCast(raster, ray, camera, format, scale);
      std::printf("[%s %s g%u] %-26s %-4s %s\n", c.backend.c_str(), c.scene.c_str(), c.guard, conv.name,
                  toString(format), describe(a).c_str());
      // Coverage differs only on silhouettes (pixel centres within the rasteriser's sub-pixel
      // precision of an edge): below 1 % of the pixels, and never where the ray cast's 3x3
      // neighbourhood is all geometry or all sky.
      EXPECT_LT(double(a.coverageMismatch), 0.01 * double(a.pixels));
      EXPECT_EQ(a.mismatchOffSilhouette, 0u);
      // Where both see geometry, a different surface (the ray and the rasteriser resolving an edge
      // between two surfaces differently) on below 1 % of the pixels.
      EXPECT_LT(double(a.surfaceMismatch), 0.01 * double(a.pixels));
      EXPECT_GT(a.interior, a.pixels / 4);
      // Inside faces: z within the format's bound, normals and positions to float precision.
      EXPECT_LE(a.zWorstBoundRatio, 1.0);
      EXPECT_LT(a.normalWorstDeg, 0.01);
      EXPECT_LT(a.positionWorstRel, 1e-5);
      // The clear value where nothing is hit, exactly as the ray cast writes it.
      const std::uint32_t clear = encodeDepth(format, conv.reversed ? 0.0 : 1.0);
      std::size_t badSky = 0;
      for (std::size_t i = 0; i < raster.depth.texels.size(); ++i)
        if (raster.position.data[4 * i + 3] == 0.0f)
          badSky += raster.depth.texels[i] != clear || raster.normal.data[4 * i] != 0.0f;
      EXPECT_EQ(badSky, 0u);
    }
  }
}

TEST_P(RayCastAgreement, CoverageDepthNormals) {
  const Case& c = GetParam();
  const LoadedScene& ls = loadScene(c.scene);
  agreeWithRayCast(c, backend(c.backend), ls, ls.scene.views.front(), kConventions);
}

// The scene's view made orthographic (scenes::toOrthographic: the eye pulled back clear of the
// scene, as the viewer does), half as tall as its field of view spans at the target distance, so
// that the scene rather than the sky fills the image.
TEST_P(RayCastAgreement, CoverageDepthNormalsOrthographic) {
  const Case& c = GetParam();
  const LoadedScene& ls = loadScene(c.scene);
  scenes::View view = ls.scene.views.front();
  view.orthoHeight = glm::length(view.target - view.eye) * std::tan(0.5 * view.fovyRadians);
  view = scenes::toOrthographic(view, ls.scene.mesh);
  ASSERT_LT(view.orthoFar, 200.0);  // the explicit far plane of kOrthoConventions lies beyond the scene
  ASSERT_EQ(scenes::makeCamera(view, kWidth, kHeight, INFINITY, ClipDepth::ZeroToOne, true).kind,
            ProjectionKind::Orthographic);
  agreeWithRayCast(c, backend(c.backend), ls, view, kOrthoConventions);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const auto& b : backendNames())
    for (const char* scene : {"crease", "sphere-plane", "sponza-like"})
      for (std::uint32_t guard : {0u, 8u}) out.push_back({b, scene, guard});
  return out;
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(RayCastAgreement);  // a build without GL and Vulkan
INSTANTIATE_TEST_SUITE_P(Scenes, RayCastAgreement, ::testing::ValuesIn(cases()), [](const auto& info) {
  std::string n = info.param.backend + "_" + info.param.scene + "_guard" + std::to_string(info.param.guard);
  for (char& ch : n)
    if (ch == '-') ch = '_';
  return n;
});

}  // namespace
}  // namespace sao::prepasstest
