// half_intermediates (HALF_INTERMEDIATES: rg16f ao_raw and ao_low) on OpenGL against the CPU
// reference (float): the images really are GL_RG16F; the keys are the CPU's bit for bit (csz level
// 0 times key_scale, rounded to binary16 in the shader, so the store does not round again); A raw,
// low and final at the reference tests' bounds (99.9% within 2/255, none beyond 4/255), at full,
// half and quarter resolution, with a guard band and at an odd size.
#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "gl_support.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

Settings halfSettings(int divisor) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  s.half_intermediates = true;
  return s;
}

GLint internalFormatOf(GLuint texture) {
  GLint f = 0;
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &f);
  return f;
}

class HalfIntermediates : public GlTest {};

TEST_F(HalfIntermediates, MatchTheCpuReference) {
  auto effect = makeEffect();
  struct SizeCase {
    std::uint32_t width, height, guard;
  };
  for (const SizeCase sc : {SizeCase{160, 90, 8}, SizeCase{97, 61, 3}}) {
    const Camera cam = camera(sc.width, sc.height, sc.guard);
    for (const char* scene : {"crease", "sphere", "stairs", "rods"}) {
      const GlDepth format = std::string(scene) == "stairs" ? GlDepth::D24 : GlDepth::D32F;
      const DepthImage depth = test::renderDepth(sceneByName(scene), cam, cpuFormat(format));
      const GLuint depthTex = uploadDepth(depth, format);
      for (int d : {1, 2, 4}) {
        const std::string name = std::string(scene) + "_" + std::to_string(sc.width) + "x" +
                                 std::to_string(sc.height) + "_d" + std::to_string(d);
        SCOPED_TRACE(name);
        const Settings settings = halfSettings(d);
        cpu::Result ref;
        ASSERT_TRUE(cpu::run(settings, cam, {&depth}, cpu::Options{cpu::Precision::Float, 2}, ref).ok());
        gl::Inputs gi;
        gi.depth = {depthTex, internalFormat(format)};
        const Status st = effect->render(cam, settings, gi);
        ASSERT_TRUE(st.ok()) << st.message;
        EXPECT_EQ(effect->plan().describe(), ref.plan.describe());
        EXPECT_EQ(std::memcmp(&effect->params(), &ref.params, sizeof ref.params), 0) << "parameter blocks differ";
        EXPECT_EQ(internalFormatOf(effect->texture(gen::ResourceId::ao_raw)), GL_RG16F);
        const FloatImage ao = readTexture(effect->aoTexture(), 1);
        const FloatImage raw = readTexture(effect->texture(gen::ResourceId::ao_raw), 2);
        const Agreement f = compare(ao, ref.ao, 0, kWithin, kNever, name + "_half_final");
        const Agreement r = compare(raw, ref.aoRaw, 0, kWithin, kNever, name + "_half_raw");
        const Agreement rk = compare(raw, ref.aoRaw, 1, 0.0, 0.0, name + "_half_raw_key");
        double lowMax = 0.0;
        if (d > 1) {
          EXPECT_EQ(internalFormatOf(effect->texture(gen::ResourceId::ao_low)), GL_RG16F);
          const FloatImage low = readTexture(effect->texture(gen::ResourceId::ao_low), 2);
          const FloatImage& refLow = ref.images[static_cast<std::size_t>(gen::ResourceId::ao_low)].at(0);
          const Agreement l = compare(low, refLow, 0, kWithin, kNever, name + "_half_low");
          const Agreement lk = compare(low, refLow, 1, 0.0, 0.0, name + "_half_low_key");
          EXPECT_TRUE(acceptable(l)) << "low: max " << l.maxAbs * 255 << "/255, " << l.beyond << " beyond 4/255";
          EXPECT_EQ(lk.maxAbs, 0.0) << "the low keys are the raw keys, copied";
          lowMax = l.maxAbs;
        }
        std::printf("AGREEMENT half %-22s final max %.3f/255 p99.9 %.3f/255 | raw max %.3f/255 | low max %.3f/255\n",
                    name.c_str(), f.maxAbs * 255, f.p999 * 255, r.maxAbs * 255, lowMax * 255);
        EXPECT_TRUE(acceptable(f)) << "final: max " << f.maxAbs * 255 << "/255, " << f.beyond << " beyond 4/255";
        EXPECT_TRUE(acceptable(r)) << "raw: max " << r.maxAbs * 255 << "/255, " << r.beyond << " beyond 4/255";
        EXPECT_EQ(rk.maxAbs, 0.0) << "raw keys: csz level 0 times key_scale, rounded alike";
      }
      deleteTexture(depthTex);
    }
  }
}

// Switching half_intermediates on and off between frames reallocates the intermediates in the
// other format (a new plan), and the rg32f frame after a half one is the rg32f frame before it.
TEST_F(HalfIntermediates, SwitchingBackRestoresTheFloatPath) {
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(sceneByName("crease"), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  auto effect = makeEffect();
  gl::Inputs gi;
  gi.depth = {depthTex, internalFormat(GlDepth::D32F)};
  Settings full = presetSettings(Preset::Medium);
  full.half_intermediates = false;
  ASSERT_TRUE(effect->render(cam, full, gi).ok());
  EXPECT_EQ(internalFormatOf(effect->texture(gen::ResourceId::ao_raw)), GL_RG32F);
  const FloatImage before = readTexture(effect->aoTexture(), 1);
  ASSERT_TRUE(effect->render(cam, halfSettings(full.resolution_divisor), gi).ok());
  EXPECT_EQ(internalFormatOf(effect->texture(gen::ResourceId::ao_raw)), GL_RG16F);
  ASSERT_TRUE(effect->render(cam, full, gi).ok());
  EXPECT_EQ(internalFormatOf(effect->texture(gen::ResourceId::ao_raw)), GL_RG32F);
  const FloatImage after = readTexture(effect->aoTexture(), 1);
  EXPECT_EQ(before.data, after.data);
  deleteTexture(depthTex);
}

}  // namespace
}  // namespace sao::gltest
