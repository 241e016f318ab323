// The multi-bounce term (setting albedo) on OpenGL against the CPU reference (Float): the five
// analytic scenes x every agreement configuration (each preset, the z hierarchy off, the untuned
// defaults, and no blur at full resolution, where ao_sample_output stores the output) at albedo 0.6,
// to the reference tests' bounds (99.9 % within 2/255, none beyond 4/255). Every output format,
// mask and blend at albedo 0.6: output_format_test.cpp (EveryFormatAndMaskMatchesTheCpuReference).
#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "gl_support.h"
#include "output_format_check.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "untuned_settings.h"

namespace sao::gltest {
namespace {

constexpr float kAlbedo = 0.6f;
constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

std::vector<test::NamedSettings> configurations() {
  std::vector<test::NamedSettings> v = test::agreementSettings();
  Settings direct = presetSettings(Preset::Reference);
  direct.blur_radius = 0;  // with resolution_divisor 1: ao_sample_output writes the output
  v.push_back({"direct", direct});
  for (auto& c : v) c.settings.albedo = kAlbedo;
  return v;
}

class MultiBounce : public GlTest {};

TEST_F(MultiBounce, AgreesWithTheCpuReferenceOnEveryScene) {
  const Camera cam = camera(160, 90, 8);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  for (const char* sceneName : {"plane", "crease", "sphere", "stairs", "rods"}) {
    const DepthImage depth = test::renderDepth(sceneByName(sceneName), cam, DepthFormat::D24);
    const GLuint depthTex = uploadDepth(depth, GlDepth::D24);
    for (const auto& [label, settings] : configurations()) {
      const std::string name = std::string("gl_bounce_") + sceneName + "_" + label;
      SCOPED_TRACE(name);
      gl::Inputs gi;
      gi.depth = {depthTex, internalFormat(GlDepth::D24)};
      const Status st = effect->render(cam, settings, gi);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Inputs ci;
      ci.depth = &depth;
      cpu::Result ref;
      const Status cst = cpu::run(settings, cam, ci, cpu::Options{cpu::Precision::Float, 2}, ref);
      ASSERT_TRUE(cst.ok()) << cst.message;
      EXPECT_EQ(std::memcmp(&effect->params(), &ref.params, sizeof ref.params), 0) << "parameter blocks differ";
      EXPECT_EQ(ref.params.multi_bounce, 1);
      const Agreement f = compare(readTexture(effect->aoTexture(), 1), ref.ao, 0, kWithin, kNever, name);
      EXPECT_TRUE(acceptable(f)) << "max |diff| " << f.maxAbs * 255 << "/255, " << f.fractionWithin * 100
                                 << "% within 2/255, " << f.beyond << " beyond 4/255";
      std::printf("BOUNCE %-34s max %.4f/255 p99.9 %.4f/255\n", name.c_str(), f.maxAbs * 255, f.p999 * 255);
    }
    deleteTexture(depthTex);
  }
}

}  // namespace
}  // namespace sao::gltest
