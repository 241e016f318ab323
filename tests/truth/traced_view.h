// A scene ray-traced from its first view: the Embree scene, the camera (D32F reversed-Z [0,1],
// infinite far) and the primary hits that the references start from. Shared by the truth tests.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "sao/raytrace/raytrace.h"

namespace sao::truthtest {

struct TracedView {
  scenes::Scene scene;
  std::unique_ptr<raytrace::RayScene> rays;
  Camera camera;
  raytrace::Primary primary;
};

inline void traceFirstView(scenes::Scene scene, std::uint32_t width, std::uint32_t height, std::uint32_t guard,
                           double metersToViewUnits, TracedView& out) {
  out.scene = std::move(scene);
  ASSERT_TRUE(raytrace::RayScene::create(out.scene.mesh, out.rays).ok());
  out.camera = scenes::makeCamera(out.scene.views[0], width, height, INFINITY, ClipDepth::ZeroToOne, true, guard);
  out.camera.metersToViewUnits = metersToViewUnits;
  ASSERT_TRUE(raytrace::castPrimary(*out.rays, out.scene.views[0], out.camera, DepthFormat::D32F, out.primary).ok());
}

}  // namespace sao::truthtest
