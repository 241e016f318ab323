// The visibility estimator's bent normal output (bent_normals, BENT_NORMALS; docs/effect-math.md
// 5.10) on OpenGL, Vulkan and the CPU reference (float): every channel of an rgba16f and an rgba8
// output (bent normal in R, G, B, A in A) over the built-in analytic scenes, with the variants the
// direct path combines with (supplied normals, a second layer, thickness from width, ortho). GL and
// Vulkan each agree with the CPU as the reference tests require (at least 99.9 % of the texels
// within 2/255, none beyond 4/255) and with each other, every channel; the worst figures are
// printed at the end. The stored bent normals are unit vectors. An open plane
// facing an orthographic camera bends nothing: (0, 0, 1). The refusals are one contract on the
// three backends: estimator 0, a blur, reduced resolution, temporal accumulation, a single-channel
// output, a channel mask and the multiply blend each fail with the rule's message.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

Settings directSettings() {
  Settings s;
  s.estimator = 1;
  s.bent_normals = true;
  s.blur_radius = 0;
  s.resolution_divisor = 1;
  return s;
}

struct Case {
  std::string name;
  std::function<void(Settings&)> tweak;
  bool ortho = false, normals = false, twoLayer = false;
};

std::vector<Case> cases() {
  return {
      {"direct", [](Settings&) {}},
      {"width_thickness", [](Settings& s) { s.thickness_model = 1, s.thickness = 1.0f; }},
      {"slices4_bounce", [](Settings& s) { s.slices = 4, s.samples = 32, s.albedo = 0.6f; }},
      {"two_layer_normals", [](Settings&) {}, false, true, true},
      {"ortho", [](Settings&) {}, true},
  };
}

Camera cameraOf(bool ortho) {
  Camera cam = ortho ? orthographicCamera(2.0, kW, kH, 0.1, 20.0, ClipDepth::NegativeOneToOne, false)
                     : openglCamera(kW, kH, kGuard, 100.0);
  cam.guardBand = kGuard;
  return cam;
}

VkFormat vkFormat(gen::Format f) {
  return f == gen::Format::RGBA8 ? VK_FORMAT_R8G8B8A8_UNORM : VK_FORMAT_R16G16B16A16_SFLOAT;
}
GLenum glFormat(gen::Format f) { return f == gen::Format::RGBA8 ? GL_RGBA8 : GL_RGBA16F; }

struct Worst {
  double p999 = 0, max = 0;
};
Worst gGlCpu, gVkCpu, gGlVk;

class Summary : public ::testing::Environment {
 public:
  void TearDown() override {
    std::printf("\nbent normal output, worst channel over every case (units of 1/255): |GL - CPU| p99.9 %.3f max %.3f, "
                "|Vulkan - CPU| p99.9 %.3f max %.3f, |GL - Vulkan| p99.9 %.3f max %.3f\n",
                gGlCpu.p999 * 255, gGlCpu.max * 255, gVkCpu.p999 * 255, gVkCpu.max * 255, gGlVk.p999 * 255,
                gGlVk.max * 255);
  }
};
const auto* const kSummary = ::testing::AddGlobalTestEnvironment(new Summary);

// Every channel of `actual` against `expected`: 99.9 % within 2/255, none beyond 4/255.
void expectAgree(const FloatImage& actual, const FloatImage& expected, const std::string& name, Worst& worst) {
  ASSERT_EQ(actual.channels, 4u) << name;
  ASSERT_EQ(expected.channels, 4u) << name;
  for (std::uint32_t c = 0; c < 4; ++c) {
    std::string note;
    const Agreement a = compare(actual, expected, c, kWithin, kNever, name + "_c" + std::to_string(c), &note);
    EXPECT_TRUE(acceptable(a)) << name << " channel " << c << ": " << a.fractionWithin * 100 << "% within 2/255, max "
                               << a.maxAbs * 255 << "/255, " << a.beyond << " beyond 4/255. " << note;
    worst.p999 = std::max(worst.p999, a.p999);
    worst.max = std::max(worst.max, a.maxAbs);
  }
}

// The GL effect into the caller's rgba texture of `format`.
Status runGl(const Settings& s, const Camera& cam, const DepthImage& depth, const DepthImage* depth2,
             const FloatImage* normals, gen::Format format, FloatImage& out, const gl::Inputs* base = nullptr) {
  std::unique_ptr<gl::Effect> effect;
  if (Status st = gl::Effect::create(gl::HeadlessContext::getProcAddress(), effect); !st) return st;
  const GLuint tex = gltest::uploadDepth(depth, gl::GlDepth::D32F);
  const GLuint tex2 = depth2 ? gltest::uploadDepth(*depth2, gl::GlDepth::D32F) : 0;
  const GLuint ntex = normals ? gltest::uploadNormals(*normals) : 0;
  const GLuint target = gltest::makeTexture(glFormat(format), {cam.width, cam.height});
  gl::Inputs gi = base ? *base : gl::Inputs{};
  gi.depth = {tex, gl::internalFormat(gl::GlDepth::D32F)};
  if (depth2) gi.depth2 = {tex2, gi.depth.internalFormat};
  gi.normals = ntex;
  gi.output = target;
  const Status st = effect->render(cam, s, gi);
  if (st) out = gl::readTexture(target, 4);
  for (GLuint t : {tex, tex2, ntex, target}) gltest::deleteTexture(t);
  return st;
}

// The Vulkan effect into the caller's rgba image of `format` (userOutput, every channel unless
// `channels` says otherwise).
Status runVk(const Settings& s, const Camera& cam, const DepthImage& depth, const DepthImage* depth2,
             const FloatImage* normals, gen::Format format, FloatImage& out, std::uint32_t channels = kAllChannels,
             OutputBlend blend = OutputBlend::Replace) {
  using vk::headless::Image;
  Image depthImage, depth2Image, normalsImage, target;
  const auto cleanup = [&] {
    for (Image* i : {&depthImage, &depth2Image, &normalsImage, &target}) context().destroy(*i);
  };
  const VkImageLayout ro = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  if (Status st = context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, ro, depthImage); !st) return st;
  if (depth2)
    if (Status st = context().uploadDepth(*depth2, VK_FORMAT_D32_SFLOAT, ro, depth2Image); !st) return cleanup(), st;
  if (normals)
    if (Status st = context().uploadColor(*normals, VK_FORMAT_R16G16B16A16_SFLOAT, ro, normalsImage); !st)
      return cleanup(), st;
  const VkFormat vf = vkFormat(format);
  const FloatImage zero(Extent{cam.width, cam.height}, 4);
  if (Status st = context().uploadColor(zero, vf, ro, target, VK_IMAGE_USAGE_STORAGE_BIT); !st) return cleanup(), st;
  vk::Config c;
  c.camera = cam;
  c.settings = s;
  c.depthFormat = VK_FORMAT_D32_SFLOAT;
  c.secondLayer = depth2 != nullptr;
  if (normals) c.normalsFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  c.userOutput = true;
  c.outputFormat = vf;
  std::unique_ptr<vk::Effect> effect;
  if (Status st = vk::Effect::create(context().deviceContext(), c, effect); !st) return cleanup(), st;
  vk::Inputs in;
  in.depth = {depthImage.view, ro, depth.extent, VK_FORMAT_D32_SFLOAT};
  in.outputChannels = channels;
  in.outputBlend = blend;
  if (depth2) in.depth2 = {depth2Image.view, ro, depth2->extent, VK_FORMAT_D32_SFLOAT};
  if (normals) in.normals = {normalsImage.view, ro, normals->extent, VK_FORMAT_R16G16B16A16_SFLOAT};
  const vk::OutputImage o{target.image, target.view, vf, {cam.width, cam.height}, ro};
  Status recorded;
  Status st = context().submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, in, &o); });
  if (st && !recorded) st = recorded;
  if (st)
    st = context().readback(target.image, vf, {cam.width, cam.height}, 0, c.outputLayout, c.outputDstStages,
                            c.outputDstAccess, out);
  cleanup();
  return st;
}

Status runCpu(const Settings& s, const Camera& cam, const DepthImage& depth, const DepthImage* depth2,
              const FloatImage* normals, gen::Format format, cpu::Result& ref, cpu::Precision precision,
              std::uint32_t channels = kAllChannels, OutputBlend blend = OutputBlend::Replace) {
  cpu::Inputs ci;
  ci.depth = &depth;
  ci.depth2 = depth2;
  ci.normals = normals;
  ci.outputFormat = format;
  ci.outputChannels = channels;
  ci.outputBlend = blend;
  const FloatImage zero(Extent{cam.width, cam.height}, 4);
  if (blend == OutputBlend::Multiply) ci.output = &zero;
  return cpu::run(s, cam, ci, {precision, 2}, ref);
}

class BentNormals : public VkWithGl, public ::testing::WithParamInterface<std::tuple<std::size_t, gen::Format>> {};

TEST_P(BentNormals, GlVulkanAndCpuAgree) {
  const auto [index, format] = GetParam();
  const Case c = cases()[index];
  Settings s = directSettings();
  c.tweak(s);
  const Camera cam = cameraOf(c.ortho);
  for (const char* sceneName : {"plane", "crease", "sphere", "stairs", "rods"}) {
    SCOPED_TRACE(sceneName);
    const test::Scene scene = gltest::sceneByName(sceneName);
    const DepthImage depth = test::renderDepth(scene, cam, DepthFormat::D32F);
    const DepthImage depth2 = test::renderDepth(scene, cam, DepthFormat::D32F, 1);
    const FloatImage normals = test::renderNormals(scene, cam);
    const DepthImage* d2 = c.twoLayer ? &depth2 : nullptr;
    const FloatImage* n = c.normals ? &normals : nullptr;
    cpu::Result ref;
    const Status cs = runCpu(s, cam, depth, d2, n, format, ref, cpu::Precision::Float);
    ASSERT_TRUE(cs.ok()) << cs.message;
    ASSERT_EQ(ref.plan.variants[std::size_t(gen::VariantId::BENT_NORMALS)], 1);
    FloatImage glOut, vkOut;
    const Status gs = runGl(s, cam, depth, d2, n, format, glOut);
    ASSERT_TRUE(gs.ok()) << gs.message;
    const Status vs = runVk(s, cam, depth, d2, n, format, vkOut);
    ASSERT_TRUE(vs.ok()) << vs.message;
    const std::string name = "bent_" + c.name + "_" + formatName(format) + "_" + sceneName;
    expectAgree(glOut, ref.ao, name + "_gl", gGlCpu);
    expectAgree(vkOut, ref.ao, name + "_vk", gVkCpu);
    expectAgree(vkOut, glOut, name + "_gl_vk", gGlVk);
    // The bent normals are unit vectors (rgba16f; rgba8 stores 0.5 + 0.5 b) wherever there is a surface.
    std::size_t notUnit = 0, surface = 0;
    const bool unorm = format == gen::Format::RGBA8;
    for (std::uint32_t y = 0; y < kH; ++y)
      for (std::uint32_t x = 0; x < kW; ++x) {
        double b[3], l2 = 0;
        for (int k = 0; k < 3; ++k) {
          const float v = ref.ao.at(x, y, std::uint32_t(k));
          b[k] = unorm ? 2.0 * v - 1.0 : v;
          l2 += b[k] * b[k];
        }
        if (l2 < 0.25) continue;  // sky: 0 (rgba8: 0.5 rounded to 128/255, |b| = 0.007)
        ++surface;
        notUnit += std::abs(std::sqrt(l2) - 1.0) > (unorm ? 0.02 : 0.002);
      }
    EXPECT_GT(surface, 0u);
    EXPECT_EQ(notUnit, 0u) << "bent normals off unit length";
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, BentNormals,
                         ::testing::Combine(::testing::Range(std::size_t{0}, cases().size()),
                                            ::testing::Values(gen::Format::RGBA16F, gen::Format::RGBA8)),
                         [](const auto& info) {
                           return cases()[std::get<0>(info.param)].name + "_" + formatName(std::get<1>(info.param));
                         });

// An open plane facing an orthographic camera: every ray of the hemisphere is clear and V = n, so
// each slice's moment lies along n and the bent normal is (0, 0, 1) on every backend and in double.
TEST_F(BentNormals, OpenPlaneFacingTheCameraBendsNothing) {
  const Camera cam = cameraOf(true);
  const DepthImage depth = test::renderDepth(test::planeScene(3.0), cam, DepthFormat::D32F);
  const Settings s = directSettings();
  cpu::Result exact, ref;
  ASSERT_TRUE(runCpu(s, cam, depth, nullptr, nullptr, gen::Format::RGBA16F, exact, cpu::Precision::Double).ok());
  ASSERT_TRUE(runCpu(s, cam, depth, nullptr, nullptr, gen::Format::RGBA16F, ref, cpu::Precision::Float).ok());
  FloatImage glOut, vkOut;
  ASSERT_TRUE(runGl(s, cam, depth, nullptr, nullptr, gen::Format::RGBA16F, glOut).ok());
  ASSERT_TRUE(runVk(s, cam, depth, nullptr, nullptr, gen::Format::RGBA16F, vkOut).ok());
  for (const auto& [label, img, tol] : {std::tuple{"double", &exact.ao, 1e-9}, std::tuple{"float", &ref.ao, 1e-3},
                                       std::tuple{"gl", &glOut, 1e-3}, std::tuple{"vulkan", &vkOut, 1e-3}}) {
    double worst = 0;
    for (std::uint32_t y = 0; y < kH; ++y)
      for (std::uint32_t x = 0; x < kW; ++x)
        worst = std::max({worst, std::abs(double(img->at(x, y, 0))), std::abs(double(img->at(x, y, 1))),
                          std::abs(double(img->at(x, y, 2)) - 1.0), std::abs(double(img->at(x, y, 3)) - 1.0)});
    EXPECT_LE(worst, tol) << label << ": (R, G, B, A) off (0, 0, 1, 1) by " << worst;
    std::printf("open plane, %-7s largest |(R, G, B, A) - (0, 0, 1, 1)| %.3g\n", label, worst);
  }
}

// Each refusal, with the same words from the CPU reference, OpenGL and Vulkan.
TEST_F(BentNormals, RefusalsAreOneContractOnEveryBackend) {
  const Camera cam = cameraOf(false);
  const DepthImage depth = test::renderDepth(gltest::sceneByName("crease"), cam, DepthFormat::D32F);
  struct Refusal {
    std::string name;
    std::function<void(Settings&)> tweak;
    gen::Format format;
    std::uint32_t channels;
    OutputBlend blend;
    std::string words;  // in every backend's message
  };
  const std::vector<Refusal> refusals = {
      {"estimator0", [](Settings& s) { s.estimator = 0; }, gen::Format::RGBA16F, kAllChannels, OutputBlend::Replace,
       "setting 'bent_normals' = true is refused while estimator = 0"},
      {"blur", [](Settings& s) { s.blur_radius = 1; }, gen::Format::RGBA16F, kAllChannels, OutputBlend::Replace,
       "setting 'bent_normals' = true is refused while blur_radius > 0, resolution_divisor > 1 or temporal = true"},
      {"half_resolution", [](Settings& s) { s.resolution_divisor = 2; }, gen::Format::RGBA16F, kAllChannels,
       OutputBlend::Replace, "also set blur_radius = 0, resolution_divisor = 1 and temporal = false, or drop bent_normals"},
      {"temporal", [](Settings& s) { s.temporal = true; }, gen::Format::RGBA16F, kAllChannels, OutputBlend::Replace,
       "ao_sample_output alone writes the bent normal"},
      {"r16f", [](Settings&) {}, gen::Format::R16F, kAllChannels, OutputBlend::Replace,
       "bent normals need an rgba output (rgba8 or rgba16f)"},
      {"r8", [](Settings&) {}, gen::Format::R8, kAllChannels, OutputBlend::Replace,
       "bent normals need an rgba output (rgba8 or rgba16f)"},
      {"mask", [](Settings&) {}, gen::Format::RGBA8, kChannelR | kChannelG | kChannelB, OutputBlend::Replace,
       "it needs the output channel mask kAllChannels (15, got 7)"},
      {"multiply", [](Settings&) {}, gen::Format::RGBA16F, kAllChannels, OutputBlend::Multiply,
       "and output blend replace (got multiply)"},
  };
  for (const Refusal& r : refusals) {
    SCOPED_TRACE(r.name);
    Settings s = directSettings();
    r.tweak(s);
    cpu::Result ref;
    const Status cs = runCpu(s, cam, depth, nullptr, nullptr, r.format, ref, cpu::Precision::Float, r.channels, r.blend);
    EXPECT_FALSE(cs.ok());
    EXPECT_NE(cs.message.find(r.words), std::string::npos) << "CPU: " << cs.message;
    FloatImage out;
    gl::Inputs base;
    base.outputChannels = r.channels;
    base.outputBlend = r.blend;
    const bool single = r.format == gen::Format::R16F || r.format == gen::Format::R8;
    Status gs;
    if (single) {  // the GL effect's own r16f output, or the caller's r8 texture
      std::unique_ptr<gl::Effect> effect;
      ASSERT_TRUE(gl::Effect::create(gl::HeadlessContext::getProcAddress(), effect).ok());
      const GLuint tex = gltest::uploadDepth(depth, gl::GlDepth::D32F);
      const GLuint target = r.format == gen::Format::R8 ? gltest::makeTexture(GL_R8, {cam.width, cam.height}) : 0;
      gl::Inputs gi = base;
      gi.depth = {tex, gl::internalFormat(gl::GlDepth::D32F)};
      gi.output = target;
      gs = effect->render(cam, s, gi);
      gltest::deleteTexture(tex);
      gltest::deleteTexture(target);
    } else {
      gs = runGl(s, cam, depth, nullptr, nullptr, r.format, out, &base);
    }
    EXPECT_FALSE(gs.ok());
    EXPECT_NE(gs.message.find(r.words), std::string::npos) << "GL: " << gs.message;
    gltest::context().clearMessages();  // a refused render issues no GL call that could fail
    if (single) continue;  // runVk makes rgba images only; R16F/R8 go through the same plan() as GL's
    const Status vs = runVk(s, cam, depth, nullptr, nullptr, r.format, out, r.channels, r.blend);
    EXPECT_FALSE(vs.ok());
    EXPECT_NE(vs.message.find(r.words), std::string::npos) << "Vulkan: " << vs.message;
  }
}

}  // namespace
}  // namespace sao::vktest
