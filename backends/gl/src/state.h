// Saving and restoring the caller's GL state around everything the effect does.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "gl_functions.h"

namespace sao::SAO_GL_NS::detail {

// Saves, on construction, the state render() may change and restores it on destruction:
// the current program, the active texture unit, GL_TEXTURE_BINDING_2D, _2D_MULTISAMPLE (a
// multisampled depth input) and the sampler binding of each listed texture unit, _2D_ARRAY and
// _2D_MULTISAMPLE_ARRAY of `inspectUnit` only (the one unit an array texture is bound on, to be
// inspected for Inputs::layer), every field of each listed image unit, and the uniform-buffer bindings
// (generic and index 0, with its range).
class StateGuard {
 public:
  // Units it can save: fixed storage, so that render() allocates nothing (create() checks the
  // effect's units fit).
  static constexpr std::size_t kMaxUnits = 32;
  StateGuard(const GlFunctions& gl, const std::vector<GLuint>& textureUnits, const std::vector<GLuint>& imageUnits,
             GLuint inspectUnit);
  ~StateGuard();
  StateGuard(const StateGuard&) = delete;
  StateGuard& operator=(const StateGuard&) = delete;

 private:
  struct TextureUnit {
    GLuint unit;
    GLint texture2D, texture2DMultisample, sampler;
  };
  struct ImageUnit {
    GLuint unit;
    GLint name, level, layered, layer, access, format;
  };
  const GlFunctions& gl_;
  GLint program_ = 0, activeTexture_ = GL_TEXTURE0;
  GLuint inspectUnit_ = 0;
  GLint inspectArray_ = 0, inspectMultisampleArray_ = 0;  // inspectUnit's array bindings
  GLint uniformBuffer_ = 0, uniformBuffer0_ = 0;
  GLint64 uniformStart0_ = 0, uniformSize0_ = 0;
  std::array<TextureUnit, kMaxUnits> textures_{};
  std::array<ImageUnit, kMaxUnits> images_{};
  std::size_t textureCount_ = 0, imageCount_ = 0;
};

// Saves the texture parameters the effect sets on a caller's GL_TEXTURE_2D (base level, the
// depth-stencil texture mode of combined formats, the red swizzle) and puts them back. The
// texture is bound on `unit` for that, whose binding a StateGuard must cover.
class TextureParamGuard {
 public:
  TextureParamGuard() = default;
  ~TextureParamGuard() { restore(); }
  TextureParamGuard(const TextureParamGuard&) = delete;
  TextureParamGuard& operator=(const TextureParamGuard&) = delete;

  // Sets base level 0, and for depth inputs swizzle R = GL_RED and, when the texture has a stencil
  // part, GL_DEPTH_STENCIL_TEXTURE_MODE = GL_DEPTH_COMPONENT. Only values that differ are written.
  // `target`: GL_TEXTURE_2D, or GL_TEXTURE_2D_MULTISAMPLE for a multisampled depth input (whose
  // base level is always 0; swizzle and depth-stencil mode are texture state there too).
  void apply(const GlFunctions& gl, GLuint unit, GLuint texture, GLenum target, bool depthInput, bool hasStencil);
  void restore();

 private:
  struct Param {
    GLenum pname;
    GLint saved;
  };
  const GlFunctions* gl_ = nullptr;
  GLuint unit_ = 0, texture_ = 0;
  GLenum target_ = GL_TEXTURE_2D;
  std::array<Param, 3> changed_{};  // at most the three parameters apply() sets
  std::size_t changedCount_ = 0;
};

}  // namespace sao::SAO_GL_NS::detail
