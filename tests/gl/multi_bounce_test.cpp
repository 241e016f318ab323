// The multi-bounce term (setting albedo) on OpenGL against the CPU reference (Float): the five
// analytic scenes x every agreement configuration (each preset, the z hierarchy off, the untuned
// defaults, and no blur at full resolution, where ao_sample_output stores the output) at albedo 0.6,
// to the reference tests' bounds (99.9 % within 2/255, none beyond 4/255); and every output format,
// mask and blend of the output-format tests at albedo 0.6, at full and half resolution.
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
  Settings direct = presetSettings(Preset::Ultra);
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

// The caller's texture of `format` holding `texels` (each exact in the format).
GLuint uploadOutput(gen::Format format, const FloatImage& texels) {
  GLenum internal = GL_R16F;
  switch (format) {
    case gen::Format::R8: internal = GL_R8; break;
    case gen::Format::RGBA8: internal = GL_RGBA8; break;
    case gen::Format::RGBA16F: internal = GL_RGBA16F; break;
    default: break;
  }
  const GLuint tex = makeTexture(internal, texels.extent);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTextureSubImage2D(tex, 0, 0, 0, GLsizei(texels.extent.width), GLsizei(texels.extent.height),
                      texels.channels == 1 ? GL_RED : GL_RGBA, GL_FLOAT, texels.data.data());
  return tex;
}

TEST_F(MultiBounce, EveryOutputFormatAndBlendMatchesTheCpuReference) {
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(sceneByName("sphere"), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  for (int divisor : {1, 2}) {
    Settings s = presetSettings(Preset::Medium);
    s.resolution_divisor = divisor;
    s.albedo = kAlbedo;
    for (const test::OutputCase& oc : test::kOutputCases) {
      const std::string name = "gl_bounce_" + test::caseName(oc) + "_d" + std::to_string(divisor);
      SCOPED_TRACE(name);
      const FloatImage sentinel = test::sentinelOutput({cam.width, cam.height}, oc.format);
      const GLuint out = uploadOutput(oc.format, sentinel);
      gl::Inputs gi;
      gi.depth = {depthTex, gl::kDepthComponent32F};
      gi.output = out;
      gi.outputChannels = oc.mask;
      gi.outputBlend = oc.blend;
      const Status st = effect->render(cam, s, gi);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Inputs ci;
      ci.depth = &depth;
      ci.outputFormat = oc.format;
      ci.outputChannels = oc.mask;
      ci.outputBlend = oc.blend;
      ci.output = &sentinel;
      cpu::Result ref;
      const Status cst = cpu::run(s, cam, ci, cpu::Options{cpu::Precision::Float, 2}, ref);
      ASSERT_TRUE(cst.ok()) << cst.message;
      test::checkOutput(readTexture(out, channelCount(oc.format)), ref.ao, sentinel, oc.format, oc.mask, compare, name);
      deleteTexture(out);
    }
  }
  deleteTexture(depthTex);
}

}  // namespace
}  // namespace sao::gltest
