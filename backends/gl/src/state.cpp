#include "state.h"

namespace sao::SAO_GL_NS::detail {

StateGuard::StateGuard(const GlFunctions& gl, const std::vector<GLuint>& textureUnits,
                       const std::vector<GLuint>& imageUnits, GLuint inspectUnit)
    : gl_(gl), inspectUnit_(inspectUnit) {
  gl.GetIntegerv(GL_CURRENT_PROGRAM, &program_);
  gl.GetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
  gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniformBuffer_);
  gl.GetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &uniformBuffer0_);
  gl.GetInteger64i_v(GL_UNIFORM_BUFFER_START, 0, &uniformStart0_);
  gl.GetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, 0, &uniformSize0_);
  for (GLuint u : textureUnits) {
    if (textureCount_ == kMaxUnits) break;
    TextureUnit t{u, 0, 0, 0};
    gl.ActiveTexture(GL_TEXTURE0 + u);
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &t.texture2D);
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE, &t.texture2DMultisample);
    gl.GetIntegerv(GL_SAMPLER_BINDING, &t.sampler);
    if (u == inspectUnit) {
      gl.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &inspectArray_);
      if (!kEs || gl.atLeast(3, 2))  // ES 3.1 has no multisample array textures
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY, &inspectMultisampleArray_);
    }
    textures_[textureCount_++] = t;
  }
  for (GLuint u : imageUnits) {
    if (imageCount_ == kMaxUnits) break;
    ImageUnit i{u, 0, 0, 0, 0, GL_READ_ONLY, GL_R8};
    gl.GetIntegeri_v(GL_IMAGE_BINDING_NAME, u, &i.name);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_LEVEL, u, &i.level);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYERED, u, &i.layered);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYER, u, &i.layer);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_ACCESS, u, &i.access);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_FORMAT, u, &i.format);
    images_[imageCount_++] = i;
  }
}

StateGuard::~StateGuard() {
  const GlFunctions& gl = gl_;
  // A saved texture the effect deleted meanwhile (its own output, reallocated by a resize, which the
  // caller had left bound) is restored as 0: what GL itself leaves on a unit whose texture is
  // deleted, where binding the dead name again would be GL_INVALID_OPERATION / _VALUE.
  auto alive = [&gl](GLint name) { return name != 0 && gl.IsTexture(GLuint(name)) ? GLuint(name) : 0u; };
  for (std::size_t k = 0; k < imageCount_; ++k) {
    const ImageUnit& i = images_[k];
    gl.BindImageTexture(i.unit, alive(i.name), i.level, i.layered ? GL_TRUE : GL_FALSE, i.layer, GLenum(i.access),
                        GLenum(i.format));
  }
  for (std::size_t k = 0; k < textureCount_; ++k) {
    const TextureUnit& t = textures_[k];
    gl.ActiveTexture(GL_TEXTURE0 + t.unit);
    gl.BindTexture(GL_TEXTURE_2D, alive(t.texture2D));
    gl.BindTexture(GL_TEXTURE_2D_MULTISAMPLE, alive(t.texture2DMultisample));
    if (t.unit == inspectUnit_) {
      gl.BindTexture(GL_TEXTURE_2D_ARRAY, alive(inspectArray_));
      if (!kEs || gl_.atLeast(3, 2)) gl.BindTexture(GL_TEXTURE_2D_MULTISAMPLE_ARRAY, alive(inspectMultisampleArray_));
    }
    gl.BindSampler(t.unit, GLuint(t.sampler));
  }
  gl.ActiveTexture(GLenum(activeTexture_));
  // Indexed binds also set the generic binding point, so the generic one goes last.
  if (uniformBuffer0_ != 0 && (uniformStart0_ != 0 || uniformSize0_ != 0))
    gl.BindBufferRange(GL_UNIFORM_BUFFER, 0, GLuint(uniformBuffer0_), GLintptr(uniformStart0_),
                       GLsizeiptr(uniformSize0_));
  else
    gl.BindBufferBase(GL_UNIFORM_BUFFER, 0, GLuint(uniformBuffer0_));
  gl.BindBuffer(GL_UNIFORM_BUFFER, GLuint(uniformBuffer_));
  gl.UseProgram(GLuint(program_));
}

void TextureParamGuard::apply(const GlFunctions& gl, GLuint unit, GLuint texture, GLenum target, bool depthInput,
                              bool hasStencil) {
  restore();
  gl_ = &gl;
  unit_ = unit;
  texture_ = texture;
  target_ = target;
  gl.ActiveTexture(GL_TEXTURE0 + unit);
  gl.BindTexture(target, texture);
  auto set = [&](GLenum pname, GLint wanted) {
    GLint current = 0;
    gl.GetTexParameteriv(target, pname, &current);
    if (current == wanted) return;
    changed_[changedCount_++] = {pname, current};
    gl.TexParameteri(target, pname, wanted);
  };
  // texelFetch's lod is relative to the base level: read level 0 whatever the caller set.
  set(GL_TEXTURE_BASE_LEVEL, 0);
  if (depthInput) {
    set(GL_TEXTURE_SWIZZLE_R, GL_RED);
    if (hasStencil) set(GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
  }
}

void TextureParamGuard::restore() {
  if (!gl_ || changedCount_ == 0) {
    changedCount_ = 0;
    return;
  }
  const GlFunctions& gl = *gl_;
  gl.ActiveTexture(GL_TEXTURE0 + unit_);
  gl.BindTexture(target_, texture_);
  while (changedCount_ > 0) {
    const Param& p = changed_[--changedCount_];
    gl.TexParameteri(target_, p.pname, p.saved);
  }
}

}  // namespace sao::SAO_GL_NS::detail
