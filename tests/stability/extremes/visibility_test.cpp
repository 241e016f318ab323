// The visibility estimator (estimator = 1) at the extremes, on every backend (runScene: finite,
// in [0, 1], sky = 1, GL = Vulkan): radius 0.01 and 100 m, thickness 0.001 and 100 m,
// depth_tolerance 0 and 0.1, 1 and 8 slices with 1 and 64 samples, thickness_model 1 (a cap under
// its least thickness, huge radius and cap, a tiny radius), temporal, and far depths (a
// scene 1000x farther, reversed and standard depth).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "extremes_support.h"

namespace sao::stability {
namespace {

// The three views of both tests: perspective (D24 here), orthographic, and reversed infinite (far depths).
const Camera& perspCamera() {
  static const Camera c = camera(64, 48, 0.1, 1e4, ClipDepth::NegativeOneToOne, false, 8);
  return c;
}
const Camera& farCamera() {
  static const Camera c = camera(64, 48, 0.1, kInf, ClipDepth::ZeroToOne, true, 8);
  return c;
}
const Camera& orthographicCamera() {
  static const Camera c = orthoCamera(64, 48, 0.1, 100.0, ClipDepth::ZeroToOne, true, 8, 3.0);
  return c;
}

// The settings' extremes both tests run, each on top of estimator 1 at full resolution.
struct Tweak {
  std::string name;
  void (*apply)(Settings&);
};
const std::vector<Tweak>& tweaks() {
  static const std::vector<Tweak> list = {
      {"defaults", [](Settings&) {}},
      {"radius 0.01", [](Settings& s) { s.radius = 0.01f; }},
      {"radius 100", [](Settings& s) { s.radius = 100.0f; }},
      {"thickness 0.001", [](Settings& s) { s.thickness = 0.001f; }},
      {"thickness 100", [](Settings& s) { s.thickness = 100.0f; }},
      {"depth_tolerance 0", [](Settings& s) { s.depth_tolerance = 0.0f; }},
      {"depth_tolerance 0.1 radius 100", [](Settings& s) { s.depth_tolerance = 0.1f, s.radius = 100.0f; }},
      {"slices 8 samples 1", [](Settings& s) { s.slices = 8, s.samples = 1; }},
      {"slices 8 samples 64", [](Settings& s) { s.slices = 8, s.samples = 64; }},
      {"slices 1 samples 64 intensity 10 contrast 8", [](Settings& s) { s.slices = 1, s.samples = 64, s.intensity = 10.0f, s.contrast = 8.0f; }},
      {"thickness_model 1 thickness 0.001", [](Settings& s) { s.thickness_model = 1, s.thickness = 0.001f; }},
      {"thickness_model 1 thickness 100 radius 100", [](Settings& s) { s.thickness_model = 1, s.thickness = 100.0f, s.radius = 100.0f; }},
      {"thickness_model 1 radius 0.01 slices 8 samples 64", [](Settings& s) { s.thickness_model = 1, s.radius = 0.01f, s.slices = 8, s.samples = 64; }},
  };
  return list;
}

// Runs every tweak (estimator 1 at full resolution; with bentNormals the bent normal on the direct
// path) on the three views, then a floor and a wall 1 and 5 km away at radius and thickness 100 m,
// handing each scene's runs to `visit` with their label.
template <class Visit>
void runExtremes(bool bentNormals, Visit visit) {
  auto run = [&](const std::string& label, const Settings& s, const Camera& cam, const test::Scene& scene,
                 DepthFormat fm) { visit(label, runScene(label, s, cam, scene, fm)); };
  Settings base = fullResolution();
  base.estimator = 1;
  if (bentNormals) base.bent_normals = true, base.blur_radius = 0;
  for (const Tweak& t : tweaks()) {
    Settings s = base;
    t.apply(s);
    ASSERT_TRUE(validate(s).ok()) << t.name;
    run(t.name + " persp", s, perspCamera(), test::sphereOnPlaneScene(), DepthFormat::D24);
    run(t.name + " ortho", s, orthographicCamera(), test::creaseScene(5.0), DepthFormat::D32F);
    // Far depths: the stairs 1000x farther (a 3 km wide flight at 2 km and beyond), reversed infinite.
    run(t.name + " far", s, farCamera(), test::stairsScene(), DepthFormat::D32F);
  }
  Settings far = base;
  far.radius = 100.0f;
  far.thickness = 100.0f;
  test::Scene distant{"distant_planes", {}, {}, {}, {}};
  distant.planes.push_back({{0, -1000, 0}, {0, 1, 0}, {}});
  distant.planes.push_back({{0, 0, -5000}, {0, 0, 1}, {}});
  run("far floor and wall (5 km)", far, farCamera(), distant, DepthFormat::D32F);
}

TEST(VisibilityEstimator, ExtremesStayInZeroOne) {
  double lo = 1, hi = 0;
  std::size_t runs = 0;
  runExtremes(false, [&](const std::string& label, const SceneRun& r) {
    for (const BackendRun& b : r.runs.runs) {
      ++runs;
      const Range a = range(b.out.ao);
      EXPECT_TRUE(allFinite(b.out.ao)) << label << " on " << b.name;
      EXPECT_GE(a.min, 0.0) << label << " on " << b.name;
      EXPECT_LE(a.max, 1.0) << label << " on " << b.name;
      lo = std::min(lo, a.min);
      hi = std::max(hi, a.max);
    }
  });
  report("visibility estimator at the extremes (radius, thickness, depth_tolerance, slices x samples, far depths; "
         "persp, ortho, reversed infinite)",
         "A finite and in [0,1]", fmt("%zu runs: A in [%.4f, %.4f]", runs, lo, hi));
}

// The bent normal (bent_normals, the direct path's rgba16f output through the runners) at the same
// extremes: on every backend finite, unit length on geometry (to binary16's rounding) and 0 on sky,
// GL = Vulkan within the bent normal's agreement bound (tests/executors/bent_normal_test.cpp: 4/255).
TEST(VisibilityEstimator, BentNormalsAtTheExtremesAreUnitAndFinite) {
  double worstLength = 0, worstGpu = 0;
  std::size_t runs = 0;
  runExtremes(true, [&](const std::string& label, const SceneRun& r) {
    for (const BackendRun& b : r.runs.runs) {
      ++runs;
      const FloatImage& bent = b.out.bentNormals;
      ASSERT_EQ(bent.channels, 3u) << label << " on " << b.name;
      ASSERT_EQ(bent.extent, b.out.ao.extent) << label << " on " << b.name;
      EXPECT_TRUE(allFinite(bent)) << label << " on " << b.name;
      for (std::uint32_t y = 0; y < bent.extent.height; ++y)
        for (std::uint32_t x = 0; x < bent.extent.width; ++x) {
          const double bx = bent.at(x, y, 0), by = bent.at(x, y, 1), bz = bent.at(x, y, 2);
          const double length = std::sqrt(bx * bx + by * by + bz * bz);
          if (r.sky[std::size_t(y) * bent.extent.width + x]) {
            EXPECT_EQ(length, 0.0) << label << " on " << b.name << ": sky pixel " << x << "," << y;
          } else {
            worstLength = std::max(worstLength, std::abs(length - 1.0));
            EXPECT_NEAR(length, 1.0, 2e-3) << label << " on " << b.name << ": pixel " << x << "," << y;
          }
        }
    }
    const BackendRun* gl = r.runs.find("gl");
    const BackendRun* vk = r.runs.find("vulkan");
    if (gl && vk) {
      const double d = maxAbsDiff(gl->out.bentNormals, vk->out.bentNormals);
      worstGpu = std::max(worstGpu, d);
      EXPECT_LE(d, 4.0 / 255.0) << label << ": GL and Vulkan bent normals differ";
    }
  });
  report("bent normal at the extremes (radius, thickness, depth_tolerance, slices x samples, width model, far "
         "depths; persp, ortho, reversed infinite)",
         "finite, unit on geometry, 0 on sky, GL = Vulkan <= 4/255",
         fmt("%zu runs: | |b| - 1 | <= %.2g, GL vs Vulkan <= %.3g", runs, worstLength, worstGpu));
}

}  // namespace
}  // namespace sao::stability
