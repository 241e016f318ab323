// Moving images between the CPU and GL textures, for tests and tools (not part of the effect):
// upload the user-side depth representations exactly, read results back as floats. Needs a
// current context (HeadlessContext or the caller's) and GL 4.5 direct state access.
#pragma once
#include <cstdint>

#include "sao/image.h"
#include "sao/status.h"

namespace sao::gl {

// The GL depth representations a caller may hand the effect.
enum class GlDepth { D16, D24, D32F, D24S8, D32FS8, R32F };
const char* toString(GlDepth format);
std::uint32_t internalFormat(GlDepth format);
DepthFormat cpuFormat(GlDepth format);  // the DepthImage format holding the same texels

// A new GL_TEXTURE_2D with immutable storage holding `depth` exactly; verified by reading it back
// (InvalidInput when the texels differ, e.g. a driver's integer conversion is off by one). GL
// clamps D32F / D32FS8 depth to [0, 1]: an image with NaN, +-Inf or values outside [0, 1] is
// refused up front with checkDepthValues' message (sao/image.h), and -0.0 is held as +0.0 (the
// same depth). R32F holds every float bit pattern, NaN payloads and -0.0 included.
Status uploadDepth(const DepthImage& depth, GlDepth format, std::uint32_t& texture);
// GL_RGBA16F from a 4-channel image, uploaded as nearest-even half bits (sao::halfBits).
Status uploadNormals(const FloatImage& normals, std::uint32_t& texture);
std::uint32_t makeTexture(std::uint32_t internalFormat, Extent extent);
void deleteTexture(std::uint32_t texture);
// Level 0, or level `level`, as floats (1, 2 or 4 channels).
FloatImage readTexture(std::uint32_t texture, std::uint32_t channels);
FloatImage readTextureLevel(std::uint32_t texture, std::uint32_t level, std::uint32_t channels = 1);

}  // namespace sao::gl
