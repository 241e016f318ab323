#include "gl_msaa_depth_writer.h"

#include <gtest/gtest.h>

namespace sao::gltest {
namespace {

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

}  // namespace

GLuint writeSamples(Extent e, const std::vector<float>& values) {
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &tex);
  glTextureStorage2DMultisample(tex, kWriterSamples, GL_DEPTH_COMPONENT32F, GLsizei(e.width), GLsizei(e.height), GL_TRUE);
  writeSamplesInto(tex, -1, e, values);
  return tex;
}

void writeSamplesInto(GLuint tex, GLint layer, Extent e, const std::vector<float>& values) {
  static const char* vs = R"(#version 430
void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); })";
  static const char* fs = R"(#version 430
layout(std430, binding = 0) readonly buffer Samples { float v[]; };
uniform int width;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  gl_FragDepth = v[(p.y * width + p.x) * 4 + gl_SampleID];  // gl_SampleID: one invocation per sample
})";
  GLuint fbo = 0, buffer = 0, vao = 0;
  glCreateFramebuffers(1, &fbo);
  if (layer < 0) glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, tex, 0);
  else glNamedFramebufferTextureLayer(fbo, GL_DEPTH_ATTACHMENT, tex, 0, layer);
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
}


}  // namespace sao::gltest
