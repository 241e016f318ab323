// resolution_divisor 2 and 4: Vulkan against OpenGL on the same inputs (the GL test camera, the
// reference scenes, D24 and D32F) at 160x90 with a guard band and the odd sizes 641x359 and
// 97x61; the final AO, the reduced raw AO and the reduced (A, key) image within 1/255 anywhere.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "analytic_scenes.h"
#include "gl_support.h"
#include "sao/gl/effect.h"
#include "sao/gl/headless.h"
#include "sao/presets.h"
#include "vk_gl_fixture.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr double kLimit = 1.0 / 255.0;

double maxDiff(const FloatImage& a, const FloatImage& b) {
  if (a.extent != b.extent || a.channels != b.channels) return INFINITY;
  double m = 0;
  for (std::size_t i = 0; i < a.data.size(); i += a.channels)
    m = std::max(m, std::isfinite(a.data[i]) && std::isfinite(b.data[i]) ? std::fabs(double(a.data[i]) - b.data[i])
                                                                         : INFINITY);
  return m;
}

class VkVsGlReduced : public VkWithGl {};

TEST_F(VkVsGlReduced, SameOutput) {
  std::unique_ptr<gl::Effect> glEffect;
  const Status gs = gl::Effect::create(gl::HeadlessContext::getProcAddress(), glEffect);
  ASSERT_TRUE(gs.ok()) << gs.message;
  struct Size {
    std::uint32_t w, h, guard;
  };
  for (const Size sz : {Size{160, 90, 8}, Size{641, 359, 0}, Size{97, 61, 3}}) {
    const Camera cam = openglCamera(sz.w, sz.h, sz.guard, 1000.0);
    for (const char* sceneName : {"plane", "crease", "sphere", "stairs", "rods"}) {
      const gltest::GlDepth format = std::string(sceneName) == "stairs" ? gltest::GlDepth::D24 : gltest::GlDepth::D32F;
      const DepthImage depth = test::renderDepth(gltest::sceneByName(sceneName), cam, gltest::cpuFormat(format));
      for (int d : {2, 4}) {
        Settings settings = presetSettings(Preset::Medium);
        settings.resolution_divisor = d;
        const std::string name = std::string(sceneName) + "_" + std::to_string(sz.w) + "x" + std::to_string(sz.h) +
                                 "_d" + std::to_string(d);
        SCOPED_TRACE(name);
        const GLuint tex = gltest::uploadDepth(depth, format);
        gl::Inputs gi;
        gi.depth = {tex, gltest::internalFormat(format)};
        const Status rs = glEffect->render(cam, settings, gi);
        ASSERT_TRUE(rs.ok()) << rs.message;
        const FloatImage glAo = gltest::readTexture(glEffect->aoTexture(), 1);
        const FloatImage glRaw = gltest::readTexture(glEffect->texture(gen::ResourceId::ao_raw), 2);
        const FloatImage glLow = gltest::readTexture(glEffect->texture(gen::ResourceId::ao_low), 2);
        gltest::deleteTexture(tex);
        RunResult vk;
        const Status vs =
            runEffect(settings, cam, depth, format == gltest::GlDepth::D24 ? VkDepth::X8D24 : VkDepth::D32F, vk);
        ASSERT_TRUE(vs.ok()) << vs.message;
        EXPECT_EQ(std::memcmp(&vk.params, &glEffect->params(), sizeof(ParamBlock)), 0) << "same parameter block";
        const double f = maxDiff(vk.ao, glAo), r = maxDiff(vk.aoRaw, glRaw), l = maxDiff(vk.aoLow, glLow);
        std::printf("vk vs gl %-22s final max %.4f/255 | raw max %.4f/255 | low max %.4f/255\n", name.c_str(), f * 255,
                    r * 255, l * 255);
        EXPECT_LE(f, kLimit) << "final AO";
        EXPECT_LE(r, kLimit) << "raw AO";
        EXPECT_LE(l, kLimit) << "ao_low";
      }
    }
  }
}

}  // namespace
}  // namespace sao::vktest
