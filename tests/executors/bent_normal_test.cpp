// The visibility estimator's bent normal output (bent_normals; docs/effect-math.md 5.10) in the
// caller's rgba16f and rgba8 output (bent normal in R, G, B, A in A) over the analytic scenes, with
// the variants the direct path combines with: every channel of each API against the CPU reference
// (float) and of GL against Vulkan, at the agreement bounds; the bent normals are unit vectors. An
// open plane facing an orthographic camera bends nothing: (0, 0, 1). The refusals (estimator 0, a
// blur, reduced resolution, temporal, a single-channel output, a channel mask, the multiply blend)
// are one contract with the CPU reference.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include "both_apis.h"

namespace sao::exectest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;

Settings directSettings() {
  Settings s;
  s.estimator = 1, s.bent_normals = true, s.blur_radius = 0, s.resolution_divisor = 1;
  return s;
}

Camera cameraOf(bool ortho) {
  Camera cam = ortho ? orthographicCamera(2.0, kW, kH, 0.1, 20.0, ClipDepth::NegativeOneToOne, false)
                     : test::openglCamera(kW, kH, kGuard, 100.0);
  cam.guardBand = kGuard;
  return cam;
}

struct Case {
  std::string name;
  std::function<void(Settings&)> tweak;
  bool ortho = false, normals = false, twoLayer = false;
  gen::Format format = gen::Format::RGBA16F;
};
std::string caseName(const Case& c) { return c.name + "_" + formatName(c.format); }

std::vector<Case> cases() {
  const std::vector<Case> variants = {
      {"direct", [](Settings&) {}},
      {"width_thickness", [](Settings& s) { s.thickness_model = 1, s.thickness = 1.0f; }},
      {"slices4_bounce", [](Settings& s) { s.slices = 4, s.samples = 32, s.albedo = 0.6f; }},
      {"two_layer_normals", [](Settings&) {}, false, true, true},
      {"ortho", [](Settings&) {}, true},
  };
  std::vector<Case> v;
  for (const Case& c : variants)
    for (gen::Format format : {gen::Format::RGBA16F, gen::Format::RGBA8}) v.push_back(c), v.back().format = format;
  return v;
}

// One scene's frame of a case, into the caller's rgba output (the images live in `this`).
struct SceneFrame {
  DepthImage depth, depth2;
  FloatImage normals;
  Frame frame;
  SceneFrame(const Case& c, const char* sceneName) {
    frame.settings = directSettings();
    c.tweak(frame.settings);
    frame.camera = cameraOf(c.ortho);
    const test::Scene scene = sceneByName(sceneName);
    depth = test::renderDepth(scene, frame.camera, DepthFormat::D32F);
    depth2 = test::renderDepth(scene, frame.camera, DepthFormat::D32F, 1);
    normals = test::renderNormals(scene, frame.camera);
    frame.depth = &depth;
    frame.depth2 = c.twoLayer ? &depth2 : nullptr;
    frame.normals = c.normals ? &normals : nullptr;
    frame.output = {true, c.format};
  }
  SceneFrame(const SceneFrame&) = delete;  // `frame` points into this one
};

constexpr const char* kScenes[] = {"plane", "crease", "sphere", "stairs", "rods"};

// Every channel of `actual` against `expected`: 99.9 % within 2/255, none beyond 4/255.
void expectAgree(Api api, const FloatImage& actual, const FloatImage& expected, const std::string& name) {
  ASSERT_EQ(actual.channels, 4u) << name;
  ASSERT_EQ(expected.channels, 4u) << name;
  double p999 = 0, max = 0;
  for (std::uint32_t c = 0; c < 4; ++c) {
    std::string note;
    const Agreement a = compare(api, actual, expected, c, kWithin, kNever, name + "_c" + std::to_string(c), &note);
    EXPECT_TRUE(acceptable(a)) << name << " channel " << c << ": " << a.fractionWithin * 100 << "% within 2/255, max "
                               << a.maxAbs * 255 << "/255, " << a.beyond << " beyond 4/255. " << note;
    p999 = std::max(p999, a.p999);
    max = std::max(max, a.maxAbs);
  }
  std::printf("%-44s worst channel p99.9 %.3f/255 max %.3f/255\n", name.c_str(), p999 * 255, max * 255);
}

using BentNormals = ApiCaseTest<Case>;
TEST_P(BentNormals, AgreeWithTheCpuReference) {
  auto e = make();
  for (const char* sceneName : kScenes) {
    SCOPED_TRACE(sceneName);
    const SceneFrame s(param(), sceneName);
    cpu::Result ref;
    const Status cs = runCpu(s.frame, ref);
    ASSERT_TRUE(cs.ok()) << cs.message;
    ASSERT_EQ(ref.plan.variants[std::size_t(gen::VariantId::BENT_NORMALS)], 1);
    const Status st = e->render(s.frame);
    ASSERT_TRUE(st.ok()) << st.message;
    expectAgree(api(), e->output(), ref.ao, "bent_" + caseName(param()) + "_" + sceneName);
    // The bent normals are unit vectors (rgba16f; rgba8 stores 0.5 + 0.5 b) wherever there is a surface.
    std::size_t notUnit = 0, surface = 0;
    const bool unorm = param().format == gen::Format::RGBA8;
    for (std::uint32_t y = 0; y < kH; ++y)
      for (std::uint32_t x = 0; x < kW; ++x) {
        double l2 = 0;
        for (std::uint32_t k = 0; k < 3; ++k) l2 += std::pow(unorm ? 2.0 * ref.ao.at(x, y, k) - 1.0 : ref.ao.at(x, y, k), 2);
        if (l2 < 0.25) continue;  // sky: 0 (rgba8: 0.5 rounded to 128/255, |b| = 0.007)
        ++surface;
        notUnit += std::abs(std::sqrt(l2) - 1.0) > (unorm ? 0.02 : 0.002);
      }
    EXPECT_GT(surface, 0u);
    EXPECT_EQ(notUnit, 0u) << "bent normals off unit length";
  }
}
SAO_INSTANTIATE_API_CASES(BentNormals, cases());

// GL against Vulkan, every channel within the same bounds.
using BentNormalsGlVulkan = BothApis<::testing::TestWithParam<Case>>;
TEST_P(BentNormalsGlVulkan, Agree) {
  for (const char* sceneName : kScenes) {
    SCOPED_TRACE(sceneName);
    const SceneFrame s(GetParam(), sceneName);
    for (Executor* e : {gl.get(), vk.get()}) {
      const Status st = e->render(s.frame);
      ASSERT_TRUE(st.ok()) << toString(e->api()) << ": " << st.message;
    }
    expectAgree(Api::Vulkan, vk->output(), gl->output(), "bent_" + caseName(GetParam()) + "_" + sceneName + "_gl_vk");
  }
}
INSTANTIATE_TEST_SUITE_P(Cases, BentNormalsGlVulkan, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return caseName(info.param); });

using BentNormalsApi = ApiTest;

// An open plane facing an orthographic camera: every ray of the hemisphere is clear and V = n, so
// each slice's moment lies along n and the bent normal is (0, 0, 1) on every backend and in double.
TEST_P(BentNormalsApi, OpenPlaneFacingTheCameraBendsNothing) {
  Frame f;
  f.settings = directSettings();
  f.camera = cameraOf(true);
  const DepthImage depth = test::renderDepth(test::planeScene(3.0), f.camera, DepthFormat::D32F);
  f.depth = &depth;
  f.output = {true, gen::Format::RGBA16F};
  cpu::Inputs in;
  in.depth = &depth;
  in.outputFormat = f.output.format;
  cpu::Result exact, ref;
  ASSERT_TRUE(cpu::run(f.settings, f.camera, in, {cpu::Precision::Double, 2}, exact).ok());
  ASSERT_TRUE(runCpu(f, ref).ok());
  auto e = make();
  ASSERT_TRUE(e->render(f).ok());
  FloatImage out = e->output();
  for (const auto& [label, img, tol] : {std::tuple{"double", &exact.ao, 1e-9}, std::tuple{"float", &ref.ao, 1e-3},
                                       std::tuple{toString(api()), &out, 1e-3}}) {
    double worst = 0;
    for (std::uint32_t y = 0; y < kH; ++y)
      for (std::uint32_t x = 0; x < kW; ++x)
        worst = std::max({worst, std::abs(double(img->at(x, y, 0))), std::abs(double(img->at(x, y, 1))),
                          std::abs(double(img->at(x, y, 2)) - 1.0), std::abs(double(img->at(x, y, 3)) - 1.0)});
    EXPECT_LE(worst, tol) << label << ": (R, G, B, A) off (0, 0, 1, 1) by " << worst;
    std::printf("open plane, %-7s largest |(R, G, B, A) - (0, 0, 1, 1)| %.3g\n", label, worst);
  }
}

// Each refusal, with the same words from the CPU reference and the API: the effect's own r16f
// output, the caller's r8 / rgba8 / rgba16f one.
TEST_P(BentNormalsApi, RefusalsAreOneContract) {
  const Camera cam = cameraOf(false);
  const DepthImage depth = test::renderDepth(sceneByName("crease"), cam, DepthFormat::D32F);
  const FloatImage zero(Extent{cam.width, cam.height}, 4);
  struct Refusal {
    std::string name, words;  // `words`: in every backend's message
    std::function<void(Settings&)> tweak = [](Settings&) {};
    gen::Format format = gen::Format::RGBA16F;
    std::uint32_t channels = kAllChannels;
    OutputBlend blend = OutputBlend::Replace;
  };
  const auto keep = [](Settings&) {};
  const std::vector<Refusal> refusals = {
      {"estimator0", "setting 'bent_normals' = true is refused while estimator = 0", [](Settings& s) { s.estimator = 0; }},
      {"blur", "setting 'bent_normals' = true is refused while blur_radius > 0, resolution_divisor > 1 or temporal = true",
       [](Settings& s) { s.blur_radius = 1; }},
      {"half_resolution", "also set blur_radius = 0, resolution_divisor = 1 and temporal = false, or drop bent_normals",
       [](Settings& s) { s.resolution_divisor = 2; }},
      {"temporal", "ao_sample_output alone writes the bent normal", [](Settings& s) { s.temporal = true; }},
      {"r16f", "bent normals need an rgba output (rgba8 or rgba16f)", keep, gen::Format::R16F},
      {"r8", "bent normals need an rgba output (rgba8 or rgba16f)", keep, gen::Format::R8},
      {"mask", "it needs the output channel mask kAllChannels (15, got 7)", keep, gen::Format::RGBA8,
       kChannelR | kChannelG | kChannelB},
      {"multiply", "and output blend replace (got multiply)", keep, gen::Format::RGBA16F, kAllChannels,
       OutputBlend::Multiply},
  };
  for (const Refusal& r : refusals) {
    SCOPED_TRACE(r.name);
    Frame f;
    f.settings = directSettings();
    r.tweak(f.settings);
    f.camera = cam;
    f.depth = &depth;
    const bool rgba = gen::formatInfo(r.format).channels == 4;
    f.output = {r.format != gen::Format::R16F, r.format, rgba ? &zero : nullptr, r.channels, r.blend};
    cpu::Result ref;
    const Status cs = runCpu(f, ref);
    EXPECT_FALSE(cs.ok());
    EXPECT_NE(cs.message.find(r.words), std::string::npos) << "CPU: " << cs.message;
    const Status st = make()->render(f);
    EXPECT_FALSE(st.ok());
    EXPECT_NE(st.message.find(r.words), std::string::npos) << toString(api()) << ": " << st.message;
  }
}
SAO_INSTANTIATE_APIS(BentNormalsApi);

}  // namespace
}  // namespace sao::exectest
