// The GL state the prepass changes, saved on construction and put back on destruction, so that it
// can run inside a caller's context. (With its own context nothing else uses that state, but the
// same code path keeps the two cases alike.)
#pragma once
#include <epoxy/gl.h>

#include <array>

namespace sao::prepass::detail {

class GlStateGuard {
 public:
  GlStateGuard();  // saves, then sets the neutral state the prepass relies on
  ~GlStateGuard();
  GlStateGuard(const GlStateGuard&) = delete;
  GlStateGuard& operator=(const GlStateGuard&) = delete;

 private:
  static constexpr std::array<GLenum, 15> kCaps = {
      GL_DEPTH_TEST,      GL_SCISSOR_TEST,    GL_CULL_FACE,       GL_POLYGON_OFFSET_FILL, GL_RASTERIZER_DISCARD,
      GL_DEPTH_CLAMP,     GL_STENCIL_TEST,    GL_CLIP_DISTANCE0,  GL_CLIP_DISTANCE1,      GL_CLIP_DISTANCE2,
      GL_CLIP_DISTANCE3,  GL_CLIP_DISTANCE4,  GL_CLIP_DISTANCE5,  GL_CLIP_DISTANCE6,      GL_CLIP_DISTANCE7};
  std::array<GLboolean, kCaps.size()> caps_{};
  GLboolean blend_[2]{}, colorMask_[2][4]{};
  GLint drawFbo_ = 0, readFbo_ = 0, viewport_[4]{}, depthFunc_ = 0, program_ = 0, vao_ = 0;
  GLboolean depthMask_ = GL_TRUE;
  GLdouble depthClear_ = 1, depthRange_[2]{0, 1};
  GLint clipOrigin_ = 0, clipDepth_ = 0, polygonMode_[2]{}, provoking_ = 0;
  GLint uboGeneric_ = 0, ubo0_ = 0;
  GLint64 ubo0Start_ = 0, ubo0Size_ = 0;
  GLint activeTexture_ = 0, texture1_ = 0, sampler1_ = 0;
  GLint packBuffer_ = 0, pack_[6]{};
  GLboolean packSwap_ = GL_FALSE, packLsb_ = GL_FALSE;
};

}  // namespace sao::prepass::detail
