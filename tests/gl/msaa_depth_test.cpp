// A multisampled depth input on OpenGL (GL_TEXTURE_2D_MULTISAMPLE, Camera::depthSamplePolicy): a
// 4-sample GL_DEPTH_COMPONENT32F texture whose every sample is written by a fragment shader with
// per-sample shading (gl_SampleID) from the values of tests/cpu/msaa_depth.h, read by the effect
// with Sample0 and Nearest and compared with the CPU reference on the same samples (csz level 0
// and the output); the caller's multisample bindings are restored; a multisampled normals or output
// texture, and multisampled depth with a second layer, are refused.
#include <epoxy/gl.h>

#include <cstdio>
#include <string>
#include <vector>

#include "gl_support.h"
#include "msaa_depth.h"
#include "msaa_depth_writer.h"
#include "sao/cpu/reference.h"
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

TEST_F(MsaaDepth, BothPoliciesMatchTheCpuReference) {
  const GLuint ms = writeSamples(msaa.extent, test::sampleValues(msaa));
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  const Settings settings = presetSettings(Preset::Medium);
  FloatImage csz[2];
  for (DepthSamplePolicy policy : {DepthSamplePolicy::Sample0, DepthSamplePolicy::Nearest}) {
    const int k = int(policy);
    SCOPED_TRACE(k == 0 ? "Sample0" : "Nearest");
    Camera c = cam;
    c.depthSamplePolicy = policy;
    gl::Inputs gi;
    gi.depth = {ms, gl::kDepthComponent32F};
    const Status st = effect->render(c, settings, gi);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(effect->plan().variants[std::size_t(gen::VariantId::DEPTH_MULTISAMPLE)], 1);
    EXPECT_EQ(effect->params().depth_samples, kSamples);
    cpu::Inputs ci;
    ci.depth = &msaa;
    cpu::Result ref;
    const Status cst = cpu::run(settings, c, ci, cpu::Options{cpu::Precision::Float, 2}, ref);
    ASSERT_TRUE(cst.ok()) << cst.message;
    csz[k] = readTexture(effect->texture(gen::ResourceId::csz), 1);
    EXPECT_EQ(test::differingValues(csz[k], ref.csz[0]), 0u) << "csz level 0, bit for bit";
    const std::string name = std::string("gl_msaa_") + (k == 0 ? "sample0" : "nearest");
    // The output within the GL reference tests' bound (99.9 % within 2/255, none beyond 4/255): the
    // passes after linear_z are the single-sample ones, whose float arithmetic llvmpipe may contract.
    const Agreement a = compare(readTexture(effect->aoTexture(), 1), ref.ao, 0, 2.0 / 255.0, 4.0 / 255.0, name);
    std::printf("AGREEMENT %s: csz level 0 bit for bit; final max %.4f/255 p99.9 %.4f/255\n", name.c_str(),
                a.maxAbs * 255, a.p999 * 255);
    EXPECT_TRUE(acceptable(a)) << name << ": max " << a.maxAbs * 255 << "/255";
  }
  // Not vacuous: the policies keep other samples on many texels.
  EXPECT_GT(test::differingValues(csz[0], csz[1]), csz[0].data.size() / 4);
  deleteTexture(ms);
}

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
  const GLuint ms = writeSamples(msaa.extent, test::sampleValues(msaa));
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
  in.output = 0;
  in.depth = {ms, 0};
  in.depth2 = {single, 0};
  refused(in, StatusCode::InvalidInput, "multisampled depth input has no second layer");
  glDeleteTextures(1, &msNormals);
  glDeleteTextures(1, &msOutput);
  deleteTexture(ms);
  deleteTexture(single);
}

}  // namespace
}  // namespace sao::gltest
