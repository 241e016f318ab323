// The harness's fourth executor: sao::gles::Effect::render() (the OpenGL backend's sources built for
// OpenGL ES 3.1) on a headless ES 3.1 debug context of its own. ES has neither direct state access
// nor glGetTexImage: textures are made and filled through the 2D binding, and read back by a compute
// shader that texelFetch()es one level into a buffer. The caller's output is stored in its format's
// ES form (gen::glesStorageFormat: R16F as GL_R32F; an R8 output stays GL_R8, which sao::gles
// refuses). What sao::gles refuses (harness.h Feature: a multisampled depth, stereo layers) is
// refused here, naming it.
#include <epoxy/gl.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gl_family.h"
#include "harness_apis.h"
#include "sao/cpu/reference.h"
#include "sao/gl/headless.h"
#include "sao/gl/program_build.h"
#include "sao/gles/effect.h"

namespace sao::exectest {
namespace {

// The ES context of every GLES executor (created on first use), not the GL executor's.
gl::HeadlessContext& context() {
  static std::unique_ptr<gl::HeadlessContext> ctx = [] {
    gl::HeadlessOptions options;
    options.es = true;
    options.major = 3;
    options.minor = 1;
    std::unique_ptr<gl::HeadlessContext> c;
    if (const Status st = gl::HeadlessContext::create(c, options); !st) {
      std::fprintf(stderr, "no headless OpenGL ES 3.1 context: %s\n", st.message.c_str());
      std::abort();
    }
    std::printf("GLES context: %s\n", c->description().c_str());
    return c;
  }();
  return *ctx;
}

// Every call that touches GL makes the ES context current first: a program's GL executor, or the
// fixture of a GL test, may have left its own context current.
void makeCurrent() {
  const Status st = context().makeCurrent();
  if (!st) ADD_FAILURE() << st.message;
}

// The feature of harness.h a frame needs that sao::gles lacks, if any.
std::optional<Feature> unsupported(const Frame& f) {
  if (!f.depthLayers.empty()) return Feature::Stereo;
  if (f.depth && f.depth->samples > 1) return Feature::MultisampledDepth;
  return std::nullopt;
}
Status checkSupported(const Frame& f) {
  if (const auto feature = unsupported(f))
    return Status::error(StatusCode::InvalidInput,
                         std::string("harness: sao::gles does not implement ") + describe(*feature));
  return Status::success();
}

// How a depth format goes up on ES (its table of format and type combinations).
struct DepthUpload {
  GLenum internal, layout, type;
};
DepthUpload depthUpload(Depth d) {
  switch (d) {
    case Depth::D16: return {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT};
    case Depth::D24: return {GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT};
    case Depth::D24S8: return {GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8};
    case Depth::D32F: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
    case Depth::D32FS8: return {GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV};
    case Depth::R32F: return {GL_R32F, GL_RED, GL_FLOAT};
  }
  return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
}


// A new immutable single-level GL_TEXTURE_2D, left bound to unit 0's 2D target for the upload.
GLuint makeTexture(GLenum internal, Extent e) {
  GLuint t = 0;
  glGenTextures(1, &t);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, t);
  glTexStorage2D(GL_TEXTURE_2D, 1, internal, GLsizei(e.width), GLsizei(e.height));
  return t;
}

void deleteTexture(GLuint& t) {
  if (t) glDeleteTextures(1, &t);
  t = 0;
}

// Level 0 of the bound texture from tightly packed texels.
void fill(Extent e, GLenum layout, GLenum type, const void* texels) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, GLsizei(e.width), GLsizei(e.height), layout, type, texels);
}

// The depth's texels as texture_io.cpp's uploadDepth converts them (stencil 0x5A beside the depth),
// but D24 as GL_UNSIGNED_INT, since ES takes no GL_FLOAT into GL_DEPTH_COMPONENT24: the 24-bit value
// t in the top bits and 0x80 below, the middle of the 2^8 values that stand for t, which a
// truncating conversion and a rounding one both store as t. Mesa truncates: t << 8 alone is stored
// as t - 1 for all but 2 of the 2^24 values, t << 8 | t >> 16 for 65535 of them; this for none
// (checked for all 2^24 against GL_UNSIGNED_INT_24_8, which packs t without converting).
void fillDepth(const DepthImage& d, Depth format) {
  const DepthUpload up = depthUpload(format);
  std::vector<std::uint32_t> u32;
  switch (format) {
    case Depth::D16: {
      std::vector<std::uint16_t> u16(d.texels.size());
      std::transform(d.texels.begin(), d.texels.end(), u16.begin(), [](std::uint32_t v) { return std::uint16_t(v); });
      return fill(d.extent, up.layout, up.type, u16.data());
    }
    case Depth::D24:
    case Depth::D24S8:
      for (std::uint32_t v : d.texels) u32.push_back(v << 8 | (format == Depth::D24S8 ? 0x5Au : 0x80u));
      return fill(d.extent, up.layout, up.type, u32.data());
    case Depth::D32FS8:
      for (std::uint32_t v : d.texels) u32.insert(u32.end(), {v, 0x5Au});
      return fill(d.extent, up.layout, up.type, u32.data());
    case Depth::D32F:
    case Depth::R32F: return fill(d.extent, up.layout, up.type, d.texels.data());
  }
}

// A texture of `internal` holding `image` (its channels), uploaded as gl_family.h's hostTexels says.
GLuint uploadColor(const FloatImage& image, GLenum internal) {
  const GLuint t = makeTexture(internal, image.extent);
  const HostTexels texels = hostTexels(image, internal);
  fill(image.extent, texels.layout, texels.type, texels.data());
  return t;
}

// Reads a level of a 2D texture as floats: a compute shader texelFetch()es it through a sampler of
// its own (nearest, so that depth and 32-bit float textures are complete) into a buffer mapped back.
constexpr const char* kReadbackShader = R"(#version 310 es
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform highp sampler2D src;
layout(location = 0) uniform int level;
layout(std430, binding = 0) writeonly buffer Texels { highp vec4 texels[]; };
void main() {
  ivec2 size = textureSize(src, level);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x < size.x && p.y < size.y) texels[p.y * size.x + p.x] = texelFetch(src, p, level);
}
)";

class Readback {
 public:
  Readback() {
    const Status st =
        gl::buildProgram({{GL_COMPUTE_SHADER, kReadbackShader, "readback.comp"}}, "GLES readback", program_);
    EXPECT_TRUE(st.ok()) << st.message;
    glGenSamplers(1, &sampler_);
    glSamplerParameteri(sampler_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glSamplerParameteri(sampler_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenBuffers(1, &buffer_);
  }
  ~Readback() {
    glDeleteProgram(program_);
    glDeleteSamplers(1, &sampler_);
    glDeleteBuffers(1, &buffer_);
  }
  Readback(const Readback&) = delete;
  Readback& operator=(const Readback&) = delete;

  // Level `level` of `texture`, its first `channels` channels; empty if the level has no texels.
  FloatImage read(GLuint texture, std::uint32_t level, std::uint32_t channels) {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture);
    GLint w = 0, h = 0;
    glGetTexLevelParameteriv(GL_TEXTURE_2D, GLint(level), GL_TEXTURE_WIDTH, &w);
    glGetTexLevelParameteriv(GL_TEXTURE_2D, GLint(level), GL_TEXTURE_HEIGHT, &h);
    if (w <= 0 || h <= 0) return {};
    FloatImage img({std::uint32_t(w), std::uint32_t(h)}, channels);
    dispatch(level, img.extent);
    copyBack(img);
    return img;
  }

 private:
  // The shader over the bound texture's level into the buffer (vec4 texels, row by row).
  void dispatch(std::uint32_t level, Extent e) {
    glBindSampler(0, sampler_);
    glUseProgram(program_);
    glUniform1i(0, GLint(level));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::size_t(e.width) * e.height * 4 * sizeof(float)), nullptr,
                 GL_STREAM_READ);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // the effect's image stores to intermediates
    glDispatchCompute((e.width + 7) / 8, (e.height + 7) / 8, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the mapping sees the shader's writes
    glUseProgram(0);
    glBindSampler(0, 0);
  }

  // The buffer's first img.channels channels of each texel into `img`.
  void copyBack(FloatImage& img) const {
    const std::size_t texels = std::size_t(img.extent.width) * img.extent.height;
    const auto bytes = GLsizeiptr(texels * 4 * sizeof(float));
    const auto* v = static_cast<const float*>(glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, bytes, GL_MAP_READ_BIT));
    if (v == nullptr) {
      ADD_FAILURE() << "GLES readback: glMapBufferRange failed";
      return;
    }
    for (std::size_t i = 0; i < texels; ++i)
      std::memcpy(&img.data[i * img.channels], v + i * 4, img.channels * sizeof(float));
    glUnmapBuffer(GL_SHADER_STORAGE_BUFFER);
  }

  GLuint program_ = 0, sampler_ = 0, buffer_ = 0;
};

// Whether `read` (the readback of a D16, D32F, D32FS8 or R32F texel) is texel `v`: the 16-bit
// integer recovered, float depth bit for bit (-0.0 held as +0.0, as GL stores it).
bool holds(Depth format, std::uint32_t v, float read) {
  if (format == Depth::D16) return std::lround(double(read) * 65535.0) == long(v);
  if (format == Depth::R32F) return std::bit_cast<std::uint32_t>(read) == v;
  return std::bit_cast<std::uint32_t>(read) == (v == 0x80000000u ? 0u : v);
}

class GlesExecutor final : public Executor {
 public:
  ~GlesExecutor() override {
    makeCurrent();
    effect_.reset();
    releaseInputs();
  }
  Api api() const override { return Api::Gles; }

  Status upload(const Frame& f) override {
    makeCurrent();
    releaseInputs();
    if (Status st = checkSupported(f); !st) return st;
    if (f.depth == nullptr) return Status::error(StatusCode::InvalidInput, "harness: the frame has no depth");
    format_ = depthUpload(f.format).internal;
    if (Status st = uploadDepth(*f.depth, f.format, depth_); !st) return st;
    if (f.depth2)
      if (Status st = uploadDepth(*f.depth2, f.format, depth2_); !st) return st;
    if (f.normals)
      normals_ = uploadColor(withChannels(*f.normals, channelsOf(f.normalsTexels)), texelsFormat(f.normalsTexels));
    if (f.motion)
      motion_ = uploadColor(withChannels(*f.motion, channelsOf(f.motionTexels)), texelsFormat(f.motionTexels));
    if (f.output.callerOwned) {
      const GLenum internal = gen::formatInfo(gen::glesStorageFormat(f.output.format)).glInternalFormat;
      output_ = f.output.initial ? uploadColor(*f.output.initial, internal)
                                 : makeTexture(internal, {f.camera.width, f.camera.height});
    }
    outputChannels_ = channelsOf(f.output.callerOwned ? f.output.format : gen::Format::R16F);
    return Status::success();
  }

  Status run(const Frame& f) override {
    makeCurrent();
    if (Status st = checkSupported(f); !st) return st;
    if (!effect_)
      if (Status st = gles::Effect::create(gl::HeadlessContext::getProcAddress(), effect_); !st) return st;
    gles::Inputs in = frameInputs<gles::Inputs>(f, format_, depth_, depth2_, normals_, motion_, output_);
    const Status st = effect_->render(f.camera, f.settings, in);
    glFinish();
    return st;
  }

  FloatImage output() override {
    makeCurrent();
    return readback_.read(effect_->aoTexture(), 0, outputChannels_);
  }

  // The effect's declared format's channels: ES stores rg16f / rg32f images as RGBA.
  FloatImage image(gen::ResourceId resource, std::uint32_t level) override {
    makeCurrent();
    const PlannedImage* planned = effect_->plan().image(resource);
    if (planned == nullptr) return {};
    return readback_.read(effect_->texture(resource), level, channelsOf(planned->format));
  }

  const Plan& plan() const override { return effect_->plan(); }
  const ParamBlock& params() const override { return effect_->params(); }
  std::uint64_t plans() const override { return effect_ ? effect_->stats().plans : 0; }
  std::uint64_t imageAllocations() const override { return effect_ ? effect_->stats().textureAllocations : 0; }
  std::uint64_t pipelines() const override { return effect_ ? effect_->stats().programsCompiled : 0; }
  std::uint64_t outputGeneration() const override { return effect_ ? effect_->outputGeneration() : 0; }
  void releaseEffect() override {
    makeCurrent();
    effect_.reset();
  }

 private:
  // A texture holding `depth` exactly, checked by reading it back (a driver's conversion off by one
  // is refused here, not found as a difference from the CPU reference). ES clamps D32F depth to
  // [0, 1] as GL does: an image it cannot hold is refused with texture_io.cpp's message.
  Status uploadDepth(const DepthImage& depth, Depth format, GLuint& texture) {
    if (depth.format != cpuFormat(format) || depth.texels.empty())
      return Status::error(StatusCode::InvalidInput, std::string("harness: a ") + sao::toString(depth.format) +
                                                         " image cannot be uploaded as " + toString(format));
    if (format == Depth::D32F || format == Depth::D32FS8)
      if (Status st = checkDepthValues(depth); !st)
        return Status::error(st.code,
                             std::string("a GL ") + toString(format) +
                                 " texture clamps depth to [0, 1], so it cannot hold this image: " + st.message);
    texture = makeTexture(depthUpload(format).internal, depth.extent);
    fillDepth(depth, format);
    const std::size_t mismatches = format == Depth::D24S8 ? 0 : differingTexels(depth, format, texture);
    if (mismatches == 0) return Status::success();
    deleteTexture(texture);
    return Status::error(StatusCode::InvalidInput, std::to_string(mismatches) + " texels of the GLES " +
                                                       toString(format) + " texture differ from the uploaded ones");
  }

  // The texels of `texture` that do not hold `depth`'s. A unorm24 texel reads back as the driver
  // converts it to float, which need not be the nearest float (llvmpipe: t * (1.0f / 16777215.0f)):
  // D24 is compared with a D24S8 texture of the same texels (packed, not converted; D24S8 itself
  // is not checked for that reason).
  std::size_t differingTexels(const DepthImage& depth, Depth format, GLuint texture) {
    const FloatImage back = readback_.read(texture, 0, 1);
    if (format == Depth::D24) {
      GLuint packed = makeTexture(GL_DEPTH24_STENCIL8, depth.extent);
      fillDepth(depth, Depth::D24S8);
      const FloatImage expected = readback_.read(packed, 0, 1);
      deleteTexture(packed);
      return test::differingValues(back, expected);
    }
    if (back.data.size() != depth.texels.size()) return depth.texels.size();
    std::size_t n = 0;
    for (std::size_t i = 0; i < back.data.size(); ++i) n += !holds(format, depth.texels[i], back.data[i]);
    return n;
  }

  void releaseInputs() {
    for (GLuint* t : {&depth_, &depth2_, &normals_, &motion_, &output_}) deleteTexture(*t);
  }
  Readback readback_;
  std::unique_ptr<gles::Effect> effect_;
  GLuint depth_ = 0, depth2_ = 0, normals_ = 0, motion_ = 0, output_ = 0;
  std::uint32_t format_ = 0, outputChannels_ = 1;
};

}  // namespace

std::unique_ptr<Executor> makeGlesExecutor() {
  makeCurrent();
  return std::make_unique<GlesExecutor>();
}

void glesMessagesBefore() {
  ASSERT_TRUE(context().makeCurrent().ok());
  context().clearMessages();
}

void glesMessagesAfter() {
  for (const auto& m : context().errors()) ADD_FAILURE() << "GLES debug message: " << gl::HeadlessContext::format(m);
  context().clearMessages();
}

}  // namespace sao::exectest
