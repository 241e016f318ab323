// Writes every sample of a multisampled GL_DEPTH_COMPONENT32F texture (or one layer of a
// multisampled array) from values laid out like sao::DepthImage::texels with 4 samples per texel
// (tests/cpu/msaa_depth.h): a full-screen triangle whose fragment shader, run per sample
// (gl_SampleID), writes gl_FragDepth. Exact: every value lies in [0, 1].
#pragma once
#include <epoxy/gl.h>

#include <vector>

#include "sao/plan.h"

namespace sao::gltest {

inline constexpr GLsizei kWriterSamples = 4;

// A new 4-sample D32F GL_TEXTURE_2D_MULTISAMPLE of extent `e` holding `values`.
GLuint writeSamples(Extent e, const std::vector<float>& values);
// The same into `tex` (4 samples, extent `e`): the whole texture (layer < 0) or one layer of a
// GL_TEXTURE_2D_MULTISAMPLE_ARRAY.
void writeSamplesInto(GLuint tex, GLint layer, Extent e, const std::vector<float>& values);

}  // namespace sao::gltest
