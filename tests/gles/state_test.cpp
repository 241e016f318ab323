// sao::gles leaves the caller's ES state as it found it (sao/gl/effect.h's contract, on an ES 3.1
// context): the program, the active unit, every texture unit's 2D binding and sampler, every image
// unit, the uniform-buffer bindings, and the depth texture's parameters, with an RGBA8 output whose
// texels the final pass keeps (read through a texture unit of its own on ES) and a multiply blend.
#include <epoxy/gl.h>

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "sao/gl/headless.h"
#include "sao/gles/effect.h"

namespace sao {
namespace {

using Snapshot = std::map<std::string, std::vector<GLint64>>;

constexpr GLuint kTextureUnits = 16, kImageUnits = 8;

GLint64 get(GLenum pname) {
  GLint64 v = 0;
  glGetInteger64v(pname, &v);
  return v;
}

GLint64 getAt(GLenum pname, GLuint index) {
  GLint64 v = 0;
  glGetInteger64i_v(pname, index, &v);
  return v;
}

Snapshot snapshot(GLuint depth) {
  Snapshot s;
  const auto active = GLenum(get(GL_ACTIVE_TEXTURE));
  s["active texture"] = {active};
  s["program"] = {get(GL_CURRENT_PROGRAM)};
  s["uniform buffer"] = {get(GL_UNIFORM_BUFFER_BINDING)};
  s["uniform buffer 0"] = {getAt(GL_UNIFORM_BUFFER_BINDING, 0), getAt(GL_UNIFORM_BUFFER_START, 0),
                           getAt(GL_UNIFORM_BUFFER_SIZE, 0)};
  for (GLuint u = 0; u < kTextureUnits; ++u) {
    glActiveTexture(GL_TEXTURE0 + u);
    s["texture unit " + std::to_string(u)] = {get(GL_TEXTURE_BINDING_2D), get(GL_SAMPLER_BINDING)};
  }
  for (GLuint u = 0; u < kImageUnits; ++u)
    s["image unit " + std::to_string(u)] = {getAt(GL_IMAGE_BINDING_NAME, u), getAt(GL_IMAGE_BINDING_LEVEL, u),
                                            getAt(GL_IMAGE_BINDING_LAYERED, u), getAt(GL_IMAGE_BINDING_LAYER, u),
                                            getAt(GL_IMAGE_BINDING_ACCESS, u), getAt(GL_IMAGE_BINDING_FORMAT, u)};
  // The depth texture's parameters, read on the active unit and put back as they were bound.
  const GLint64 bound = get(GL_TEXTURE_BINDING_2D);
  glBindTexture(GL_TEXTURE_2D, depth);
  for (GLenum p : {GL_TEXTURE_BASE_LEVEL, GL_TEXTURE_MAX_LEVEL, GL_TEXTURE_COMPARE_MODE, GL_TEXTURE_MIN_FILTER,
                   GL_TEXTURE_MAG_FILTER, GL_TEXTURE_SWIZZLE_R, GL_DEPTH_STENCIL_TEXTURE_MODE}) {
    GLint v = 0;
    glGetTexParameteriv(GL_TEXTURE_2D, p, &v);
    s["depth parameter " + std::to_string(p)] = {v};
  }
  glBindTexture(GL_TEXTURE_2D, GLuint(bound));
  glActiveTexture(active);
  return s;
}

GLuint texture(GLenum format, GLsizei w, GLsizei h) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glBindTexture(GL_TEXTURE_2D, t);
  glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
  glBindTexture(GL_TEXTURE_2D, 0);
  return t;
}

class GlesState : public ::testing::Test {
 protected:
  void SetUp() override {
    gl::HeadlessOptions o;
    o.es = true;
    o.major = 3;
    o.minor = 1;
    ASSERT_TRUE(gl::HeadlessContext::create(ctx_, o).ok());
    ASSERT_TRUE(gles::Effect::create(gl::HeadlessContext::getProcAddress(), effect_).ok());
  }
  void TearDown() override {
    effect_.reset();
    for (const auto& m : ctx_->errors()) ADD_FAILURE() << "GLES debug message: " << gl::HeadlessContext::format(m);
  }
  std::unique_ptr<gl::HeadlessContext> ctx_;
  std::unique_ptr<gles::Effect> effect_;
};

TEST_F(GlesState, RenderRestoresEverythingItTouches) {
  Camera cam = perspectiveCamera(std::numbers::pi / 3, 64, 36, 0.1, 100.0, ClipDepth::NegativeOneToOne, false);
  cam.guardBand = 4;
  const GLsizei w = 72, h = 44;
  // A tilted floor: depth varying across the image, so that every pass has work.
  std::vector<float> d(std::size_t(w) * h);
  for (GLsizei y = 0; y < h; ++y)
    for (GLsizei x = 0; x < w; ++x) d[std::size_t(y) * w + x] = 0.9f + 0.09f * float(y) / float(h) + 0.0005f * float(x);
  const GLuint depth = texture(GL_DEPTH_COMPONENT32F, w, h);
  glBindTexture(GL_TEXTURE_2D, depth);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, d.data());
  // The caller's own parameters on the depth (the effect sets base level and swizzle R itself).
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_R, GL_GREEN);
  glBindTexture(GL_TEXTURE_2D, 0);
  const GLuint output = texture(GL_RGBA8, 64, 36);

  // The caller's bindings on every unit the effect could use.
  std::vector<GLuint> dummies(kTextureUnits), samplers(kTextureUnits);
  glGenSamplers(GLsizei(kTextureUnits), samplers.data());
  for (GLuint u = 0; u < kTextureUnits; ++u) {
    dummies[u] = texture(GL_RGBA8, 4, 4);
    glActiveTexture(GL_TEXTURE0 + u);
    glBindTexture(GL_TEXTURE_2D, dummies[u]);
    glBindSampler(u, samplers[u]);
  }
  for (GLuint u = 0; u < kImageUnits; ++u)
    glBindImageTexture(u, dummies[u], 0, GL_FALSE, 0, u % 2 ? GL_READ_ONLY : GL_WRITE_ONLY, GL_RGBA8);
  GLuint ubo = 0;
  glGenBuffers(1, &ubo);
  glBindBuffer(GL_UNIFORM_BUFFER, ubo);
  glBufferData(GL_UNIFORM_BUFFER, 512, nullptr, GL_STATIC_DRAW);
  glBindBufferRange(GL_UNIFORM_BUFFER, 0, ubo, 256, 128);
  const char* src = "#version 310 es\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER), program = glCreateProgram();
  glShaderSource(shader, 1, &src, nullptr);
  glCompileShader(shader);
  glAttachShader(program, shader);
  glLinkProgram(program);
  glUseProgram(program);
  glActiveTexture(GL_TEXTURE5);

  const Snapshot before = snapshot(depth);
  gles::Inputs in;
  in.depth = {depth, gles::kDepthComponent32F};
  in.output = output;
  in.outputChannels = kChannelR | kChannelA;  // G and B kept: the pass reads them through a texture
  for (OutputBlend blend : {OutputBlend::Replace, OutputBlend::Multiply}) {
    in.outputBlend = blend;
    const Status st = effect_->render(cam, Settings{}, in);
    ASSERT_TRUE(st.ok()) << st.message;
    const Snapshot after = snapshot(depth);
    for (const auto& [what, values] : before) EXPECT_EQ(after.at(what), values) << what;
  }

  glUseProgram(0);
  glDeleteProgram(program);
  glDeleteShader(shader);
  glDeleteBuffers(1, &ubo);
  glDeleteSamplers(GLsizei(kTextureUnits), samplers.data());
  glDeleteTextures(GLsizei(kTextureUnits), dummies.data());
  glDeleteTextures(1, &output);
  glDeleteTextures(1, &depth);
}

}  // namespace
}  // namespace sao
