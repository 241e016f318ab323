#include "gl_composite.h"

#include "gl_util.h"
#include "viewer_glsl.h"

namespace sao::viewer {
namespace {
constexpr GLuint kTextures = 6;  // units 1..6: depth, ao, ao_raw, csz, reference, reduced-resolution AO
}

GlComposite::~GlComposite() {
  glDeleteProgram(program_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteBuffers(1, &ubo_);
  glDeleteSamplers(1, &nearest_);
  glDeleteSamplers(1, &nearestMip_);
  glDeleteTextures(1, &white_);
  glDeleteTextures(1, &reference_);
}

Status GlComposite::init() {
  if (Status s = linkProgram(glsl::kFullscreenVert, glsl::kCompositeFrag, "composite", program_); !s) return s;
  glGenVertexArrays(1, &vao_);  // core profile: drawing needs a VAO, even without attributes
  glGenBuffers(1, &ubo_);
  glBindBuffer(GL_UNIFORM_BUFFER, ubo_);
  glBufferData(GL_UNIFORM_BUFFER, sizeof(CompositeParams), nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  // Sampler objects override whatever filters the effect left on its textures (texelFetch only
  // needs the textures complete: csz is read at several levels).
  glGenSamplers(1, &nearest_);
  glSamplerParameteri(nearest_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(nearest_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glGenSamplers(1, &nearestMip_);
  glSamplerParameteri(nearestMip_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  glSamplerParameteri(nearestMip_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  const float one = 1.0f;
  glGenTextures(1, &white_);
  glBindTexture(GL_TEXTURE_2D, white_);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_R32F, 1, 1);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 1, 1, GL_RED, GL_FLOAT, &one);
  glBindTexture(GL_TEXTURE_2D, 0);
  return Status::success();
}

void GlComposite::setReference(const FloatImage* reference) {
  glDeleteTextures(1, &reference_);
  reference_ = 0;
  if (!reference) return;
  glGenTextures(1, &reference_);
  glBindTexture(GL_TEXTURE_2D, reference_);
  glTexStorage2D(GL_TEXTURE_2D, 1, GL_R32F, GLsizei(reference->extent.width), GLsizei(reference->extent.height));
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, GLsizei(reference->extent.width), GLsizei(reference->extent.height), GL_RED,
                  GL_FLOAT, reference->data.data());
  glBindTexture(GL_TEXTURE_2D, 0);
}

void GlComposite::draw(const CompositeParams& params, const GlCompositeInputs& in, int width, int height) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glBindBuffer(GL_UNIFORM_BUFFER, ubo_);
  glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof params, &params);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo_);
  const GLuint textures[kTextures] = {in.depth,
                                      in.ao ? in.ao : white_,
                                      in.aoRaw ? in.aoRaw : white_,
                                      in.csz ? in.csz : white_,
                                      reference_ ? reference_ : white_,
                                      in.aoReduced ? in.aoReduced : white_};
  for (GLuint unit = 0; unit < kTextures; ++unit) {
    glActiveTexture(GL_TEXTURE1 + unit);
    glBindTexture(GL_TEXTURE_2D, textures[unit]);
    glBindSampler(1 + unit, unit == 3 ? nearestMip_ : nearest_);
  }
  glActiveTexture(GL_TEXTURE0);
  glUseProgram(program_);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  // Leave no texture bound: the effect reallocates its textures on resize, and a binding kept
  // on a texture it deletes is what it would restore afterwards.
  for (GLuint unit = 1; unit <= kTextures; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindSampler(unit, 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace sao::viewer
