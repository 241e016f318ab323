#include "gl_support.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "sao/io.h"

namespace sao::gltest {

gl::HeadlessContext& context() {
  static std::unique_ptr<gl::HeadlessContext> ctx = [] {
    std::unique_ptr<gl::HeadlessContext> c;
    const Status st = gl::HeadlessContext::create(c);
    if (!st) {
      std::fprintf(stderr, "no headless GL context: %s\n", st.message.c_str());
      std::abort();
    }
    std::printf("GL context: %s\n", c->description().c_str());
    return c;
  }();
  return *ctx;
}

void GlTest::SetUp() { context().clearMessages(); }

void GlTest::TearDown() {
  for (const auto& m : context().errors()) ADD_FAILURE() << "GL debug message: " << gl::HeadlessContext::format(m);
  context().clearMessages();
}

std::unique_ptr<gl::Effect> GlTest::makeEffect() {
  std::unique_ptr<gl::Effect> e;
  const Status st = gl::Effect::create(gl::HeadlessContext::getProcAddress(), e);
  EXPECT_TRUE(st.ok()) << st.message;
  return e;
}

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

// Test helpers read and write tightly packed client memory whatever a test left in the
// pixel-store state (the state test sets odd values on purpose).
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

std::uint32_t uploadDepth(const DepthImage& depth, GlDepth format) {
  const Extent e = depth.extent;
  const std::size_t n = std::size_t(e.width) * e.height;
  EXPECT_EQ(depth.format, cpuFormat(format));
  EXPECT_EQ(depth.texels.size(), n);
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
    glGetTextureImage(t, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(back.size() * sizeof(back[0])), back.data());
    for (std::size_t i = 0; i < n; ++i) mismatches += back[i] != depth.texels[i];
  }
  EXPECT_EQ(mismatches, 0u) << "the " << toString(format) << " texture does not hold the uploaded texels";
  return t;
}

std::uint32_t uploadNormals(const FloatImage& normals) {
  EXPECT_EQ(normals.channels, 4u);
  const GLuint t = makeTexture(GL_RGBA16F, normals.extent);
  tightPixelStore();
  glTextureSubImage2D(t, 0, 0, 0, GLsizei(normals.extent.width), GLsizei(normals.extent.height), GL_RGBA, GL_FLOAT,
                      normals.data.data());
  return t;
}

FloatImage readTextureLevel(std::uint32_t texture, std::uint32_t level) {
  GLint w = 0, h = 0;
  glGetTextureLevelParameteriv(texture, GLint(level), GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(texture, GLint(level), GL_TEXTURE_HEIGHT, &h);
  FloatImage img({std::uint32_t(w), std::uint32_t(h)}, 1);
  tightPixelStore();
  glGetTextureImage(texture, GLint(level), GL_RED, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
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

Camera camera(std::uint32_t width, std::uint32_t height, std::uint32_t guard, double farDistance, bool reversedZ) {
  Camera c = perspectiveCamera(std::numbers::pi / 3.0, width, height, 0.1, farDistance, ClipDepth::NegativeOneToOne,
                               reversedZ);
  c.guardBand = guard;
  return c;
}

std::string failureDir() { return SAO_GL_TEST_FAILURE_DIR; }

bool acceptable(const Agreement& a) { return a.fractionWithin >= 0.999 && a.beyond == 0 && a.nonFinite == 0; }

Agreement compare(const FloatImage& actual, const FloatImage& expected, std::uint32_t channel, double within,
                  double never, const std::string& name, std::string* note) {
  Agreement a;
  if (actual.extent != expected.extent || channel >= actual.channels || channel >= expected.channels) {
    ADD_FAILURE() << name << ": images differ in size or channels";
    a.beyond = 1;
    return a;
  }
  const Extent e = actual.extent;
  const std::size_t n = std::size_t(e.width) * e.height;
  std::vector<double> diffs(n);
  FloatImage a1(e, 1), b1(e, 1), d1(e, 1);
  std::size_t ok = 0;
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      const float u = actual.at(x, y, channel), v = expected.at(x, y, channel);
      const double d = std::isfinite(u) ? std::fabs(double(u) - double(v)) : INFINITY;
      if (!std::isfinite(u)) ++a.nonFinite;
      diffs[std::size_t(y) * e.width + x] = d;
      a.maxAbs = std::max(a.maxAbs, d);
      ok += d <= within;
      a.beyond += d > never;
      a1.at(x, y) = std::isfinite(u) ? u : 0.0f;
      b1.at(x, y) = v;
      d1.at(x, y) = float(std::min(1.0, d / never));
    }
  a.fractionWithin = double(ok) / double(n);
  std::vector<double> sorted = diffs;
  const std::size_t k = std::min(n - 1, std::size_t(std::ceil(0.999 * double(n))) - 1);
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
  a.p999 = sorted[k];
  if (!acceptable(a)) {
    std::error_code ec;
    std::filesystem::create_directories(failureDir(), ec);
    const std::string base = failureDir() + "/" + name;
    (void)writeAoPng(base + "_actual.png", a1);
    (void)writeAoPng(base + "_expected.png", b1);
    (void)writeAoPng(base + "_diff.png", d1);
    (void)writeFloatExr(base + "_actual.exr", a1, {"A"});
    (void)writeFloatExr(base + "_expected.exr", b1, {"A"});
    if (note) {
      char white[32];
      std::snprintf(white, sizeof white, "%.3g/255", never * 255.0);
      *note = "images written to " + base + "_{actual,expected,diff}.png and _{actual,expected}.exr (diff: white = " +
              white + ")";
    }
  }
  return a;
}

}  // namespace sao::gltest
