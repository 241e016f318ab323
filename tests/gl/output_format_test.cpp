// The output (sao/output.h) on OpenGL, what only GL has: textures of other internal formats
// refused naming the four GL takes, aoTexture() naming the caller's texture or the owned one, and
// the generated format table's GL enums. Every format, mask and blend against the CPU reference,
// bad masks and blends and outputGeneration() on both APIs: tests/executors/output_format_test.cpp.
#include <epoxy/gl.h>

#include <string>

#include "gl_support.h"
#include "sao/output.h"

namespace sao::gltest {
namespace {

class OutputFormat : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    depth_ = test::renderDepth(sceneByName("plane"), cam_, DepthFormat::D32F);
    in_.depth = {uploadDepth(depth_, GlDepth::D32F), gl::kDepthComponent32F};
  }
  void TearDown() override {
    deleteTexture(in_.depth.texture);
    GlTest::TearDown();
  }
  const Camera cam_ = camera(32, 18, 0);
  DepthImage depth_;
  gl::Inputs in_;
};

TEST_F(OutputFormat, OtherInternalFormatsAreRefused) {
  auto effect = makeEffect();
  for (GLenum f : {GL_R32F, GL_RG16F, GL_RGBA32F, GL_RGB16F, GL_R16}) {
    const GLuint out = makeTexture(f, {cam_.width, cam_.height});
    in_.output = out;
    const Status st = effect->render(cam_, Settings{}, in_);
    EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
    EXPECT_NE(st.message.find("GL_R16F, GL_R8, GL_RGBA8 or GL_RGBA16F"), std::string::npos) << st.message;
    deleteTexture(out);
  }
  in_.output = 0;
  EXPECT_TRUE(effect->render(cam_, Settings{}, in_).ok()) << "the effect stays usable";
}

TEST_F(OutputFormat, AoTextureNamesTheOutputInUse) {
  auto effect = makeEffect();
  ASSERT_TRUE(effect->render(cam_, Settings{}, in_).ok());
  const GLuint owned = effect->aoTexture();
  EXPECT_NE(owned, 0u);
  for (gen::Format f : outputFormats()) {
    const GLuint mine = makeTexture(gen::formatInfo(f).glInternalFormat, {cam_.width, cam_.height});
    in_.output = mine;
    ASSERT_TRUE(effect->render(cam_, Settings{}, in_).ok()) << formatName(f);
    EXPECT_EQ(effect->aoTexture(), mine) << formatName(f);
    in_.output = 0;
    ASSERT_TRUE(effect->render(cam_, Settings{}, in_).ok());
    EXPECT_NE(effect->aoTexture(), mine) << "an owned texture again";
    deleteTexture(mine);
  }
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
