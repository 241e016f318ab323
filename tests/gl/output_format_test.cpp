// The output as the engine wants it (sao/output.h) on OpenGL: the caller's GL_R16F, GL_R8,
// GL_RGBA8 and GL_RGBA16F textures with channel masks and the multiply blend (the apply step, also
// on an HDR colour target with infinities and NaNs) against the CPU reference (Float) at full and
// half resolution (upsample writes the output at both), untouched channels keeping their
// sentinel texels, other formats, masks and a multiply without the caller's texture refused, and
// outputGeneration() following the owned output texture.
#include <cmath>
#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "gl_support.h"
#include "output_format_check.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

GLenum glInternal(gen::Format f) {
  switch (f) {
    case gen::Format::R16F: return GL_R16F;
    case gen::Format::R8: return GL_R8;
    case gen::Format::RGBA8: return GL_RGBA8;
    case gen::Format::RGBA16F: return GL_RGBA16F;
    default: return 0;
  }
}

// A texture of `format` holding `texels` (each value exact in the format), checked by reading back.
GLuint uploadOutput(gen::Format format, const FloatImage& texels) {
  const GLuint tex = makeTexture(glInternal(format), texels.extent);
  const GLenum layout = texels.channels == 1 ? GL_RED : GL_RGBA;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTextureSubImage2D(tex, 0, 0, 0, GLsizei(texels.extent.width), GLsizei(texels.extent.height), layout, GL_FLOAT,
                      texels.data.data());
  const FloatImage back = readTexture(tex, texels.channels);
  const bool unorm = format == gen::Format::R8 || format == gen::Format::RGBA8;
  auto held = [&](float got, float want) {
    if (std::isnan(want)) return std::isnan(got);
    if (unorm) return test::unormByte(got) == test::unormByte(want);
    return got == want;
  };
  std::size_t differ = 0;
  for (std::size_t i = 0; i < back.data.size(); ++i) differ += !held(back.data[i], texels.data[i]);
  EXPECT_EQ(differ, 0u) << "the sentinel upload did not hold its texels";
  return tex;
}

Settings settingsFor(int divisor, float albedo = 0) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  s.albedo = albedo;  // > 0: the multi-bounce fit in the store (docs/effect-math.md 9)
  return s;
}

class OutputFormat : public GlTest {};

TEST_F(OutputFormat, EveryFormatAndMaskMatchesTheCpuReference) {
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(sceneByName("sphere"), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  for (int divisor : {1, 2})
    for (float albedo : {0.0f, 0.6f})
    for (const test::OutputCase& oc : test::kOutputCases) {
      const std::string name = "gl_" + test::caseName(oc) + "_d" + std::to_string(divisor) + (albedo > 0 ? "_bounce" : "");
      SCOPED_TRACE(name);
      const FloatImage sentinel = test::sentinelOutput({cam.width, cam.height}, oc.format);
      const GLuint out = uploadOutput(oc.format, sentinel);
      gl::Inputs gi;
      gi.depth = {depthTex, gl::kDepthComponent32F};
      gi.output = out;
      gi.outputChannels = oc.mask;
      gi.outputBlend = oc.blend;
      const Status st = effect->render(cam, settingsFor(divisor, albedo), gi);
      ASSERT_TRUE(st.ok()) << st.message;
      EXPECT_EQ(effect->aoTexture(), out);
      cpu::Inputs ci;
      ci.depth = &depth;
      ci.outputFormat = oc.format;
      ci.outputChannels = oc.mask;
      ci.outputBlend = oc.blend;
      ci.output = &sentinel;
      cpu::Result ref;
      const Status cst = cpu::run(settingsFor(divisor, albedo), cam, ci, cpu::Options{cpu::Precision::Float, 2}, ref);
      ASSERT_TRUE(cst.ok()) << cst.message;
      EXPECT_EQ(effect->plan().variants, ref.plan.variants) << "the same OUTPUT_FORMAT variant";
      const FloatImage actual = readTexture(out, channelCount(oc.format));
      test::checkOutput(actual, ref.ao, sentinel, oc.format, oc.mask, compare, name);
      deleteTexture(out);
    }
  deleteTexture(depthTex);
}

// The apply step on an engine's HDR colour target: RGB multiplied by A, not clamped, infinities and
// NaNs stored back, alpha kept, at full and half resolution.
TEST_F(OutputFormat, MultiplyIntoAnHdrColourTarget) {
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(sceneByName("sphere"), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  const FloatImage colour = test::hdrColour({cam.width, cam.height});
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  for (int divisor : {1, 2}) {
    const std::string name = "gl_hdr_d" + std::to_string(divisor);
    const GLuint out = uploadOutput(gen::Format::RGBA16F, colour);
    gl::Inputs gi;
    gi.depth = {depthTex, gl::kDepthComponent32F};
    gi.output = out;
    gi.outputChannels = kChannelR | kChannelG | kChannelB;
    gi.outputBlend = OutputBlend::Multiply;
    const Status st = effect->render(cam, settingsFor(divisor), gi);
    ASSERT_TRUE(st.ok()) << st.message;
    cpu::Inputs ci;
    ci.depth = &depth;
    ci.outputFormat = gen::Format::RGBA16F;
    ci.outputChannels = gi.outputChannels;
    ci.outputBlend = OutputBlend::Multiply;
    ci.output = &colour;
    cpu::Result ref;
    const Status cst = cpu::run(settingsFor(divisor), cam, ci, cpu::Options{cpu::Precision::Float, 2}, ref);
    ASSERT_TRUE(cst.ok()) << cst.message;
    test::checkHdrMultiply(readTexture(out, 4), ref.ao, colour, name);
    deleteTexture(out);
  }
  deleteTexture(depthTex);
}

// The R16F path of an RGBA16F output is the default output's: the same binary16 values.
TEST_F(OutputFormat, Rgba16fChannelsHoldTheDefaultOutputBits) {
  const Camera cam = camera(96, 54, 4);
  const DepthImage depth = test::renderDepth(sceneByName("stairs"), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  auto effect = makeEffect();
  gl::Inputs gi;
  gi.depth = {depthTex, gl::kDepthComponent32F};
  ASSERT_TRUE(effect->render(cam, settingsFor(1), gi).ok());
  const FloatImage r16 = readTexture(effect->aoTexture(), 1);
  const GLuint out = makeTexture(GL_RGBA16F, {cam.width, cam.height});
  gi.output = out;
  ASSERT_TRUE(effect->render(cam, settingsFor(1), gi).ok());
  const FloatImage rgba = readTexture(out, 4);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < r16.data.size(); ++i)
    for (std::size_t c = 0; c < 4; ++c) differ += rgba.data[i * 4 + c] != r16.data[i];
  EXPECT_EQ(differ, 0u);
  deleteTexture(out);
  deleteTexture(depthTex);
}

TEST_F(OutputFormat, OtherFormatsAndMasksAreRefused) {
  const Camera cam = camera(32, 18, 0);
  const DepthImage depth = test::renderDepth(sceneByName("plane"), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  auto effect = makeEffect();
  gl::Inputs gi;
  gi.depth = {depthTex, gl::kDepthComponent32F};
  for (GLenum f : {GL_R32F, GL_RG16F, GL_RGBA32F, GL_RGB16F, GL_R16}) {
    const GLuint out = makeTexture(f, {cam.width, cam.height});
    gi.output = out;
    const Status st = effect->render(cam, settingsFor(1), gi);
    EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
    EXPECT_NE(st.message.find("GL_R16F, GL_R8, GL_RGBA8 or GL_RGBA16F"), std::string::npos) << st.message;
    deleteTexture(out);
  }
  struct BadMask {
    GLenum format;
    std::uint32_t mask;
  };
  for (const BadMask b : {BadMask{GL_R8, kChannelG}, BadMask{GL_R16F, kChannelR | kChannelA},
                          BadMask{GL_RGBA8, 0u}, BadMask{GL_RGBA16F, 16u}}) {
    const GLuint out = makeTexture(b.format, {cam.width, cam.height});
    gi.output = out;
    gi.outputChannels = b.mask;
    const Status st = effect->render(cam, settingsFor(1), gi);
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    EXPECT_NE(st.message.find("channel mask " + std::to_string(b.mask)), std::string::npos) << st.message;
    deleteTexture(out);
  }
  // The owned output is GL_R16F: a mask keeping channels has nothing to keep there, and a
  // multiply nothing to multiply.
  gi.output = 0;
  gi.outputChannels = kChannelG;
  EXPECT_EQ(effect->render(cam, settingsFor(1), gi).code, StatusCode::InvalidInput);
  gi.outputChannels = kAllChannels;
  gi.outputBlend = OutputBlend::Multiply;
  Status st = effect->render(cam, settingsFor(1), gi);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("output blend multiply needs your own output"), std::string::npos) << st.message;
  gi.outputBlend = static_cast<OutputBlend>(7);
  st = effect->render(cam, settingsFor(1), gi);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("unknown output blend 7"), std::string::npos) << st.message;
  gi.outputBlend = OutputBlend::Replace;
  EXPECT_TRUE(effect->render(cam, settingsFor(1), gi).ok()) << "the effect stays usable";
  deleteTexture(depthTex);
}

TEST_F(OutputFormat, OutputGenerationFollowsTheOwnedTexture) {
  const Camera small = camera(32, 18, 0), large = camera(48, 27, 0);
  const DepthImage d1 = test::renderDepth(sceneByName("sphere"), small, DepthFormat::D32F);
  const DepthImage d2 = test::renderDepth(sceneByName("sphere"), large, DepthFormat::D32F);
  const GLuint t1 = uploadDepth(d1, GlDepth::D32F), t2 = uploadDepth(d2, GlDepth::D32F);
  auto effect = makeEffect();
  EXPECT_EQ(effect->outputGeneration(), 0u) << "nothing rendered yet";
  gl::Inputs gi;
  gi.depth = {t1, 0};
  ASSERT_TRUE(effect->render(small, settingsFor(1), gi).ok());
  const std::uint64_t g1 = effect->outputGeneration();
  EXPECT_EQ(g1, 1u);
  ASSERT_TRUE(effect->render(small, settingsFor(1), gi).ok());
  EXPECT_EQ(effect->outputGeneration(), g1) << "a steady frame keeps the texture";
  Settings other = settingsFor(1);
  other.intensity = 0.7f;
  ASSERT_TRUE(effect->render(small, other, gi).ok());
  EXPECT_EQ(effect->outputGeneration(), g1) << "new settings, same output texture";
  gi.depth = {t2, 0};
  ASSERT_TRUE(effect->render(large, settingsFor(1), gi).ok());
  const std::uint64_t g2 = effect->outputGeneration();
  EXPECT_GT(g2, g1) << "a resize makes a new texture";
  EXPECT_EQ(readTexture(effect->aoTexture(), 1).extent, (Extent{48, 27}));
  const GLuint mine = makeTexture(GL_RGBA8, {48, 27});
  gi.output = mine;
  ASSERT_TRUE(effect->render(large, settingsFor(1), gi).ok());
  const std::uint64_t g3 = effect->outputGeneration();
  EXPECT_GT(g3, g2) << "the owned texture is deleted when the caller gives one";
  EXPECT_EQ(effect->aoTexture(), mine);
  ASSERT_TRUE(effect->render(large, settingsFor(1), gi).ok());
  EXPECT_EQ(effect->outputGeneration(), g3) << "the caller's own output never changes it";
  gi.output = 0;
  ASSERT_TRUE(effect->render(large, settingsFor(1), gi).ok());
  EXPECT_GT(effect->outputGeneration(), g3) << "an owned texture again";
  // A failed render changes nothing.
  const std::uint64_t g4 = effect->outputGeneration();
  gi.depth = {t1, 0};
  EXPECT_FALSE(effect->render(large, settingsFor(1), gi).ok());
  EXPECT_EQ(effect->outputGeneration(), g4);
  deleteTexture(mine);
  deleteTexture(t1);
  deleteTexture(t2);
}

// The generated format table (codegen/src/formats.cpp) names the GL enums GL's own header has.
TEST(Formats, GeneratedTableNamesTheGlInternalFormats) {
  using F = gen::Format;
  const std::pair<F, GLenum> expected[] = {
      {F::R32F, GL_R32F},   {F::RG32F, GL_RG32F},     {F::R16F, GL_R16F},
      {F::RG16F, GL_RG16F}, {F::RGBA16F, GL_RGBA16F}, {F::R8, GL_R8},
      {F::RGBA8, GL_RGBA8}, {F::RGBA32F, GL_RGBA32F}, {F::Depth, GL_DEPTH_COMPONENT32F}};
  ASSERT_EQ(std::size(expected), gen::kFormatInfo.size());
  for (const auto& [format, gl] : expected) EXPECT_EQ(gen::formatInfo(format).glInternalFormat, gl) << formatName(format);
}

}  // namespace
}  // namespace sao::gltest
