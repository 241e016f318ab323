// A multisampled depth input on OpenGL only (GL_TEXTURE_2D_MULTISAMPLE): the caller's multisample
// bindings are restored; a multisampled normals or output texture is refused. Both policies against
// the CPU reference and the second-layer refusal: tests/executors/msaa_depth_test.cpp.
#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "gl_msaa_depth_writer.h"
#include "gl_support.h"
#include "msaa_depth.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

constexpr std::uint32_t kSamples = 4;

class MsaaDepth : public GlTest {
 protected:
  Camera cam = camera(160, 90, 8);
  DepthImage sphere = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
  DepthImage rods = test::renderDepth(test::rodsScene(), cam, DepthFormat::D32F);
  DepthImage sky = test::renderDepth(test::skyScene(), cam, DepthFormat::D32F);
  DepthImage msaa = test::interleaveSamples({&sphere, &rods, &sky}, kSamples);
};

// The effect binds the multisampled depth on its own units; the caller's GL_TEXTURE_2D and
// GL_TEXTURE_2D_MULTISAMPLE bindings on every unit come back.
TEST_F(MsaaDepth, CallersMultisampleBindingsAreRestored) {
  const GLuint ms = writeSamples(msaa.extent, test::sampleValues(msaa));
  const GLuint other = writeSamples(msaa.extent, test::sampleValues(msaa));
  auto effect = makeEffect();
  for (GLuint unit = 0; unit < 8; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, other);
  }
  glActiveTexture(GL_TEXTURE3);
  gl::Inputs gi;
  gi.depth = {ms, 0};
  ASSERT_TRUE(effect->render(cam, presetSettings(Preset::Medium), gi).ok());
  GLint active = 0;
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  EXPECT_EQ(active, GL_TEXTURE3);
  for (GLuint unit = 0; unit < 8; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    GLint bound = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE, &bound);
    EXPECT_EQ(GLuint(bound), other) << "unit " << unit;
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
  }
  glActiveTexture(GL_TEXTURE0);
  deleteTexture(ms);
  deleteTexture(other);
}

TEST_F(MsaaDepth, OtherMultisampledInputsAreRefused) {
  const GLuint single = uploadDepth(sphere, GlDepth::D32F);
  auto effect = makeEffect();
  const Settings settings = presetSettings(Preset::Medium);
  GLuint msNormals = 0, msOutput = 0;
  glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &msNormals);
  glTextureStorage2DMultisample(msNormals, kSamples, GL_RGBA16F, GLsizei(msaa.extent.width), GLsizei(msaa.extent.height),
                                GL_TRUE);
  glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &msOutput);
  glTextureStorage2DMultisample(msOutput, kSamples, GL_R16F, GLsizei(cam.width), GLsizei(cam.height), GL_TRUE);
  auto refused = [&](const gl::Inputs& in, StatusCode code, const std::string& words) {
    const Status st = effect->render(cam, settings, in);
    EXPECT_EQ(st.code, code) << st.message;
    EXPECT_NE(st.message.find(words), std::string::npos) << st.message;
  };
  gl::Inputs in;
  in.depth = {single, 0};
  in.normals = msNormals;
  refused(in, StatusCode::UnsupportedFormat, "normals texture " + std::to_string(msNormals) + " is multisampled");
  in.normals = 0;
  in.output = msOutput;
  refused(in, StatusCode::UnsupportedFormat, "output texture " + std::to_string(msOutput) + " is multisampled");
  glDeleteTextures(1, &msNormals);
  glDeleteTextures(1, &msOutput);
  deleteTexture(single);
}

}  // namespace
}  // namespace sao::gltest
