// Orthographic views through the ray-traced references (samples/raytrace): parallel primary rays
// from the view plane, and the CPU effect on an orthographic depth against the near-field
// reference, side by side with the perspective view of the same scene.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "sao/cpu/reference.h"
#include "sao/raytrace/raytrace.h"
#include "sao/samples/metrics.h"

namespace sao::truthtest {
namespace {

// A wall facing +z at z = 0, seen straight on from z = 10: every primary ray of an orthographic
// view hits it at the same depth, under its own texel (x, y), with the normal +z.
TEST(OrthographicPrimary, RaysAreParallelFromTheViewPlane) {
  scenes::MeshBuilder b;
  b.box({-20, -20, -1}, {20, 20, 0});
  const scenes::Mesh mesh = b.build();
  std::unique_ptr<raytrace::RayScene> rays;
  ASSERT_TRUE(raytrace::RayScene::create(mesh, rays));
  scenes::View view;
  view.eye = {0.5, 1.0, 10.0};
  view.target = {0.5, 1.0, 0.0};
  view.nearDistance = 0.5;
  view.orthoHeight = 4.0;
  scenes::fitOrthoFar(view, mesh);
  constexpr std::uint32_t kW = 64, kH = 32, kGuard = 2;
  const Camera camera = scenes::makeCamera(view, kW, kH, INFINITY, ClipDepth::ZeroToOne, true, kGuard);
  ASSERT_EQ(camera.kind, ProjectionKind::Orthographic);
  raytrace::Primary primary;
  ASSERT_TRUE(raytrace::castPrimary(*rays, view, camera, DepthFormat::D32F, primary));
  DepthModel model;
  ASSERT_TRUE(analyze(camera, model));
  const double halfHeight = 2.0, halfWidth = halfHeight * kW / kH;
  for (std::uint32_t y = 0; y < kH + 2 * kGuard; ++y)
    for (std::uint32_t x = 0; x < kW + 2 * kGuard; ++x) {
      ASSERT_EQ(primary.position.at(x, y, 3), 1.0f) << x << "," << y;
      const double px = (2.0 * (x - double(kGuard) + 0.5) / kW - 1.0) * halfWidth;
      const double py = (2.0 * (y - double(kGuard) + 0.5) / kH - 1.0) * halfHeight;
      EXPECT_NEAR(primary.position.at(x, y, 0), px, 1e-5);
      EXPECT_NEAR(primary.position.at(x, y, 1), py, 1e-5);
      EXPECT_NEAR(primary.position.at(x, y, 2), -10.0, 1e-5);
      EXPECT_NEAR(primary.normal.at(x, y, 2), 1.0, 1e-6);
      EXPECT_NEAR(linearZ(model, camera.kind, primary.depth.value(x, y)), -10.0, 1e-5);
    }
}

struct ViewRun {
  samples::ReferenceComparison metrics;
  double openPlaneMean = 0, openPlaneMin = 1;  // the effect's AO where the reference sees no occluder
  std::size_t openPlanePixels = 0;
};

// The CPU effect (default settings) on the ray-cast depth of `view`, against the near-field
// reference; `open` picks the world points of the open plane (farther than the 1 m radius from
// anything but the plane they lie on).
ViewRun effectAgainstReference(const raytrace::RayScene& rays, const scenes::View& view,
                               const std::function<bool(glm::dvec3)>& open) {
  ViewRun r;
  constexpr std::uint32_t kW = 96, kH = 64, kGuard = 8;
  const Camera camera = scenes::makeCamera(view, kW, kH, INFINITY, ClipDepth::ZeroToOne, true, kGuard);
  raytrace::Primary primary;
  EXPECT_TRUE(raytrace::castPrimary(rays, view, camera, DepthFormat::D32F, primary));
  raytrace::ReferenceOptions ro;
  ro.rays = 128;
  FloatImage reference;
  EXPECT_TRUE(raytrace::referenceAmbientOcclusion(rays, camera, primary, view, ro, reference));
  cpu::Inputs inputs;
  inputs.depth = &primary.depth;
  cpu::Result result;
  const Status s = cpu::run(Settings{}, camera, inputs, cpu::Options{}, result);
  EXPECT_TRUE(s) << s.message;
  if (!s) return r;
  r.metrics = samples::compareToReference(result.ao, reference, samples::geometryMask(primary.position, kGuard));
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(view));
  double sum = 0;
  for (std::uint32_t y = 0; y < kH; ++y)
    for (std::uint32_t x = 0; x < kW; ++x) {
      if (primary.position.at(x + kGuard, y + kGuard, 3) == 0.0f) continue;
      const glm::dvec3 pc(primary.position.at(x + kGuard, y + kGuard, 0), primary.position.at(x + kGuard, y + kGuard, 1),
                          primary.position.at(x + kGuard, y + kGuard, 2));
      const glm::dvec3 p = glm::dvec3(toWorld * glm::dvec4(pc, 1.0));
      if (!open(p)) continue;
      const double ao = result.ao.at(x, y);
      sum += ao;
      r.openPlaneMin = std::min(r.openPlaneMin, ao);
      ++r.openPlanePixels;
    }
  r.openPlaneMean = r.openPlanePixels ? sum / double(r.openPlanePixels) : NAN;
  return r;
}

// A view of a built-in scene, perspective and made orthographic (as tall as the field of view
// spans at the target): the effect's error against the reference is of the same size, and the
// open floor is unoccluded (AO ~1) in both.
void compareProjections(const char* sceneName, const scenes::View& perspective,
                        const std::function<bool(glm::dvec3)>& open) {
  scenes::Scene scene;
  ASSERT_TRUE(scenes::makeBuiltinScene(sceneName, scene));
  std::unique_ptr<raytrace::RayScene> rays;
  ASSERT_TRUE(raytrace::RayScene::create(scene.mesh, rays));
  scenes::View ortho = perspective;
  ortho.orthoHeight = 2.0 * glm::length(ortho.target - ortho.eye) * std::tan(0.5 * ortho.fovyRadians);
  scenes::fitOrthoFar(ortho, scene.mesh);
  const ViewRun p = effectAgainstReference(*rays, perspective, open);
  const ViewRun o = effectAgainstReference(*rays, ortho, open);
  std::printf("%s:\n", sceneName);
  for (const auto& [name, r] : {std::pair{"perspective", &p}, std::pair{"orthographic", &o}})
    std::printf("%-12s RMSE %.4f, mean bias %+.4f, SSIM %.4f over %zu pixels; open floor %zu pixels: AO mean %.4f, "
                "min %.4f\n",
                name, r->metrics.raw.rmse, r->metrics.raw.meanBias, r->metrics.raw.ssim, r->metrics.raw.pixels,
                r->openPlanePixels, r->openPlaneMean, r->openPlaneMin);
  ASSERT_GT(o.metrics.raw.pixels, 3000u);
  ASSERT_GT(o.openPlanePixels, 1000u);
  EXPECT_TRUE(std::isfinite(o.metrics.raw.rmse));
  EXPECT_TRUE(std::isfinite(o.metrics.raw.ssim));
  // Measured figures in tests/README.md; the bounds leave room for the reference's noise.
  EXPECT_LT(o.metrics.raw.rmse, 1.5 * p.metrics.raw.rmse + 0.02);
  EXPECT_GT(o.openPlaneMean, 0.99);
  EXPECT_GT(o.openPlaneMin, 0.95);
}

// sphere-plane's "top" view: the floor faces the camera; open beyond 2.5 m from the sphere's axis
// (its radius 1 m plus the AO radius, 1 m, and a margin).
TEST(OrthographicReference, SpherePlaneTopAsInPerspective) {
  scenes::Scene scene;
  ASSERT_TRUE(scenes::makeBuiltinScene("sphere-plane", scene));
  ASSERT_EQ(scene.views[1].name, "top");
  compareProjections("sphere-plane", scene.views[1],
                     [](glm::dvec3 p) { return std::abs(p.y) < 1e-3 && std::hypot(p.x, p.z) > 2.5; });
}

// The crease (floor and a wall at z = -10) seen obliquely from the eye of its "corner" view pulled
// back along the view direction, so that the orthographic view plane stays clear of the floor (the
// rays are parallel: the framing is the same). The floor is open more than 1.5 m from the wall.
TEST(OrthographicReference, CreaseObliqueAsInPerspective) {
  scenes::Scene scene;
  ASSERT_TRUE(scenes::makeBuiltinScene("crease", scene));
  scenes::View view = scene.views[0];
  view.eye = view.target + 2.0 * (view.eye - view.target);
  view.fovyRadians = 2.0 * std::atan(0.5 * std::tan(0.5 * view.fovyRadians));  // the same height at the target
  compareProjections("crease", view,
                     [](glm::dvec3 p) { return std::abs(p.y) < 1e-3 && p.z > -8.5 && std::abs(p.x) < 9; });
}

}  // namespace
}  // namespace sao::truthtest
