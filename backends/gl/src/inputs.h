// Checking the caller's textures: the real internal format and size are queried from the GL
// (glGetTexLevelParameteriv on level 0), never taken on trust.
#pragma once
#include <array>

#include "gl_functions.h"
#include "sao/output.h"
#include "sao/schedule.h"

namespace sao::SAO_GL_NS::detail {

struct TextureInfo {
  GLuint texture = 0;
  GLenum internalFormat = 0;
  bool hasStencil = false;
  Extent extent;  // level 0
  GLenum target = GL_TEXTURE_2D;  // GL_TEXTURE_2D_MULTISAMPLE only for a multisampled depth input
  std::uint32_t samples = 1;
};

// Texture views of one layer of the caller's array textures (Inputs::layer), made by checkInputs
// for this render only and deleted with the CheckedInputs (after the dispatches are issued; the GL
// keeps a view's storage alive while commands still use it).
class LayerViews {
 public:
  explicit LayerViews(const GlFunctions& gl) : gl_(gl) {}
  ~LayerViews() {
    if (count_) gl_.DeleteTextures(GLsizei(count_), views_.data());
  }
  LayerViews(const LayerViews&) = delete;
  LayerViews& operator=(const LayerViews&) = delete;
  // A GL_TEXTURE_2D (or _2D_MULTISAMPLE) view of level 0, layer `layer` of `texture`; 0 when the
  // GL made none (the caller reports it).
  GLuint make(GLuint texture, GLenum viewTarget, GLenum internalFormat, GLuint layer);

 private:
  const GlFunctions& gl_;
  std::array<GLuint, gen::kInputIds.size() + 1> views_{};  // at most one per input and the output
  std::size_t count_ = 0;
};

struct CheckedInputs {
  explicit CheckedInputs(const GlFunctions& gl) : views(gl) {}
  LayerViews views;                            // per-render views of array layers (Inputs::layer)
  gen::InputSet<TextureInfo> inputs;  // texture 0 where absent; a layer's view for an array
  TextureInfo output;
  std::optional<Offset> region{};  // Inputs::region: where the region starts in every input
  PlanInputs planInputs;
};

// Inspects every texture in `inputs` (binding each on `scratchUnit`, whose binding the caller
// saves) and derives the plan inputs; an array texture is replaced by a view of Inputs::layer.
// `out` must be freshly constructed. InvalidInput / UnsupportedFormat naming the texture's role;
// each input's format against the effect's contract (sao/inputs.h; the normals' channels against
// the camera's encoding).
Status checkInputs(const GlFunctions& gl, GLuint scratchUnit, const Inputs& inputs, const Camera& camera,
                   CheckedInputs& out);

// The textures as sao::checkSupplied sees them (sizes against the plan are checked there).
SuppliedImages supplied(const CheckedInputs& in);

}  // namespace sao::SAO_GL_NS::detail
