// Stereo on OpenGL (Inputs::layer): two eyes with mirrored off-axis projections, their depth in
// one 2-layer GL_TEXTURE_2D_ARRAY and their AO in one 2-layer output array, rendered by ONE effect
// (one plan, one set of programs and intermediate textures). Each layer is bit-identical to a
// single-eye effect on plain 2D textures and agrees with the CPU reference; the second eye and
// later frames plan nothing and create no texture; a multisampled depth array works per layer;
// the caller's array bindings are restored; bad layers and mutable arrays are refused.
#include <epoxy/gl.h>

#include <cstdio>
#include <string>
#include <vector>

#include "gl_support.h"
#include "msaa_depth.h"
#include "gl_msaa_depth_writer.h"
#include "sao/frame.h"
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

FloatImage readLayer(GLuint t, Extent e, GLint layer) {
  FloatImage img(e, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureSubImage(t, 0, 0, 0, layer, GLsizei(e.width), GLsizei(e.height), 1, GL_RED, GL_FLOAT,
                       GLsizei(img.data.size() * sizeof(float)), img.data.data());
  return img;
}

class Stereo : public GlTest {
 protected:
  Camera eyes[kEyes] = {eyeCamera(0.04), eyeCamera(-0.04)};
  DepthImage depth[kEyes] = {test::renderDepth(test::sphereOnPlaneScene(), eyes[0], DepthFormat::D32F),
                             test::renderDepth(test::sphereOnPlaneScene(), eyes[1], DepthFormat::D32F)};
  Settings settings = presetSettings(Preset::Medium);
  Extent viewport{160, 90};
};

TEST_F(Stereo, OneEffectRendersBothLayersAsTwoEffectsWould) {
  Plan a, b;
  ASSERT_TRUE(plan(settings, eyes[0], {}, a).ok());
  ASSERT_TRUE(plan(settings, eyes[1], {}, b).ok());
  ASSERT_EQ(a.describe(), b.describe()) << "mirrored eyes plan alike";
  EXPECT_TRUE(cameraKeepsPlan(settings, eyes[0], eyes[1]));
  const GLuint depthArray = uploadDepthArray(GL_DEPTH_COMPONENT32F, {&depth[0], &depth[1]});
  const GLuint outArray = makeTextureArray(GL_R16F, viewport, kEyes);
  auto stereo = makeEffect();
  ASSERT_TRUE(stereo);
  gl::Stats afterFirstFrame{};
  for (int frame = 0; frame < 4; ++frame) {
    for (GLsizei eye = 0; eye < kEyes; ++eye) {
      gl::Inputs in;
      in.depth = {depthArray, gl::kDepthComponent32F};
      in.output = outArray;
      in.layer = std::uint32_t(eye);
      const Status st = stereo->render(eyes[eye], settings, in);
      ASSERT_TRUE(st.ok()) << st.message;
    }
    if (frame == 0) afterFirstFrame = stereo->stats();
  }
  // The fixed costs, paid once: one plan, one set of programs and intermediate textures.
  EXPECT_EQ(stereo->stats().plans, 1u) << "the second eye and later frames plan nothing";
  EXPECT_EQ(stereo->stats().programsCompiled, afterFirstFrame.programsCompiled);
  EXPECT_EQ(stereo->stats().textureAllocations, afterFirstFrame.textureAllocations);
  EXPECT_EQ(stereo->stats().renders, 8u);

  std::uint64_t singleBytes = 0, singlePrograms = 0, singleTextures = 0;
  for (GLsizei eye = 0; eye < kEyes; ++eye) {
    SCOPED_TRACE(eye == 0 ? "left" : "right");
    const FloatImage layer = readLayer(outArray, viewport, eye);
    auto single = makeEffect();
    const GLuint depthTex = uploadDepth(depth[eye], GlDepth::D32F);
    gl::Inputs in;
    in.depth = {depthTex, gl::kDepthComponent32F};
    ASSERT_TRUE(single->render(eyes[eye], settings, in).ok());
    EXPECT_EQ(test::differingValues(layer, readTexture(single->aoTexture(), 1)), 0u) << "bit for bit the single-eye effect's";
    singleBytes += single->plan().totalBytes;
    singlePrograms += single->stats().programsCompiled;
    singleTextures += single->stats().textureAllocations;
    cpu::Inputs ci;
    ci.depth = &depth[eye];
    cpu::Result ref;
    ASSERT_TRUE(cpu::run(settings, eyes[eye], ci, cpu::Options{cpu::Precision::Float, 2}, ref).ok());
    const Agreement g = compare(layer, ref.ao, 0, 2.0 / 255.0, 4.0 / 255.0, std::string("gl_stereo_eye") + char('0' + eye));
    EXPECT_TRUE(acceptable(g)) << "max " << g.maxAbs * 255 << "/255";
    std::printf("STEREO eye %d: vs single-eye effect 0 differing texels; vs CPU max %.4f/255\n", int(eye), g.maxAbs * 255);
    deleteTexture(depthTex);
  }
  // The output is the caller's here, so the effect's bytes are its intermediates; the owned R16F
  // output of each single-eye effect is counted in theirs.
  std::printf("STEREO one effect: %llu bytes, %llu programs, %llu textures; two single-eye effects: %llu bytes, %llu "
              "programs, %llu textures\n",
              (unsigned long long)stereo->plan().totalBytes, (unsigned long long)stereo->stats().programsCompiled,
              (unsigned long long)stereo->stats().textureAllocations, (unsigned long long)singleBytes,
              (unsigned long long)singlePrograms, (unsigned long long)singleTextures);
  EXPECT_EQ(2 * stereo->stats().programsCompiled, singlePrograms);
  EXPECT_LT(2 * stereo->plan().totalBytes, singleBytes + 1) << "one set of intermediates for both eyes";
  deleteTexture(depthArray);
  deleteTexture(outArray);
}

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
