// sao::gl::Effect on bad input (docs/ROBUSTNESS.md), what only GL has: other header versions,
// deleted and storage-less textures, multisampled depth (with and without GL 4.5 direct state
// access), stencil-only and integer textures, normals texture formats, every input also passed as
// the output. Every case must return the documented code with a message, raise no GL error (the
// fixture fails on any GL_DEBUG_TYPE_ERROR), allocate nothing, and leave the context and the
// effect usable: the same effect then renders what a fresh one renders. Settings, cameras, sizes
// and two-channel normals on both APIs: tests/executors/robustness_test.cpp.
#include <epoxy/gl.h>

#include <cstring>

#include "image_compare.h"
#include "analytic_scenes.h"
#include "gl_support.h"
#include "normal_encodings.h"

namespace sao::gltest {
namespace {

using test::sameBits;

// A loader that hides glGetTextureParameteriv: the effect takes its GL 4.3 path (no DSA).
gl::ProcAddress noDsaLoader(const char* name) {
  if (std::strcmp(name, "glGetTextureParameteriv") == 0) return nullptr;
  return gl::HeadlessContext::getProcAddress()(name);
}

class Robustness : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    effect = makeEffect();
    camera = gltest::camera(64, 36, 8);
    depth = test::renderDepth(test::sphereOnPlaneScene(), camera, cpuFormat(GlDepth::D24));
    texture = uploadDepth(depth, GlDepth::D24);
  }
  void TearDown() override {
    // Whatever came before, the effect still renders what a fresh effect renders.
    if (effect && !HasFatalFailure()) {
      const Status st = render(good());
      EXPECT_TRUE(st.ok()) << "the effect is not usable after the bad calls: " << st.message;
      auto fresh = makeEffect();
      ASSERT_TRUE(fresh->render(camera, Settings{}, good()).ok());
      EXPECT_TRUE(sameBits(readTexture(effect->aoTexture(), 1), readTexture(fresh->aoTexture(), 1)));
    }
    deleteTexture(texture);
    effect.reset();
    GlTest::TearDown();
  }
  gl::Inputs good() const {
    gl::Inputs in;
    in.depth = {texture, gl::kDepthComponent24};
    return in;
  }
  Status render(const gl::Inputs& in, const Settings& s = {}) { return effect->render(camera, s, in); }
  // The call fails with `code`, names `needle`, and allocates nothing.
  void expectRejected(const Status& st, StatusCode code, const std::string& needle, std::uint64_t allocationsBefore) {
    EXPECT_EQ(st.code, code) << toString(st.code) << ": " << st.message;
    EXPECT_NE(st.message.find(needle), std::string::npos) << "expected \"" << needle << "\" in: " << st.message;
    EXPECT_EQ(effect->stats().textureAllocations, allocationsBefore) << st.message;
  }

  std::unique_ptr<gl::Effect> effect;
  Camera camera;
  DepthImage depth;
  GLuint texture = 0;
};

TEST_F(Robustness, OtherHeaderVersionsAreRejected) {
  for (int version : {SAO_VERSION - 1, SAO_VERSION + (1 << 8), SAO_VERSION + (1 << 16), 0, -1}) {
    std::unique_ptr<gl::Effect> e;
    const Status st = gl::Effect::create(gl::HeadlessContext::getProcAddress(), e, version);
    EXPECT_EQ(st.code, StatusCode::VersionMismatch) << version << ": " << st.message;
    EXPECT_FALSE(e);
  }
}

TEST_F(Robustness, DeletedAndStoragelessTextures) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);  // a texture object now, but without any image
  glBindTexture(GL_TEXTURE_2D, 0);
  gl::Inputs in;
  in.depth = {t, 0};
  expectRejected(render(in), StatusCode::InvalidInput, "has no level 0 image", 0);
  glDeleteTextures(1, &t);
  expectRejected(render(in), StatusCode::InvalidInput, "is not a texture object", 0);
  in = good();
  in.normals = 0xFFFFFFFFu;
  expectRejected(render(in), StatusCode::InvalidInput, "normals texture 4294967295 is not a texture", 0);
}

GLuint multisampleDepth(Extent e) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, t);
  glTexStorage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, 4, GL_DEPTH_COMPONENT24, GLsizei(e.width), GLsizei(e.height),
                            GL_TRUE);
  glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
  return t;
}

// Only the depth input may be multisampled (it is read directly: msaa_depth_test.cpp); a
// multisampled second layer is refused with a clear error.
TEST_F(Robustness, MultisampledSecondLayerIsRejected) {
  const GLuint ms = multisampleDepth(depth.extent);
  gl::Inputs in = good();
  in.depth2 = {ms, 0};
  expectRejected(render(in), StatusCode::UnsupportedFormat,
                 "depth2 texture " + std::to_string(ms) + " is multisampled (GL_TEXTURE_2D_MULTISAMPLE); only "
                 "the depth input may be",
                 0);
  glDeleteTextures(1, &ms);
}

// Without GL 4.5 the target cannot be queried: the failed bind is detected (and not mistaken for
// the caller's own texture still bound on that unit). The bind's GL_INVALID_OPERATION is expected.
TEST_F(Robustness, MultisampledDepthWithoutDirectStateAccess) {
  std::unique_ptr<gl::Effect> e;
  ASSERT_TRUE(gl::Effect::create(&noDsaLoader, e).ok());
  ASSERT_TRUE(e->render(camera, Settings{}, good()).ok()) << "the GL 4.3 path renders";
  const GLuint ms = multisampleDepth(depth.extent);
  // The caller's own 2D texture of the right size and format bound on every unit the effect uses.
  const GLuint decoy = uploadDepth(depth, GlDepth::D24);
  for (GLuint unit = 0; unit < 8; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, decoy);
  }
  glActiveTexture(GL_TEXTURE0);
  gl::Inputs in;
  in.depth = {ms, 0};
  const Status st = e->render(camera, Settings{}, in);
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  EXPECT_NE(st.message.find("cannot be bound as GL_TEXTURE_2D"), std::string::npos) << st.message;
  const auto errors = context().errors();
  EXPECT_EQ(errors.size(), 1u) << "the one failed glBindTexture";
  context().clearMessages();
  for (GLuint unit = 0; unit < 8; ++unit) {
    GLint bound = 0;
    glActiveTexture(GL_TEXTURE0 + unit);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    EXPECT_EQ(GLuint(bound), decoy) << "unit " << unit << " restored";
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glActiveTexture(GL_TEXTURE0);
  deleteTexture(decoy);
  glDeleteTextures(1, &ms);
  e.reset();
}

TEST_F(Robustness, StencilOnlyAndIntegerTexturesAreUnsupported) {
  for (GLenum format : {GLenum(GL_STENCIL_INDEX8), GLenum(GL_R32UI), GLenum(GL_RGBA16F), GLenum(GL_R16F)}) {
    const GLuint t = makeTexture(format, depth.extent);
    gl::Inputs in;
    in.depth = {t, 0};
    expectRejected(render(in), StatusCode::UnsupportedFormat, "depth must be", 0);
    deleteTexture(t);
  }
}

// Motion vectors only in the formats effect/sao.glsl lists for the input (formats=): another is
// refused naming the list (core's one contract for a declared input, sao/inputs.h).
TEST_F(Robustness, MotionTextureFormatsAreTheDeclaredOnes) {
  Settings temporal;
  temporal.temporal = true;
  Camera cam = camera;
  cam.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  for (GLenum format : {GLenum(GL_R16F), GLenum(GL_RGBA8), GLenum(GL_RG16_SNORM)}) {
    const GLuint t = makeTexture(format, depth.extent);
    gl::Inputs in = good();
    in.motion = t;
    expectRejected(effect->render(cam, temporal, in), StatusCode::UnsupportedFormat,
                   "; motion must be GL_RG16F, GL_RG32F, GL_RGBA16F or GL_RGBA32F", 0);
    deleteTexture(t);
  }
}

// Normals texture formats against Camera::normalsEncoding: a two-channel texture with an xyz
// encoding is refused naming the texture, its format and the encoding; one channel is never a
// normals format. The SNORM two-channel formats are then accepted with an octahedral encoding, by
// the same effect (GL_RG16F, GL_RG32F and the refusals' codes on both APIs:
// Robustness.TwoChannelNormalsNeedAnOctahedralEncoding in tests/executors/robustness_test.cpp).
TEST_F(Robustness, NormalsTextureFormatsFollowTheEncoding) {
  const GLuint rg16f = makeTexture(GL_RG16F, depth.extent);
  gl::Inputs in = good();
  in.normals = rg16f;
  Camera cam = camera;
  cam.viewRotation = test::viewRotation(0.7, -0.4, 0.25);
  for (auto [encoding, name] :
       {std::pair{NormalsEncoding::CameraXyz, "CameraXyz"}, std::pair{NormalsEncoding::WorldXyz, "WorldXyz"}}) {
    cam.normalsEncoding = encoding;
    expectRejected(effect->render(cam, Settings{}, in), StatusCode::UnsupportedFormat,
                   "sao::gl: the normals texture " + std::to_string(rg16f) + " is GL_RG16F (two channels) but " +
                       "Camera::normalsEncoding is " + name +
                       ", which reads .xyz: use an octahedral encoding or a three- or four-channel texture",
                   0);
  }
  const GLuint r16f = makeTexture(GL_R16F, depth.extent);
  in.normals = r16f;
  cam.normalsEncoding = NormalsEncoding::CameraOctahedral;
  expectRejected(effect->render(cam, Settings{}, in), StatusCode::UnsupportedFormat,
                 "is GL_R16F (one channel) but Camera::normalsEncoding is CameraOctahedral, which reads .xy: use a "
                 "two-, three- or four-channel texture",
                 0);
  deleteTexture(r16f);
  const GLuint rgba8 = makeTexture(GL_RGBA8, depth.extent);  // unsigned normalised: no signed components
  in.normals = rgba8;
  expectRejected(effect->render(cam, Settings{}, in), StatusCode::UnsupportedFormat,
                 "is GL_RGBA8; the normals input cannot be read from that format", 0);
  deleteTexture(rgba8);
  deleteTexture(rg16f);
  for (GLenum format : {GLenum(GL_RG8_SNORM), GLenum(GL_RG16_SNORM)}) {
    const GLuint t = makeTexture(format, depth.extent);
    const float zero[2] = {0, 0};  // (0, 0): the octahedral +z, facing the camera
    glClearTexImage(t, 0, GL_RG, GL_FLOAT, zero);
    in.normals = t;
    for (NormalsEncoding e : {NormalsEncoding::CameraOctahedral, NormalsEncoding::WorldOctahedral}) {
      cam.normalsEncoding = e;
      const Status st = effect->render(cam, Settings{}, in);
      EXPECT_TRUE(st.ok()) << format << " " << int(e) << ": " << st.message;
    }
    deleteTexture(t);
  }
}

// Every input also passed as the output (a feedback loop: the passes would read what they write).
TEST_F(Robustness, EveryInputAlsoPassedAsTheOutput) {
  const GLuint normals = makeTexture(GL_RGBA16F, depth.extent);
  const GLuint second = uploadDepth(depth, GlDepth::D24);
  gl::Inputs in = good();
  in.normals = normals;
  in.depth2 = {second, 0};
  for (const auto& [output, role] : {std::pair{texture, "depth"}, std::pair{second, "depth2"},
                                     std::pair{normals, "normals"}}) {
    gl::Inputs bad = in;
    bad.output = output;
    expectRejected(render(bad), StatusCode::InvalidInput,
                   std::string("is passed both as the output and as the ") + role + " input", 0);
  }
  deleteTexture(normals);
  deleteTexture(second);
}

}  // namespace
}  // namespace sao::gltest
