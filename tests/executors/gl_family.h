// What the GL and GLES halves of the harness share (one OpenGL API, two contexts): the colour
// inputs' GL formats, their texels as the host uploads them, and the effect's Inputs of a frame
// (sao::gl::Inputs and sao::gles::Inputs have the same fields).
#pragma once
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "harness.h"
#include "sao/cpu/reference.h"

namespace sao::exectest {

inline GLenum texelsFormat(Texels t) {
  switch (t) {
    case Texels::RGBA16F: return GL_RGBA16F;
    case Texels::RGBA32F: return GL_RGBA32F;
    case Texels::RG16F: return GL_RG16F;
    case Texels::RG32F: return GL_RG32F;
  }
  return GL_RGBA16F;
}

// `image`'s texels for a texture of `internal`: 16-bit floats rounded to nearest-even and 8-bit
// unorm to the nearest byte on the host (as the Vulkan half uploads them), else the floats.
struct HostTexels {
  GLenum layout = GL_RGBA, type = GL_FLOAT;
  std::vector<std::uint16_t> halves;
  std::vector<std::uint8_t> bytes;
  const float* floats = nullptr;  // the image's own, for GL_FLOAT
  const void* data() const {
    return type == GL_HALF_FLOAT ? static_cast<const void*>(halves.data())
           : type == GL_UNSIGNED_BYTE ? static_cast<const void*>(bytes.data()) : floats;
  }
};
inline HostTexels hostTexels(const FloatImage& image, GLenum internal) {
  HostTexels t;
  t.layout = image.channels == 1 ? GL_RED : image.channels == 2 ? GL_RG : GL_RGBA;
  if (internal == GL_R16F || internal == GL_RG16F || internal == GL_RGBA16F) {
    t.halves.resize(image.data.size());
    std::transform(image.data.begin(), image.data.end(), t.halves.begin(), [](float v) { return cpu::halfBits(v); });
    t.type = GL_HALF_FLOAT;
  } else if (internal == GL_R8 || internal == GL_RGBA8) {
    t.bytes.resize(image.data.size());
    std::transform(image.data.begin(), image.data.end(), t.bytes.begin(),
                   [](float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); });
    t.type = GL_UNSIGNED_BYTE;
  } else {
    t.floats = image.data.data();
  }
  return t;
}

// The effect's inputs for frame `f` from the textures uploaded for it (Inputs::layer is GL's alone).
template <class Inputs>
Inputs frameInputs(const Frame& f, std::uint32_t depthFormat, GLuint depth, GLuint depth2, GLuint normals,
                   GLuint motion, GLuint output) {
  Inputs in;
  in.depth = {depth, depthFormat};
  in.depth2 = {depth2, depth2 ? depthFormat : 0};
  in.normals = normals;
  in.motion = motion;
  in.region = f.region;
  in.output = output;
  in.outputChannels = f.output.channels;
  in.outputBlend = f.output.blend;
  in.frameIndex = f.frameIndex;
  in.resetHistory = f.resetHistory;
  in.previousCamera = f.previousCamera;
  return in;
}

}  // namespace sao::exectest
