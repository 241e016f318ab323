// Checking the caller's textures: the real internal format and size are queried from the GL
// (glGetTexLevelParameteriv on level 0), never taken on trust.
#pragma once
#include "gl_functions.h"
#include "sao/output.h"
#include "sao/schedule.h"

namespace sao::gl::detail {

struct TextureInfo {
  GLuint texture = 0;
  GLenum internalFormat = 0;
  bool hasStencil = false;
  Extent extent;  // level 0
  GLenum target = GL_TEXTURE_2D;  // GL_TEXTURE_2D_MULTISAMPLE only for a multisampled depth input
  std::uint32_t samples = 1;
};

struct CheckedInputs {
  TextureInfo depth, depth2, normals, output;  // texture 0 where absent
  std::optional<Offset> region;  // Inputs::region: where the region starts in depth, depth2 and normals
  PlanInputs planInputs;
  std::uint32_t outputChannels = 15;  // Inputs::outputChannels, checked against the output's format
  OutputBlend outputBlend = OutputBlend::Replace;  // Inputs::outputBlend, checked (multiply needs Inputs::output)
};

// Inspects every texture in `inputs` (binding each on `scratchUnit`, whose binding the caller
// saves) and derives the plan inputs. InvalidInput / UnsupportedFormat naming the texture's role;
// the normals texture's channels are checked against the camera's `normalsEncoding`.
Status checkInputs(const GlFunctions& gl, GLuint scratchUnit, const Inputs& inputs, NormalsEncoding normalsEncoding,
                   CheckedInputs& out);

// The textures as sao::checkSupplied sees them (sizes against the plan are checked there).
SuppliedImages supplied(const CheckedInputs& in);

}  // namespace sao::gl::detail
