#include "gl_prepass.h"

#include <glm/gtc/type_ptr.hpp>

#include "gl_util.h"
#include "viewer_glsl.h"

namespace sao::viewer {

GlPrepass::~GlPrepass() {
  glDeleteProgram(program_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &vbo_);
  glDeleteBuffers(1, &ibo_);
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &depth_);
}

Status GlPrepass::init() {
  if (Status s = linkProgram(glsl::kPrepassVert, {}, "prepass", program_); !s) return s;
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glGenBuffers(1, &ibo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo_);  // recorded in the VAO
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return Status::success();
}

void GlPrepass::setMesh(const scenes::Mesh& mesh) {
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.positions.size() * sizeof(glm::vec3)), mesh.positions.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindVertexArray(vao_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)), mesh.indices.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  indexCount_ = GLsizei(mesh.indices.size());
}

Status GlPrepass::resize(int width, int height) {
  if (width == width_ && height == height_ && depth_) return Status::success();
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &depth_);
  glGenTextures(1, &depth_);
  glBindTexture(GL_TEXTURE_2D, depth_);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, width, height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    return Status::error(StatusCode::DriverError, "the prepass framebuffer is incomplete");
  width_ = width;
  height_ = height;
  return Status::success();
}

void GlPrepass::render(const glm::dmat4& mvp, bool reversedZ) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(reversedZ ? GL_GREATER : GL_LESS);
  glClearDepth(reversedZ ? 0.0 : 1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glDisable(GL_CULL_FACE);  // thin panels are seen from both sides
  glUseProgram(program_);
  const glm::mat4 m(mvp);
  glUniformMatrix4fv(0, 1, GL_FALSE, glm::value_ptr(m));
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace sao::viewer
