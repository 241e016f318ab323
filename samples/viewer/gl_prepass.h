// The OpenGL depth-only prepass: the scene mesh (VBO + IBO) rasterised into the viewer's own
// GL_DEPTH_COMPONENT32F texture, which is then the effect's depth input.
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>

#include "sao/scenes/mesh.h"
#include "sao/status.h"

namespace sao::viewer {

class GlPrepass {
 public:
  GlPrepass() = default;
  ~GlPrepass();
  GlPrepass(const GlPrepass&) = delete;
  GlPrepass& operator=(const GlPrepass&) = delete;

  Status init();
  void setMesh(const scenes::Mesh& mesh);
  Status resize(int width, int height);  // (re)creates the depth texture and its framebuffer
  // Clears to the far plane's depth and draws the mesh; `mvp` is projection * view in double.
  void render(const glm::dmat4& mvp, bool reversedZ);
  GLuint depthTexture() const { return depth_; }

 private:
  GLuint program_ = 0, vao_ = 0, vbo_ = 0, ibo_ = 0, fbo_ = 0, depth_ = 0;
  GLsizei indexCount_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace sao::viewer
