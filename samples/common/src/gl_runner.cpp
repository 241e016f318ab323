// The OpenGL backend as a sample backend: a headless EGL context of its own, the depth uploaded
// as the matching GL format (once while it stays the same), the results read back.
#include <chrono>
#include <cstring>

#include "runners.h"
#include "sao/gl/effect.h"
#include "sao/gl/headless.h"
#include "sao/gl/texture_io.h"

namespace sao::samples {
namespace {

gl::GlDepth glFormat(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return gl::GlDepth::D16;
    case DepthFormat::D24: return gl::GlDepth::D24;
    case DepthFormat::D32F: return gl::GlDepth::D32F;
    case DepthFormat::LinearZ: return gl::GlDepth::R32F;
  }
  return gl::GlDepth::D32F;
}

bool sameImage(const DepthImage& a, const DepthImage& b) {
  return a.extent == b.extent && a.format == b.format && a.samples == b.samples && a.texels == b.texels;
}
bool sameImage(const FloatImage& a, const FloatImage& b) {
  return a.extent == b.extent && a.channels == b.channels && a.data.size() == b.data.size() &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;  // NaN bits too
}

// An input texture kept across runs while the image is the same (bit for bit), as an engine's
// depth stays on the GPU: with a texture created and uploaded in every run, the GL timer of the
// first pass reading it held about 0.5-1 ms more than Vulkan's on an H200, most likely the
// driver's deferred upload (docs/BENCHMARKS.md, "On a GPU").
template <class Image>
struct KeptInput {
  std::uint32_t texture = 0;
  Image uploaded;
  bool holds(const Image& image) const { return texture && sameImage(uploaded, image); }
  void release() {
    gl::deleteTexture(texture);
    texture = 0;
  }
};

class GlRunner final : public BackendRunner {
 public:
  GlRunner(std::unique_ptr<gl::HeadlessContext> context, std::unique_ptr<gl::Effect> effect)
      : context_(std::move(context)), effect_(std::move(effect)) {}
  ~GlRunner() override {
    if (!context_->makeCurrent().ok()) return;  // the objects die with the context
    effect_.reset();                              // GL objects need the context
    depth_.release();
    depth2_.release();
    normals_.release();
    gl::deleteTexture(output_.texture);
  }
  std::string_view name() const override { return "gl"; }
  std::string description() const override { return "OpenGL: " + context_->description(); }

  Status run(const Settings& settings, const Camera& camera, const RunInputs& in, bool measureTime, bool dumpPasses,
             RunOutputs& out) override {
    gl::Inputs inputs;
    if (Status s = bind(settings, camera, in, inputs); !s) return s;
    if (Status s = effect_->render(camera, settings, inputs, {measureTime}); !s) return s;
    out.plan = effect_->plan();
    out.timings = effect_->timings();
    splitOutput(gl::readTexture(effect_->aoTexture(), gen::formatInfo(runnerOutputFormat(settings)).channels), out);
    if (out.plan.image(gen::ResourceId::ao_raw))  // not planned when ao_sample_output writes the output
      out.aoRaw = gl::readTexture(effect_->texture(gen::ResourceId::ao_raw), 2);
    if (dumpPasses) {
      if (const auto* csz = out.plan.image(gen::ResourceId::csz))
        for (std::uint32_t m = 0; m < csz->mipLevels; ++m)
          out.intermediates.push_back(
              {"csz_level" + std::to_string(m), gl::readTextureLevel(effect_->texture(gen::ResourceId::csz), m)});
      if (!out.aoRaw.data.empty()) out.intermediates.push_back({"ao_raw", out.aoRaw});
      if (out.plan.image(gen::ResourceId::ao_low))  // the blurred (A, key), the upsample's input
        out.intermediates.push_back({"ao_low", gl::readTexture(effect_->texture(gen::ResourceId::ao_low), 2)});
    }
    return reportedErrors();
  }

  Status keepBusy(const Settings& settings, const Camera& camera, const RunInputs& in, double milliseconds) override {
    gl::Inputs inputs;
    if (Status s = bind(settings, camera, in, inputs); !s) return s;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(milliseconds);
    do {  // a few frames queued between waits: the GPU never idles long
      for (int i = 0; i < 4; ++i)
        if (Status s = effect_->render(camera, settings, inputs, {false}); !s) return s;
      if (Status s = context_->finish(); !s) return s;
    } while (std::chrono::steady_clock::now() < end);
    return reportedErrors();
  }

 private:
  // The context made current and the effect's inputs: the kept textures, uploaded again where the
  // images changed, and for an output format other than the effect's own (runnerOutputFormat) a
  // texture of the viewport's size in it, kept while format and size stay.
  Status bind(const Settings& settings, const Camera& camera, const RunInputs& in, gl::Inputs& inputs) {
    if (!in.depth) return Status::error(StatusCode::InvalidInput, "no depth image");
    if (Status s = context_->makeCurrent(); !s) return s;
    const gl::GlDepth format = glFormat(in.depth->format);
    if (Status s = keepDepth(*in.depth, depth_); !s) return s;
    if (in.depth2)
      if (Status s = keepDepth(*in.depth2, depth2_); !s) return s;
    if (in.normals && !normals_.holds(*in.normals)) {
      normals_.release();
      if (Status s = gl::uploadNormals(*in.normals, normals_.texture); !s) return s;
      normals_.uploaded = *in.normals;
    }
    inputs.depth = {depth_.texture, gl::internalFormat(format)};
    if (in.depth2) inputs.depth2 = {depth2_.texture, gl::internalFormat(glFormat(in.depth2->format))};
    inputs.normals = in.normals ? normals_.texture : 0;
    inputs.frameIndex = in.frameIndex;
    inputs.resetHistory = in.resetHistory;
    const Extent viewport{camera.width, camera.height};
    const gen::Format outputFormat = runnerOutputFormat(settings);
    const bool own = outputFormat != gen::kResources[std::size_t(gen::ResourceId::ao)].format;
    if (!own || output_.format != outputFormat || output_.extent != viewport) {
      gl::deleteTexture(output_.texture);
      output_ = {};
    }
    if (own && !output_.texture)
      output_ = {gl::makeTexture(gen::formatInfo(outputFormat).glInternalFormat, viewport), outputFormat, viewport};
    inputs.output = output_.texture;
    return Status::success();
  }

  // The first message the debug context reported, as an error.
  Status reportedErrors() {
    for (const auto& m : context_->errors())
      return Status::error(StatusCode::DriverError, "GL reported: " + gl::HeadlessContext::format(m));
    return Status::success();
  }

  static Status keepDepth(const DepthImage& image, KeptInput<DepthImage>& kept) {
    if (kept.holds(image)) return Status::success();
    kept.release();
    if (Status s = gl::uploadDepth(image, glFormat(image.format), kept.texture); !s) return s;
    kept.uploaded = image;
    return Status::success();
  }

  std::unique_ptr<gl::HeadlessContext> context_;
  std::unique_ptr<gl::Effect> effect_;
  KeptInput<DepthImage> depth_, depth2_;
  KeptInput<FloatImage> normals_;
  struct {
    std::uint32_t texture = 0;
    gen::Format format = gen::Format::R16F;
    Extent extent;
  } output_;  // the output in runnerOutputFormat's format (0: the effect's own)
};

}  // namespace

Status makeGlRunner(std::unique_ptr<BackendRunner>& out) {
  std::unique_ptr<gl::HeadlessContext> context;
  if (Status s = gl::HeadlessContext::create(context); !s) return s;
  std::unique_ptr<gl::Effect> effect;
  if (Status s = gl::Effect::create(gl::HeadlessContext::getProcAddress(), effect); !s) return s;
  out = std::make_unique<GlRunner>(std::move(context), std::move(effect));
  return Status::success();
}

}  // namespace sao::samples
