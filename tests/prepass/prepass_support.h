// Shared by the prepass tests: one GL prepass (own headless debug context) and one Vulkan prepass
// (own headless device with validation and synchronization validation) per process, a fixture that
// fails a test on any GL error / undefined-behaviour message or any validation message it caused,
// the built-in scenes with their ray scenes, and the comparisons with the ray cast.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "sao/prepass/prepass.h"
#include "sao/raytrace/raytrace.h"
#include "sao/scenes/scene.h"

#ifdef SAO_PREPASS_HAVE_GL
#include "sao/prepass/gl_prepass.h"
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
#include "sao/prepass/vk_prepass.h"
#endif

namespace sao::prepasstest {

#ifdef SAO_PREPASS_HAVE_GL
prepass::GlPrepass& glPrepass();
#endif
#ifdef SAO_PREPASS_HAVE_VULKAN
prepass::VkPrepass& vkPrepass();
#endif
// The backends this build has, by name ("gl", "vulkan").
std::vector<std::string> backendNames();
prepass::Prepass& backend(const std::string& name);

class PrepassTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;  // fails on GL error / undefined-behaviour messages, any Vulkan message
};

struct LoadedScene {
  scenes::Scene scene;
  std::unique_ptr<raytrace::RayScene> rays;
};
const LoadedScene& loadScene(const std::string& name);  // cached for the process

// A depth convention to render with.
struct Convention {
  const char* name;
  ClipDepth clip;
  bool reversed;
  double farDistance;  // INFINITY for an infinite far plane
};

// The stored-depth quantum of the format at window depth d: 1 / (2^n - 1) for unorm, the float
// spacing at d for D32F.
double depthQuantum(DepthFormat format, double d);
// |dz/dd| of the camera at camera-space z (from eq. 2: z^2 |c1 / c0| for perspective).
double dzdd(const DepthModel& model, double z);

// Rasterised against ray-cast, per pixel of the depth image.
struct RayAgreement {
  std::size_t pixels = 0;
  std::size_t coverageMismatch = 0;      // covered in one and not the other
  std::size_t mismatchOffSilhouette = 0;  // of those, where the ray cast's 3x3 coverage is uniform
  std::size_t surfaceMismatch = 0;        // covered in both, but by different surfaces (|dz| > 100 bounds)
  std::size_t interior = 0;               // pixels inside a face (3x3 on one plane in the ray cast)
  double zWorstAbs = 0;        // worst |z raster - z ray| at interior pixels, view units
  double zWorstRelative = 0;   // worst |dz| / |z|
  double zWorstQuanta = 0;     // worst |dz| / (|dz/dd| * quantum(d)): the error in stored-depth steps
  double zWorstBoundRatio = 0; // worst |dz| / bound (see zBound)
  double normalWorstDeg = 0;   // worst angle between raster and ray-cast normals at interior pixels
  double positionWorstRel = 0; // worst |p raster - p ray| / |p ray| at interior pixels
};
// The bound on |dz| the tests hold the prepass to: the stored depth may be off by one quantum of
// the format plus 8 float ulps of the window depth's computation (the float MVP, the perspective
// division, the [-1,1] -> [0,1] mapping), mapped through dz/dd; plus 1e-6 |z| for the ray cast's own
// float hit distance, plus 8 float ulps of `worldScale` (the largest world coordinate the float
// transform adds up: a point near the camera far from the world origin has a larger relative error).
double zBound(const Camera& camera, const DepthModel& model, DepthFormat format, double z, double d, double worldScale);

// The largest |coordinate| of the mesh and the eye.
double worldScale(const scenes::Mesh& mesh, const scenes::View& view);

RayAgreement compareWithRayCast(const prepass::PrepassResult& raster, const raytrace::Primary& ray,
                                const Camera& camera, DepthFormat format, double worldScale);

std::string describe(const RayAgreement& a);

}  // namespace sao::prepasstest
