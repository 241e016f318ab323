// The truth tests' shared setup: a scene ray-traced from its first view (the Embree scene, the
// camera, D32F reversed-Z [0,1] with an infinite far plane, and the primary hits the references
// start from), and the crease they trace most.
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

// A floor (top at y = 0) and a wall facing +x at x = -d: a 90-degree crease along z when d = 0.
inline scenes::MeshBuilder creaseMesh(double d, double scale = 1.0) {
  scenes::MeshBuilder b;
  b.box(glm::dvec3(-20, -0.1, -20) * scale, glm::dvec3(20, 0, 20) * scale);
  b.box(glm::dvec3(-d - 0.1, 0, -20) * scale, glm::dvec3(-d, 20, 20) * scale);
  return b;
}

inline void traceFirstView(scenes::Scene scene, std::uint32_t width, std::uint32_t height, std::uint32_t guard,
                           double metersToViewUnits, TracedView& out) {
  out.scene = std::move(scene);
  ASSERT_TRUE(raytrace::RayScene::create(out.scene.mesh, out.rays).ok());
  out.camera = scenes::makeCamera(out.scene.views[0], width, height, INFINITY, ClipDepth::ZeroToOne, true, guard);
  out.camera.metersToViewUnits = metersToViewUnits;
  ASSERT_TRUE(raytrace::castPrimary(*out.rays, out.scene.views[0], out.camera, DepthFormat::D32F, out.primary).ok());
}

// The crease (d = 0) seen from its corner view, 48x32 + guard 3, in view units of `scale`.
inline void traceCrease(double scale, TracedView& out) {
  traceFirstView({"crease", creaseMesh(0.0, scale).build(),
                  {{"corner", glm::dvec3(2.0, 1.5, 1.0) * scale, glm::dvec3(0, 0, 0), {0, 1, 0}, 1.0, 0.1 * scale}}},
                 48, 32, 3, scale, out);
}

}  // namespace sao::truthtest
