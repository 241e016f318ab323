// The visibility estimator (estimator = 1, ESTIMATOR) on OpenGL, Vulkan and the CPU reference (float)
// over the built-in analytic scenes, 160x90 + guard 8, D32F and D24: every variant it combines with
// (reduced and full resolution, direct output, TWO_LAYER, NORMALS_SUPPLIED, TEMPORAL, ortho, no
// hierarchy, more slices). GL and Vulkan each agree with the CPU as the reference tests require (at
// least 99.9 % of the pixels within 2/255, none beyond 4/255: atan and cos are not correctly rounded
// on a GPU, so a tap's bit can flip) and with each other by the same bounds (their compilers contract
// and order the angle arithmetic differently: bits flip between them too). An open plane is 1 to within one
// r16f step on both GPUs. Prints the figures (max and p99.9 per pair) at the end.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "analytic_scenes.h"
#include "gl_support.h"
#include "sao/cpu/reference.h"
#include "sao/gl/effect.h"
#include "sao/gl/headless.h"
#include "vk_gl_fixture.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;
constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

struct Pair {
  double max = 0, p999 = 0;
};
struct Figures {
  Pair glCpu, vkCpu, glVk;
};
Figures gAll;

class Summary : public ::testing::Environment {
 public:
  void TearDown() override {
    std::printf("\nvisibility estimator, worst over every case (final and raw AO, units of 1/255):\n"
                "  |GL - CPU| max %.4f p99.9 %.4f\n  |Vulkan - CPU| max %.4f p99.9 %.4f\n  |GL - Vulkan| max %.4f "
                "p99.9 %.4f\n",
                gAll.glCpu.max * 255, gAll.glCpu.p999 * 255, gAll.vkCpu.max * 255, gAll.vkCpu.p999 * 255,
                gAll.glVk.max * 255, gAll.glVk.p999 * 255);
  }
};
const auto* const kSummary = ::testing::AddGlobalTestEnvironment(new Summary);

void fold(Pair& p, const Agreement& a) {
  p.max = std::max(p.max, a.maxAbs);
  p.p999 = std::max(p.p999, a.p999);
}

GLuint uploadGlDepth(const DepthImage& depth, VkDepth format) {
  return gltest::uploadDepth(depth, format == VkDepth::D32F ? gl::GlDepth::D32F : gl::GlDepth::D24);
}

struct Case {
  std::string name;
  std::function<void(Settings&)> tweak;
  bool ortho = false, normals = false, twoLayer = false;
};

Camera cameraOf(const Case& c) {
  Camera cam = c.ortho ? orthographicCamera(2.0, kW, kH, 0.1, 20.0, ClipDepth::NegativeOneToOne, false)
                       : openglCamera(kW, kH, kGuard, 100.0);
  cam.guardBand = kGuard;
  cam.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // for TEMPORAL
  return cam;
}

std::vector<Case> cases() {
  return {
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
}

class VisibilityEstimator : public VkWithGl, public ::testing::WithParamInterface<std::tuple<std::size_t, VkDepth>> {};

TEST_P(VisibilityEstimator, GlVulkanAndCpuAgree) {
  const auto [index, format] = GetParam();
  const Case c = cases()[index];
  Settings settings;
  settings.estimator = 1;
  c.tweak(settings);
  const Camera cam = cameraOf(c);
  for (const char* sceneName : {"plane", "crease", "sphere", "stairs", "rods"}) {
    SCOPED_TRACE(sceneName);
    const test::Scene scene = gltest::sceneByName(sceneName);
    const DepthImage depth = test::renderDepth(scene, cam, cpuFormat(format));
    const DepthImage depth2 = test::renderDepth(scene, cam, cpuFormat(format), 1);
    const FloatImage normals = test::renderNormals(scene, cam);
    // CPU (float)
    cpu::Result ref;
    cpu::Inputs ci;
    ci.depth = &depth;
    if (c.twoLayer) ci.depth2 = &depth2;
    if (c.normals) ci.normals = &normals;
    const Status cs = cpu::run(settings, cam, ci, {cpu::Precision::Float, 2}, ref);
    ASSERT_TRUE(cs.ok()) << cs.message;
    ASSERT_EQ(ref.plan.variants[std::size_t(gen::VariantId::ESTIMATOR)], 1);
    // OpenGL: a fresh effect per scene, as runEffect's (a kept one would hold TEMPORAL's history)
    std::unique_ptr<gl::Effect> glEffect;
    ASSERT_TRUE(gl::Effect::create(gl::HeadlessContext::getProcAddress(), glEffect).ok());
    const GLuint tex = uploadGlDepth(depth, format);
    const GLuint tex2 = c.twoLayer ? uploadGlDepth(depth2, format) : 0;
    const GLuint ntex = c.normals ? gltest::uploadNormals(normals) : 0;
    gl::Inputs gi;
    gi.depth = {tex, gl::internalFormat(format == VkDepth::D32F ? gl::GlDepth::D32F : gl::GlDepth::D24)};
    if (c.twoLayer) gi.depth2 = {tex2, gi.depth.internalFormat};
    gi.normals = ntex;
    const Status rs = glEffect->render(cam, settings, gi);
    ASSERT_TRUE(rs.ok()) << rs.message;
    const FloatImage glAo = gl::readTexture(glEffect->aoTexture(), 1);
    const bool hasRaw = !ref.aoRaw.data.empty();
    const FloatImage glRaw = hasRaw ? gl::readTexture(glEffect->texture(gen::ResourceId::ao_raw), 2) : FloatImage{};
    gltest::deleteTexture(tex);
    gltest::deleteTexture(tex2);
    gltest::deleteTexture(ntex);
    // Vulkan
    RunResult vk;
    RunOptions o;
    if (c.twoLayer) o.depth2 = &depth2;
    if (c.normals) o.normals = &normals;
    o.readIntermediates = hasRaw;
    const Status vs = runEffect(settings, cam, depth, format, vk, o);
    ASSERT_TRUE(vs.ok()) << vs.message;
    EXPECT_EQ(std::memcmp(&vk.params, &ref.params, sizeof(ParamBlock)), 0) << "same parameter block";

    const std::string name = "vis_" + c.name + "_" + toString(format) + "_" + sceneName;
    std::string note;
    const Agreement gf = compare(glAo, ref.ao, 0, kWithin, kNever, name + "_gl_final", &note);
    EXPECT_TRUE(acceptable(gf)) << "GL final: " << gf.fractionWithin * 100 << "% within 2/255, " << gf.beyond
                                << " beyond 4/255, max " << gf.maxAbs * 255 << "/255. " << note;
    const Agreement vf = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_vk_final", &note);
    EXPECT_TRUE(acceptable(vf)) << "Vulkan final: " << vf.fractionWithin * 100 << "% within 2/255, " << vf.beyond
                                << " beyond 4/255, max " << vf.maxAbs * 255 << "/255. " << note;
    const Agreement xf = compare(vk.ao, glAo, 0, kWithin, kNever, name + "_gl_vk_final", &note);
    EXPECT_TRUE(acceptable(xf)) << "GL vs Vulkan final: max " << xf.maxAbs * 255 << "/255. " << note;
    fold(gAll.glCpu, gf);
    fold(gAll.vkCpu, vf);
    fold(gAll.glVk, xf);
    if (hasRaw) {
      const Agreement gr = compare(glRaw, ref.aoRaw, 0, kWithin, kNever, name + "_gl_raw", &note);
      EXPECT_TRUE(acceptable(gr)) << "GL raw: max " << gr.maxAbs * 255 << "/255. " << note;
      const Agreement vr = compare(vk.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_vk_raw", &note);
      EXPECT_TRUE(acceptable(vr)) << "Vulkan raw: max " << vr.maxAbs * 255 << "/255. " << note;
      const Agreement xr = compare(vk.aoRaw, glRaw, 0, kWithin, kNever, name + "_gl_vk_raw", &note);
      EXPECT_TRUE(acceptable(xr)) << "GL vs Vulkan raw: max " << xr.maxAbs * 255 << "/255. " << note;
      fold(gAll.glCpu, gr);
      fold(gAll.vkCpu, vr);
      fold(gAll.glVk, xr);
      std::printf("%-28s %-5s %-7s final |GL-CPU| %.3f/%.3f |VK-CPU| %.3f/%.3f |GL-VK| %.3f | raw |GL-CPU| %.3f/%.3f "
                  "|VK-CPU| %.3f/%.3f (max/p99.9, 1/255)\n",
                  c.name.c_str(), toString(format), sceneName, gf.maxAbs * 255, gf.p999 * 255, vf.maxAbs * 255,
                  vf.p999 * 255, xf.maxAbs * 255, gr.maxAbs * 255, gr.p999 * 255, vr.maxAbs * 255, vr.p999 * 255);
    } else {
      std::printf("%-28s %-5s %-7s final |GL-CPU| %.3f/%.3f |VK-CPU| %.3f/%.3f |GL-VK| %.3f (max/p99.9, 1/255)\n",
                  c.name.c_str(), toString(format), sceneName, gf.maxAbs * 255, gf.p999 * 255, vf.maxAbs * 255,
                  vf.p999 * 255, xf.maxAbs * 255);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, VisibilityEstimator,
                         ::testing::Combine(::testing::Range(std::size_t{0}, cases().size()),
                                            ::testing::Values(VkDepth::D32F, VkDepth::X8D24)),
                         [](const auto& info) {
                           return cases()[std::get<0>(info.param)].name + "_" + toString(std::get<1>(info.param));
                         });

// An open plane (facing the camera, and a floor under sky) is 1 on both GPUs to within one r16f
// step below 1 (2^-11): the CPU's double is exactly 1 (tests/cpu/visibility_estimator_test.cpp).
TEST_F(VisibilityEstimator, OpenPlaneIsOneOnBothGpus) {
  test::Scene floor{"floor", {}, {}, {}, {}};
  floor.planes.push_back({{0, -1, 0}, {0, 1, 0}, {}});
  std::unique_ptr<gl::Effect> glEffect;
  ASSERT_TRUE(gl::Effect::create(gl::HeadlessContext::getProcAddress(), glEffect).ok());
  const Camera cam = openglCamera(kW, kH, kGuard, 100.0);
  for (const test::Scene& scene : {test::planeScene(3.0), floor}) {
    for (int divisor : {1, 2}) {
      SCOPED_TRACE(scene.name + " divisor " + std::to_string(divisor));
      Settings s;
      s.estimator = 1;
      s.resolution_divisor = divisor;
      s.radius = 2.0f;
      const DepthImage depth = test::renderDepth(scene, cam, DepthFormat::D32F);
      const GLuint tex = uploadGlDepth(depth, VkDepth::D32F);
      gl::Inputs gi;
      gi.depth = {tex, gl::internalFormat(gl::GlDepth::D32F)};
      ASSERT_TRUE(glEffect->render(cam, s, gi).ok());
      const FloatImage glAo = gl::readTexture(glEffect->aoTexture(), 1);
      gltest::deleteTexture(tex);
      RunResult vk;
      ASSERT_TRUE(runEffect(s, cam, depth, VkDepth::D32F, vk).ok());
      const float step = 1.0f - 1.0f / 2048.0f;
      std::size_t glBelow = 0, vkBelow = 0;
      for (float v : glAo.data) glBelow += !(v >= step);
      for (float v : vk.ao.data) vkBelow += !(v >= step);
      EXPECT_EQ(glBelow, 0u) << "GL pixels below 1 - 2^-11";
      EXPECT_EQ(vkBelow, 0u) << "Vulkan pixels below 1 - 2^-11";
    }
  }
}

}  // namespace
}  // namespace sao::vktest
