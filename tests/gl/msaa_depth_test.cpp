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
#include "sao/cpu/reference.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

constexpr GLsizei kSamples = 4;

GLuint compile(GLenum stage, const char* source) {
  const GLuint s = glCreateShader(stage);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    ADD_FAILURE() << "test shader: " << log;
  }
  return s;
}

// Every sample of a new 4-sample D32F texture set to `values` (texel by texel, samples together).
GLuint writeSamples(Extent e, const std::vector<float>& values) {
  static const char* vs = R"(#version 430
void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); })";
  static const char* fs = R"(#version 430
layout(std430, binding = 0) readonly buffer Samples { float v[]; };
uniform int width;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  gl_FragDepth = v[(p.y * width + p.x) * 4 + gl_SampleID];  // gl_SampleID: one invocation per sample
})";
  GLuint tex = 0, fbo = 0, buffer = 0, vao = 0;
  glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &tex);
  glTextureStorage2DMultisample(tex, kSamples, GL_DEPTH_COMPONENT32F, GLsizei(e.width), GLsizei(e.height), GL_TRUE);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, tex, 0);
  glNamedFramebufferDrawBuffer(fbo, GL_NONE);
  EXPECT_EQ(glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, GLsizeiptr(values.size() * sizeof(float)), values.data(), 0);
  const GLuint program = glCreateProgram();
  const GLuint v = compile(GL_VERTEX_SHADER, vs), f = compile(GL_FRAGMENT_SHADER, fs);
  glAttachShader(program, v);
  glAttachShader(program, f);
  glLinkProgram(program);
  glCreateVertexArrays(1, &vao);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, GLsizei(e.width), GLsizei(e.height));
  glEnable(GL_DEPTH_TEST);  // depth is written only with the test on
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_TRUE);
  glUseProgram(program);
  glUniform1i(glGetUniformLocation(program, "width"), GLint(e.width));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vao);
  glDeleteProgram(program);
  glDeleteShader(v);
  glDeleteShader(f);
  glDeleteBuffers(1, &buffer);
  glDeleteFramebuffers(1, &fbo);
  return tex;
}

class MsaaDepth : public GlTest {
 protected:
  Camera cam = camera(160, 90, 8);
  DepthImage sphere = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
  DepthImage rods = test::renderDepth(test::rodsScene(), cam, DepthFormat::D32F);
  DepthImage sky = test::renderDepth(test::skyScene(), cam, DepthFormat::D32F);
  DepthImage msaa = test::interleaveSamples({&sphere, &rods, &sky}, kSamples);
};

std::size_t differing(const FloatImage& a, const FloatImage& b) {
  std::size_t n = a.data.size() != b.data.size();
  for (std::size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i) n += a.data[i] != b.data[i];
  return n;
}

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
    EXPECT_EQ(differing(csz[k], ref.csz[0]), 0u) << "csz level 0, bit for bit";
    const std::string name = std::string("gl_msaa_") + (k == 0 ? "sample0" : "nearest");
    // The output within the GL reference tests' bound (99.9 % within 2/255, none beyond 4/255): the
    // passes after linear_z are the single-sample ones, whose float arithmetic llvmpipe may contract.
    const Agreement a = compare(readTexture(effect->aoTexture(), 1), ref.ao, 0, 2.0 / 255.0, 4.0 / 255.0, name);
    std::printf("AGREEMENT %s: csz level 0 bit for bit; final max %.4f/255 p99.9 %.4f/255\n", name.c_str(),
                a.maxAbs * 255, a.p999 * 255);
    EXPECT_TRUE(acceptable(a)) << name << ": max " << a.maxAbs * 255 << "/255";
  }
  // Not vacuous: the policies keep other samples on many texels.
  EXPECT_GT(differing(csz[0], csz[1]), csz[0].data.size() / 4);
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
