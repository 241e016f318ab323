#include "sao/gl/texture_io.h"

#include <epoxy/gl.h>

#include <string>
#include <vector>

namespace sao::gl {

const char* toString(GlDepth f) {
  switch (f) {
    case GlDepth::D16: return "D16";
    case GlDepth::D24: return "D24";
    case GlDepth::D32F: return "D32F";
    case GlDepth::D24S8: return "D24S8";
    case GlDepth::D32FS8: return "D32FS8";
    case GlDepth::R32F: return "R32F";
  }
  return "?";
}

std::uint32_t internalFormat(GlDepth f) {
  switch (f) {
    case GlDepth::D16: return GL_DEPTH_COMPONENT16;
    case GlDepth::D24: return GL_DEPTH_COMPONENT24;
    case GlDepth::D32F: return GL_DEPTH_COMPONENT32F;
    case GlDepth::D24S8: return GL_DEPTH24_STENCIL8;
    case GlDepth::D32FS8: return GL_DEPTH32F_STENCIL8;
    case GlDepth::R32F: return GL_R32F;
  }
  return 0;
}

DepthFormat cpuFormat(GlDepth f) {
  switch (f) {
    case GlDepth::D16: return DepthFormat::D16;
    case GlDepth::D24:
    case GlDepth::D24S8: return DepthFormat::D24;
    case GlDepth::D32F:
    case GlDepth::D32FS8: return DepthFormat::D32F;
    case GlDepth::R32F: return DepthFormat::LinearZ;
  }
  return DepthFormat::D32F;
}

// These helpers read and write tightly packed client memory whatever a test left in the
// pixel-store state (the state test sets odd values on purpose).
namespace {
void tightPixelStore() {
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  for (GLenum p : {GL_PACK_ROW_LENGTH, GL_PACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS, GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_IMAGES,
                   GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_IMAGE_HEIGHT,
                   GL_UNPACK_SKIP_IMAGES})
    glPixelStorei(p, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
}
}  // namespace

// DSA throughout: creating or reading a texture leaves every binding alone.
std::uint32_t makeTexture(std::uint32_t format, Extent e) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, GLsizei(e.width), GLsizei(e.height));
  return t;
}

void deleteTexture(std::uint32_t texture) {
  GLuint t = texture;
  if (t) glDeleteTextures(1, &t);
}

Status uploadDepth(const DepthImage& depth, GlDepth format, std::uint32_t& texture) {
  const Extent e = depth.extent;
  const std::size_t n = std::size_t(e.width) * e.height;
  if (depth.format != cpuFormat(format))
    return Status::error(StatusCode::InvalidInput, std::string("a ") + sao::toString(depth.format) +
                                                       " image cannot be uploaded as " + toString(format));
  if (depth.texels.size() != n || n == 0)
    return Status::error(StatusCode::InvalidInput, "depth image texel count does not match its extent");
  // GL clamps depth to [0, 1] on upload (NaN and -inf to 0, +inf to 1): a texture of such texels
  // would hold other values than the CPU reference reads, which are sky by the contract.
  const bool floatDepth = format == GlDepth::D32F || format == GlDepth::D32FS8;
  if (floatDepth)
    if (Status st = checkDepthValues(depth); !st)
      return Status::error(st.code, std::string("a GL ") + toString(format) +
                                        " texture clamps depth to [0, 1], so it cannot hold this image: " + st.message);
  const GLuint t = makeTexture(internalFormat(format), e);
  tightPixelStore();
  std::vector<std::uint16_t> u16;
  std::vector<std::uint32_t> u32;
  const auto w = GLsizei(e.width), h = GLsizei(e.height);
  switch (format) {
    case GlDepth::D16:
      for (auto v : depth.texels) u16.push_back(std::uint16_t(v));
      glTextureSubImage2D(t, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, u16.data());
      break;
    case GlDepth::D24: {
      // As float(t / (2^24 - 1)): Mesa stores exactly t for every 24-bit t that way (checked for
      // all 2^24 values), while its GL_UNSIGNED_INT path (t * 2^8 + t / 2^16) is off by one for
      // 65535 of them. The readback below verifies it for the texels at hand.
      std::vector<float> f;
      for (auto v : depth.texels) f.push_back(float(double(v) / 16777215.0));
      glTextureSubImage2D(t, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, f.data());
      break;
    }
    case GlDepth::D24S8:
      for (auto v : depth.texels) u32.push_back((v << 8) | 0x5Au);
      glTextureSubImage2D(t, 0, 0, 0, w, h, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, u32.data());
      break;
    case GlDepth::D32F:
      glTextureSubImage2D(t, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.texels.data());
      break;
    case GlDepth::D32FS8:
      for (auto v : depth.texels) {
        u32.push_back(v);
        u32.push_back(0x5Au);
      }
      glTextureSubImage2D(t, 0, 0, 0, w, h, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, u32.data());
      break;
    case GlDepth::R32F:
      glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RED, GL_FLOAT, depth.texels.data());
      break;
  }
  // Check that the texture holds exactly the texels the CPU reference reads.
  std::vector<std::uint32_t> back(n * 2, 0);
  std::size_t mismatches = 0;
  if (format == GlDepth::D16) {
    std::vector<std::uint16_t> b(n);
    glGetTextureImage(t, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, GLsizei(b.size() * sizeof(b[0])), b.data());
    for (std::size_t i = 0; i < n; ++i) mismatches += b[i] != depth.texels[i];
  } else if (format == GlDepth::D24) {
    glGetTextureImage(t, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, GLsizei(back.size() * sizeof(back[0])), back.data());
    for (std::size_t i = 0; i < n; ++i) mismatches += (back[i] >> 8) != depth.texels[i];
  } else if (format == GlDepth::D24S8) {
    glGetTextureImage(t, 0, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, GLsizei(back.size() * sizeof(back[0])), back.data());
    for (std::size_t i = 0; i < n; ++i) mismatches += (back[i] >> 8) != depth.texels[i];
  } else if (format == GlDepth::R32F) {
    glGetTextureImage(t, 0, GL_RED, GL_FLOAT, GLsizei(back.size() * sizeof(back[0])), back.data());
    for (std::size_t i = 0; i < n; ++i) mismatches += back[i] != depth.texels[i];
  } else {
    // GL stores -0.0 as +0.0: the same depth, and the same csz by the contract (sao/image.h).
    glGetTextureImage(t, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(back.size() * sizeof(back[0])), back.data());
    for (std::size_t i = 0; i < n; ++i)
      mismatches += back[i] != (depth.texels[i] == 0x80000000u ? 0u : depth.texels[i]);
  }
  if (mismatches) {
    deleteTexture(t);
    return Status::error(StatusCode::InvalidInput, std::to_string(mismatches) + " texels of the " + toString(format) +
                                                       " texture differ from the uploaded ones");
  }
  texture = t;
  return Status::success();
}

Status uploadNormals(const FloatImage& normals, std::uint32_t& texture) {
  if (normals.channels != 4 || normals.data.empty())
    return Status::error(StatusCode::InvalidInput, "normals must be a non-empty 4-channel image");
  std::vector<std::uint16_t> half(normals.data.size());
  for (std::size_t i = 0; i < half.size(); ++i) half[i] = halfBits(normals.data[i]);
  const GLuint t = makeTexture(GL_RGBA16F, normals.extent);
  tightPixelStore();
  glTextureSubImage2D(t, 0, 0, 0, GLsizei(normals.extent.width), GLsizei(normals.extent.height), GL_RGBA,
                      GL_HALF_FLOAT, half.data());
  texture = t;
  return Status::success();
}

FloatImage readTextureLevel(std::uint32_t texture, std::uint32_t level, std::uint32_t channels) {
  GLint w = 0, h = 0;
  glGetTextureLevelParameteriv(texture, GLint(level), GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(texture, GLint(level), GL_TEXTURE_HEIGHT, &h);
  FloatImage img({std::uint32_t(w), std::uint32_t(h)}, channels);
  const GLenum f = channels == 1 ? GL_RED : channels == 2 ? GL_RG : GL_RGBA;
  tightPixelStore();
  glGetTextureImage(texture, GLint(level), f, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
  return img;
}

FloatImage readTexture(std::uint32_t texture, std::uint32_t channels) {
  GLint w = 0, h = 0;
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &h);
  FloatImage img({std::uint32_t(w), std::uint32_t(h)}, channels);
  const GLenum f = channels == 1 ? GL_RED : channels == 2 ? GL_RG : GL_RGBA;
  tightPixelStore();
  glGetTextureImage(texture, 0, f, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
  return img;
}

}  // namespace sao::gl
