// The visibility estimator (estimator = 1) over the analytic scenes, 160x90 + guard 8, D32F and D24,
// with every variant it combines with: each API against the CPU reference (float, computed once per
// scene) and GL against Vulkan, at the agreement bounds (atan and cos are not correctly rounded on a GPU, and the
// compilers contract and order the angle arithmetic differently: a tap's bit can flip between any
// two of them). An open plane is 1 to within one r16f step.
#include <algorithm>
#include <array>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "harness.h"

namespace sao::exectest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;

struct Case {
  std::string name;
  std::function<void(Settings&)> tweak;
  bool ortho = false, normals = false, twoLayer = false;
  Depth format = Depth::D32F;
};
std::string caseName(const Case& c) { return c.name + "_" + toString(c.format); }

std::vector<Case> cases() {
  const std::vector<Case> variants = {
      {"default", [](Settings&) {}},
      {"full_res_direct", [](Settings& s) { s.resolution_divisor = 1, s.blur_radius = 0; }},
      {"quarter_res", [](Settings& s) { s.resolution_divisor = 4; }},
      {"slices4_r2_s64", [](Settings& s) { s.slices = 4, s.samples = 64, s.radius = 2.0f; }},
      {"slices1_s5_thick", [](Settings& s) { s.slices = 1, s.samples = 5, s.thickness = 5.0f, s.depth_tolerance = 0; }},
      {"no_hierarchy", [](Settings& s) { s.use_z_hierarchy = false, s.resolution_divisor = 1; }},
      {"temporal", [](Settings& s) { s.temporal = true; }},
      {"rg32f", [](Settings& s) { s.half_intermediates = false, s.contrast = 1.0f, s.intensity = 2.0f; }},
      {"two_layer", [](Settings&) {}, false, false, true},
      {"normals", [](Settings&) {}, false, true, false},
      {"two_layer_normals_full_res", [](Settings& s) { s.resolution_divisor = 1; }, false, true, true},
      {"ortho", [](Settings&) {}, true},
      {"width_thickness", [](Settings& s) { s.thickness_model = 1, s.thickness = 1.0f; }},
      {"width_thickness_full_res_ortho", [](Settings& s) { s.thickness_model = 1, s.resolution_divisor = 1; }, true},
  };
  std::vector<Case> v;
  for (const Case& c : variants)
    for (Depth format : {Depth::D32F, Depth::D24}) v.push_back(c), v.back().format = format;
  return v;
}

// One scene's frame of a case: its settings, camera and inputs (the images live in `this`).
struct SceneFrame {
  DepthImage depth, depth2;
  FloatImage normals;
  Frame frame;
  SceneFrame(const Case& c, const char* sceneName) {
    Camera& cam = frame.camera = c.ortho ? orthographicCamera(2.0, kW, kH, 0.1, 20.0, ClipDepth::NegativeOneToOne, false)
                                         : test::openglCamera(kW, kH, kGuard, 100.0);
    cam.guardBand = kGuard;
    cam.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // for TEMPORAL
    frame.settings.estimator = 1;
    c.tweak(frame.settings);
    const test::Scene scene = sceneByName(sceneName);
    depth = test::renderDepth(scene, cam, cpuFormat(c.format));
    depth2 = test::renderDepth(scene, cam, cpuFormat(c.format), 1);
    normals = test::renderNormals(scene, cam);
    frame.format = c.format;
    frame.depth = &depth;
    frame.depth2 = c.twoLayer ? &depth2 : nullptr;
    frame.normals = c.normals ? &normals : nullptr;
  }
  SceneFrame(const SceneFrame&) = delete;  // `frame` points into this one
};

constexpr const char* kScenes[] = {"plane", "crease", "sphere", "stairs", "rods"};

// Each case once per scene: the CPU reference computed once, every API against it, and GL against
// Vulkan (the final AO and, when planned, the raw AO) within the same bounds.
class VisibilityEstimator : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    for (Api a : apis()) checkMessagesBefore(a);
  }
  void TearDown() override {
    for (Api a : apis()) checkMessagesAfter(a);
  }
};
TEST_P(VisibilityEstimator, EveryApiAgreesWithTheCpuReferenceAndTheOther) {
  for (const char* sceneName : kScenes) {
    SCOPED_TRACE(sceneName);
    const SceneFrame s(GetParam(), sceneName);
    cpu::Result ref;
    const Status cs = runCpu(s.frame, ref);
    ASSERT_TRUE(cs.ok()) << cs.message;
    ASSERT_EQ(ref.plan.variants[std::size_t(gen::VariantId::ESTIMATOR)], 1);
    const std::string name = "vis_" + caseName(GetParam()) + "_" + sceneName;
    std::vector<std::unique_ptr<Executor>> executors;
    for (Api api : apis()) {
      executors.push_back(makeExecutor(api));  // a fresh effect per scene: a kept one would hold TEMPORAL's history
      const Status st = executors.back()->render(s.frame);
      ASSERT_TRUE(st.ok()) << toString(api) << ": " << st.message;
      expectAgreesWithCpu(*executors.back(), ref, name);
    }
    if (executors.size() < 2) continue;
    Executor &gl = *executors[0], &vk = *executors[1];
    for (const bool final : {true, false}) {
      const auto id = final ? gen::ResourceId::ao : gen::ResourceId::ao_raw;
      if (!final && gl.plan().image(id) == nullptr) continue;  // the direct path plans no raw AO
      std::string note;
      const Agreement a = compare(Api::Vulkan, final ? vk.output() : vk.image(id), final ? gl.output() : gl.image(id), 0,
                                  kWithin, kNever, name + "_gl_vk" + (final ? "_final" : "_raw"), &note);
      std::printf("%-48s %-5s max %.3f/255 p99.9 %.3f/255\n", (name + "_gl_vk").c_str(), final ? "final" : "raw",
                  a.maxAbs * 255, a.p999 * 255);
      EXPECT_TRUE(acceptable(a)) << (final ? "final" : "raw") << ": max " << a.maxAbs * 255 << "/255. " << note;
    }
  }
}
INSTANTIATE_TEST_SUITE_P(Cases, VisibilityEstimator, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return caseName(info.param); });

// An open plane (facing the camera, and a floor under sky) is 1 to within one r16f step below 1
// (2^-11): the CPU's double is exactly 1 (tests/cpu/visibility_estimator_test.cpp).
using VisibilityEstimatorApi = ApiTest;
TEST_P(VisibilityEstimatorApi, OpenPlaneIsOne) {
  test::Scene floor{"floor", {}, {}, {}, {}};
  floor.planes.push_back({{0, -1, 0}, {0, 1, 0}, {}});
  auto e = make();
  Frame f;
  f.camera = test::openglCamera(kW, kH, kGuard, 100.0);
  f.settings.estimator = 1;
  f.settings.radius = 2.0f;
  for (const test::Scene& scene : {test::planeScene(3.0), floor}) {
    const DepthImage depth = test::renderDepth(scene, f.camera, DepthFormat::D32F);
    f.depth = &depth;
    for (int divisor : {1, 2}) {
      SCOPED_TRACE(scene.name + " divisor " + std::to_string(divisor));
      f.settings.resolution_divisor = divisor;
      ASSERT_TRUE(e->render(f).ok());
      const FloatImage ao = e->output();
      EXPECT_EQ(std::count_if(ao.data.begin(), ao.data.end(), [](float v) { return !(v >= 1.0f - 1.0f / 2048.0f); }), 0)
          << "pixels below 1 - 2^-11";
    }
  }
}
SAO_INSTANTIATE_APIS(VisibilityEstimatorApi);

}  // namespace
}  // namespace sao::exectest
