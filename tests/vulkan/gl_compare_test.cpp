// Vulkan against OpenGL on the same inputs as the GL backend's reference tests (160x90, guard band
// 8, the GL test camera: 60 degrees, near 0.1, far 1000, [-1,1] depth; scenes plane(3), crease(2),
// sphere on a plane, stairs, rods; every preset; D16 / D24 / D32F). Both run on Mesa's LLVM here:
// the aim is identical output, the requirement at most 1/255 anywhere (final and raw AO).
#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <cmath>
#include <map>
#include <numbers>

#include "analytic_scenes.h"
#include "untuned_settings.h"
#include "gl_support.h"
#include "sao/gl/effect.h"
#include "sao/gl/headless.h"
#include "sao/presets.h"
#include "vk_gl_fixture.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;
constexpr double kLimit = 1.0 / 255.0;

using gltest::sceneByName;

GLuint uploadGlDepth(const DepthImage& depth) {
  const auto w = GLsizei(depth.extent.width), h = GLsizei(depth.extent.height);
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  std::vector<std::uint16_t> u16;
  std::vector<std::uint32_t> u32;
  switch (depth.format) {
    case DepthFormat::D16:
      glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT16, w, h);
      for (auto v : depth.texels) u16.push_back(std::uint16_t(v));
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, u16.data());
      break;
    case DepthFormat::D24:  // the 24-bit value as a 32-bit normalised integer, exact both ways
      glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT24, w, h);
      for (auto v : depth.texels) u32.push_back((v << 8) | (v >> 16));
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, u32.data());
      break;
    default:
      glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, w, h);
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.texels.data());
      break;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glBindTexture(GL_TEXTURE_2D, 0);
  return t;
}

std::uint32_t glFormat(DepthFormat f) {
  return f == DepthFormat::D16 ? gl::kDepthComponent16 : f == DepthFormat::D24 ? gl::kDepthComponent24 : gl::kDepthComponent32F;
}

FloatImage readGl(GLuint texture, std::uint32_t channels) {
  GLint w = 0, h = 0;
  glBindTexture(GL_TEXTURE_2D, texture);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &w);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &h);
  FloatImage img({std::uint32_t(w), std::uint32_t(h)}, channels);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTexImage(GL_TEXTURE_2D, 0, channels == 1 ? GL_RED : GL_RG, GL_FLOAT, img.data.data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glBindTexture(GL_TEXTURE_2D, 0);
  return img;
}

struct Diff {
  double max = 0;
  std::size_t differing = 0;  // pixels whose bits differ
};
Diff diff(const FloatImage& a, const FloatImage& b, std::uint32_t channel) {
  Diff d;
  if (a.extent != b.extent) {
    d.max = INFINITY;
    return d;
  }
  for (std::uint32_t y = 0; y < a.extent.height; ++y)
    for (std::uint32_t x = 0; x < a.extent.width; ++x) {
      const float u = a.at(x, y, channel), v = b.at(x, y, channel);
      d.differing += std::bit_cast<std::uint32_t>(u) != std::bit_cast<std::uint32_t>(v);
      d.max = std::max(d.max, std::isfinite(u) && std::isfinite(v) ? std::fabs(double(u) - double(v)) : INFINITY);
    }
  return d;
}

struct Worst {
  double finalMax = 0, rawMax = 0;
  std::size_t finalDiffering = 0, rawDiffering = 0, pixels = 0;
};
std::map<std::string, Worst> gTable;

class Summary : public ::testing::Environment {
 public:
  void TearDown() override {
    if (gTable.empty()) return;
    std::printf("\nVulkan vs OpenGL, %ux%u + guard %u, five scenes per row (max |diff| in 1/255; pixels whose bits "
                "differ):\n",
                kW, kH, kGuard);
    double overall = 0;
    for (const auto& [k, w] : gTable) {
      std::printf("  %-16s final max %.3g (%zu of %zu pixels differ) | raw max %.3g (%zu differ)\n", k.c_str(),
                  w.finalMax * 255, w.finalDiffering, w.pixels, w.rawMax * 255, w.rawDiffering);
      overall = std::max({overall, w.finalMax, w.rawMax});
    }
    std::printf("  overall max %.4f/255\n", overall * 255);
  }
};
const auto* const kSummary = ::testing::AddGlobalTestEnvironment(new Summary);

using WithGl = VkWithGl;
class VkVsGl : public WithGl, public ::testing::WithParamInterface<std::tuple<std::size_t, DepthFormat>> {};

TEST_P(VkVsGl, SameOutput) {
  const auto [index, format] = GetParam();
  const Settings settings = test::agreementSettings()[index].settings;
  const Camera cam = openglCamera(kW, kH, kGuard, 1000.0);
  std::unique_ptr<gl::Effect> glEffect;
  const Status gs = gl::Effect::create(gl::HeadlessContext::getProcAddress(), glEffect);
  ASSERT_TRUE(gs.ok()) << gs.message;
  const std::string presetName = test::agreementSettings()[index].name;
  Worst worst;
  for (const char* sceneName : {"plane", "crease", "sphere", "stairs", "rods"}) {
    SCOPED_TRACE(sceneName);
    const DepthImage depth = test::renderDepth(sceneByName(sceneName), cam, format);
    // OpenGL
    const GLuint tex = uploadGlDepth(depth);
    gl::Inputs gi;
    gi.depth = {tex, glFormat(format)};
    const Status rs = glEffect->render(cam, settings, gi);
    ASSERT_TRUE(rs.ok()) << rs.message;
    const FloatImage glAo = readGl(glEffect->aoTexture(), 1);
    const FloatImage glRaw = readGl(glEffect->texture(gen::ResourceId::ao_raw), 2);
    glDeleteTextures(1, &tex);
    // Vulkan
    const VkDepth vf = format == DepthFormat::D16 ? VkDepth::D16 : format == DepthFormat::D24 ? VkDepth::X8D24 : VkDepth::D32F;
    RunResult vk;
    const Status vs = runEffect(settings, cam, depth, vf, vk);
    ASSERT_TRUE(vs.ok()) << vs.message;
    EXPECT_EQ(std::memcmp(&vk.params, &glEffect->params(), sizeof(ParamBlock)), 0) << "same parameter block";

    const Diff f = diff(vk.ao, glAo, 0), r = diff(vk.aoRaw, glRaw, 0);
    std::printf("%-9s %-4s %-7s final max %.4f/255 (%zu pixels differ) | raw max %.4f/255 (%zu differ)\n",
                presetName.c_str(), toString(format), sceneName, f.max * 255, f.differing, r.max * 255, r.differing);
    EXPECT_LE(f.max, kLimit) << "final AO";
    EXPECT_LE(r.max, kLimit) << "raw AO";
    if (f.max > kLimit || r.max > kLimit) {
      const std::string name = "vk_gl_" + presetName + "_" + toString(format) + "_" + sceneName;
      (void)compare(vk.ao, glAo, 0, 0.0, kLimit, name + "_final");
      (void)compare(vk.aoRaw, glRaw, 0, 0.0, kLimit, name + "_raw");
    }
    worst.finalMax = std::max(worst.finalMax, f.max);
    worst.rawMax = std::max(worst.rawMax, r.max);
    worst.finalDiffering += f.differing;
    worst.rawDiffering += r.differing;
    worst.pixels += vk.ao.data.size();
  }
  gTable[presetName + "/" + toString(format)] = worst;
}

// The distance fade on (3 to 6 m, the floors recede through it): the same output as well.
TEST_F(WithGl, DistanceFadeSameOutput) {
  Settings settings = presetSettings(Preset::Medium);
  settings.fade_start = 3.0f;
  settings.fade_end = 6.0f;
  const Camera cam = openglCamera(kW, kH, kGuard, 1000.0);
  std::unique_ptr<gl::Effect> glEffect;
  ASSERT_TRUE(gl::Effect::create(gl::HeadlessContext::getProcAddress(), glEffect).ok());
  for (const char* sceneName : {"sphere", "stairs"}) {
    SCOPED_TRACE(sceneName);
    const DepthImage depth = test::renderDepth(sceneByName(sceneName), cam, DepthFormat::D32F);
    const GLuint tex = uploadGlDepth(depth);
    gl::Inputs gi;
    gi.depth = {tex, glFormat(DepthFormat::D32F)};
    const Status rs = glEffect->render(cam, settings, gi);
    ASSERT_TRUE(rs.ok()) << rs.message;
    const FloatImage glAo = readGl(glEffect->aoTexture(), 1);
    const FloatImage glRaw = readGl(glEffect->texture(gen::ResourceId::ao_raw), 2);
    glDeleteTextures(1, &tex);
    RunResult vk;
    const Status vs = runEffect(settings, cam, depth, VkDepth::D32F, vk);
    ASSERT_TRUE(vs.ok()) << vs.message;
    EXPECT_EQ(std::memcmp(&vk.params, &glEffect->params(), sizeof(ParamBlock)), 0) << "same parameter block";
    const Diff f = diff(vk.ao, glAo, 0), r = diff(vk.aoRaw, glRaw, 0);
    std::printf("fade 3-6 m medium D32F %-7s final max %.4f/255 (%zu pixels differ) | raw max %.4f/255 (%zu differ)\n",
                sceneName, f.max * 255, f.differing, r.max * 255, r.differing);
    EXPECT_LE(f.max, kLimit) << "final AO";
    EXPECT_LE(r.max, kLimit) << "raw AO";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Matrix, VkVsGl,
    ::testing::Combine(::testing::Range(std::size_t{0}, test::agreementSettings().size()),
                       ::testing::Values(DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F)),
    [](const auto& info) {
      return test::agreementSettings()[std::get<0>(info.param)].name + "_" +
             toString(std::get<1>(info.param));
    });

}  // namespace
}  // namespace sao::vktest
