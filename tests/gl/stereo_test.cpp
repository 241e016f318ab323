// Stereo on OpenGL, GL only (the rest, each layer against a single-eye effect and the CPU reference
// with one plan and one set of textures: tests/executors/stereo_test.cpp): a multisampled depth
// array works per layer; the caller's array bindings are restored; bad layers and mutable arrays
// are refused.
#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "gl_support.h"
#include "msaa_depth.h"
#include "gl_msaa_depth_writer.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

constexpr GLsizei kEyes = 2;

// The eye's camera: `camera(160, 90, 8)` with its frustum shifted by `shift` in NDC x (projection
// row 0, column 2), as VR runtimes give for the left (+) and right (-) eye.
Camera eyeCamera(double shift) {
  Camera c = camera(160, 90, 8);
  c.projection[2 * 4 + 0] += shift;
  return c;
}

class Stereo : public GlTest {
 protected:
  Camera eyes[kEyes] = {eyeCamera(0.04), eyeCamera(-0.04)};
  DepthImage depth[kEyes] = {test::renderDepth(test::sphereOnPlaneScene(), eyes[0], DepthFormat::D32F),
                             test::renderDepth(test::sphereOnPlaneScene(), eyes[1], DepthFormat::D32F)};
  Settings settings = presetSettings(Preset::Medium);
  Extent viewport{160, 90};
};

// A multisampled depth array (GL_TEXTURE_2D_MULTISAMPLE_ARRAY): each layer read per sample.
TEST_F(Stereo, MultisampledDepthArrayLayers) {
  const DepthImage rods = test::renderDepth(test::rodsScene(), eyes[1], DepthFormat::D32F);
  const DepthImage sky = test::renderDepth(test::skyScene(), eyes[1], DepthFormat::D32F);
  const DepthImage ms[kEyes] = {test::interleaveSamples({&depth[0]}, kWriterSamples),
                                test::interleaveSamples({&depth[1], &rods, &sky}, kWriterSamples)};
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, 1, &t);
  glTextureStorage3DMultisample(t, kWriterSamples, GL_DEPTH_COMPONENT32F, GLsizei(depth[0].extent.width),
                                GLsizei(depth[0].extent.height), kEyes, GL_TRUE);
  for (GLint eye = 0; eye < kEyes; ++eye) writeSamplesInto(t, eye, depth[0].extent, test::sampleValues(ms[eye]));
  auto effect = makeEffect();
  for (GLsizei eye = 0; eye < kEyes; ++eye) {
    Camera c = eyes[eye];
    c.depthSamplePolicy = DepthSamplePolicy::Nearest;
    gl::Inputs in;
    in.depth = {t, 0};
    in.layer = std::uint32_t(eye);
    const Status st = effect->render(c, settings, in);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(effect->plan().variants[std::size_t(gen::VariantId::DEPTH_MULTISAMPLE)], 1);
    cpu::Inputs ci;
    ci.depth = &ms[eye];
    cpu::Result ref;
    ASSERT_TRUE(cpu::run(settings, c, ci, cpu::Options{cpu::Precision::Float, 2}, ref).ok());
    EXPECT_EQ(test::differingValues(readTexture(effect->texture(gen::ResourceId::csz), 1), ref.csz[0]), 0u) << "eye " << eye;
  }
  EXPECT_EQ(effect->stats().plans, 1u);
  EXPECT_EQ(effect->stats().renders, 2u) << "every layer's render counted";
  deleteTexture(t);
}

TEST_F(Stereo, CallersArrayBindingsAreRestored) {
  const GLuint depthArray = uploadDepthArray(GL_DEPTH_COMPONENT32F, {&depth[0], &depth[1]});
  const GLuint other = makeTextureArray(GL_R16F, viewport, kEyes);
  for (GLuint unit = 0; unit < 8; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, other);
  }
  glActiveTexture(GL_TEXTURE0);
  auto effect = makeEffect();
  gl::Inputs in;
  in.depth = {depthArray, 0};
  in.layer = 1;
  ASSERT_TRUE(effect->render(eyes[1], settings, in).ok());
  for (GLuint unit = 0; unit < 8; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    GLint bound = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &bound);
    EXPECT_EQ(GLuint(bound), other) << "unit " << unit;
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  }
  glActiveTexture(GL_TEXTURE0);
  deleteTexture(depthArray);
  deleteTexture(other);
}

TEST_F(Stereo, BadLayersAreRefused) {
  const GLuint depthArray = uploadDepthArray(GL_DEPTH_COMPONENT32F, {&depth[0], &depth[1]});
  const GLuint plain = uploadDepth(depth[0], GlDepth::D32F);
  const GLuint plainOut = makeTexture(GL_R16F, viewport);
  GLuint mutableArray = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &mutableArray);
  glBindTexture(GL_TEXTURE_2D_ARRAY, mutableArray);
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, GLsizei(depth[0].extent.width),
               GLsizei(depth[0].extent.height), kEyes, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  auto effect = makeEffect();
  auto refused = [&](const gl::Inputs& in, const std::string& words) {
    const Status st = effect->render(eyes[0], settings, in);
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    EXPECT_NE(st.message.find(words), std::string::npos) << st.message;
  };
  gl::Inputs in;
  in.depth = {depthArray, 0};
  in.layer = 2;
  refused(in, "has 2 layers, but Inputs::layer is 2");
  in.depth = {plain, 0};
  in.layer = 1;
  refused(in, "depth texture " + std::to_string(plain) + " is a GL_TEXTURE_2D, which has no layers, but Inputs::layer is 1");
  in.depth = {depthArray, 0};
  in.output = plainOut;
  refused(in, "output texture " + std::to_string(plainOut) + " is a GL_TEXTURE_2D, which has no layers");
  in.output = 0;
  in.depth = {mutableArray, 0};
  in.layer = 0;
  refused(in, "without immutable storage (glTexImage3D)");
  EXPECT_EQ(effect->stats().textureAllocations, 0u) << "nothing allocated for refused inputs";
  glDeleteTextures(1, &mutableArray);
  deleteTexture(depthArray);
  deleteTexture(plain);
  deleteTexture(plainOut);
}

}  // namespace
}  // namespace sao::gltest
