#include "gl_state.h"

namespace sao::prepass::detail {
namespace {
constexpr GLenum kPack[6] = {GL_PACK_ALIGNMENT,   GL_PACK_ROW_LENGTH,   GL_PACK_SKIP_ROWS,
                             GL_PACK_SKIP_PIXELS, GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_IMAGES};
void setCap(GLenum cap, GLboolean on) { on ? glEnable(cap) : glDisable(cap); }
}  // namespace

GlStateGuard::GlStateGuard() {
  for (std::size_t i = 0; i < kCaps.size(); ++i) caps_[i] = glIsEnabled(kCaps[i]);
  for (GLuint i = 0; i < 2; ++i) {
    blend_[i] = glIsEnabledi(GL_BLEND, i);
    glGetBooleani_v(GL_COLOR_WRITEMASK, i, colorMask_[i]);
  }
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFbo_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFbo_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask_);
  glGetDoublev(GL_DEPTH_CLEAR_VALUE, &depthClear_);
  glGetDoublev(GL_DEPTH_RANGE, depthRange_);
  glGetIntegerv(GL_CLIP_ORIGIN, &clipOrigin_);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &clipDepth_);
  glGetIntegerv(GL_POLYGON_MODE, polygonMode_);
  glGetIntegerv(GL_PROVOKING_VERTEX, &provoking_);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uboGeneric_);
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &ubo0_);
  glGetInteger64i_v(GL_UNIFORM_BUFFER_START, 0, &ubo0Start_);
  glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, 0, &ubo0Size_);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
  glActiveTexture(GL_TEXTURE1);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture1_);
  glGetIntegerv(GL_SAMPLER_BINDING, &sampler1_);
  glActiveTexture(GLenum(activeTexture_));
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &packBuffer_);
  for (int i = 0; i < 6; ++i) glGetIntegerv(kPack[i], &pack_[i]);
  glGetBooleanv(GL_PACK_SWAP_BYTES, &packSwap_);
  glGetBooleanv(GL_PACK_LSB_FIRST, &packLsb_);

  // The neutral state: nothing but the depth test (set per pass) shapes what is drawn or read.
  for (GLenum cap : kCaps) glDisable(cap);
  for (GLuint i = 0; i < 2; ++i) {
    glDisablei(GL_BLEND, i);
    glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  glDepthMask(GL_TRUE);
  glDepthRange(0.0, 1.0);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  // Vulkan's convention: rasterisers that set up attribute and depth planes from the provoking
  // vertex (llvmpipe) then round exactly as the Vulkan prepass does.
  glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
  glBindSampler(1, 0);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (int i = 1; i < 6; ++i) glPixelStorei(kPack[i], 0);
  glPixelStorei(GL_PACK_SWAP_BYTES, GL_FALSE);
  glPixelStorei(GL_PACK_LSB_FIRST, GL_FALSE);
}

GlStateGuard::~GlStateGuard() {
  for (std::size_t i = 0; i < kCaps.size(); ++i) setCap(kCaps[i], caps_[i]);
  for (GLuint i = 0; i < 2; ++i) {
    blend_[i] ? glEnablei(GL_BLEND, i) : glDisablei(GL_BLEND, i);
    glColorMaski(i, colorMask_[i][0], colorMask_[i][1], colorMask_[i][2], colorMask_[i][3]);
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(drawFbo_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(readFbo_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glDepthFunc(GLenum(depthFunc_));
  glDepthMask(depthMask_);
  glClearDepth(depthClear_);
  glDepthRange(depthRange_[0], depthRange_[1]);
  glClipControl(GLenum(clipOrigin_), GLenum(clipDepth_));
  glPolygonMode(GL_FRONT_AND_BACK, GLenum(polygonMode_[0]));
  glProvokingVertex(GLenum(provoking_));
  glUseProgram(GLuint(program_));
  glBindVertexArray(GLuint(vao_));
  if (ubo0_ != 0 && ubo0Size_ > 0)
    glBindBufferRange(GL_UNIFORM_BUFFER, 0, GLuint(ubo0_), GLintptr(ubo0Start_), GLsizeiptr(ubo0Size_));
  else
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, GLuint(ubo0_));
  glBindBuffer(GL_UNIFORM_BUFFER, GLuint(uboGeneric_));
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, GLuint(texture1_));
  glBindSampler(1, GLuint(sampler1_));
  glActiveTexture(GLenum(activeTexture_));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(packBuffer_));
  for (int i = 0; i < 6; ++i) glPixelStorei(kPack[i], pack_[i]);
  glPixelStorei(GL_PACK_SWAP_BYTES, packSwap_);
  glPixelStorei(GL_PACK_LSB_FIRST, packLsb_);
}

}  // namespace sao::prepass::detail
