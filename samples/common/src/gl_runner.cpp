// The OpenGL backend as a sample backend: a headless EGL context of its own, the depth uploaded
// as the matching GL format, the results read back.
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

// Deletes the textures a run uploaded, whatever path it leaves by.
struct Uploads {
  std::uint32_t depth = 0, depth2 = 0, normals = 0;
  ~Uploads() {
    for (auto t : {depth, depth2, normals}) gl::deleteTexture(t);
  }
};

class GlRunner final : public BackendRunner {
 public:
  GlRunner(std::unique_ptr<gl::HeadlessContext> context, std::unique_ptr<gl::Effect> effect)
      : context_(std::move(context)), effect_(std::move(effect)) {}
  ~GlRunner() override {
    if (context_->makeCurrent().ok()) effect_.reset();  // GL objects need the context
  }
  std::string_view name() const override { return "gl"; }
  std::string description() const override { return "OpenGL: " + context_->description(); }

  Status run(const Settings& settings, const Camera& camera, const RunInputs& in, bool measureTime, bool dumpPasses,
             RunOutputs& out) override {
    if (!in.depth) return Status::error(StatusCode::InvalidInput, "no depth image");
    if (Status s = context_->makeCurrent(); !s) return s;
    Uploads up;
    const gl::GlDepth format = glFormat(in.depth->format);
    if (Status s = gl::uploadDepth(*in.depth, format, up.depth); !s) return s;
    if (in.depth2)
      if (Status s = gl::uploadDepth(*in.depth2, glFormat(in.depth2->format), up.depth2); !s) return s;
    if (in.normals)
      if (Status s = gl::uploadNormals(*in.normals, up.normals); !s) return s;
    gl::Inputs inputs;
    inputs.depth = {up.depth, gl::internalFormat(format)};
    if (in.depth2) inputs.depth2 = {up.depth2, gl::internalFormat(glFormat(in.depth2->format))};
    inputs.normals = up.normals;
    inputs.frameIndex = in.frameIndex;
    inputs.resetHistory = in.resetHistory;
    if (Status s = effect_->render(camera, settings, inputs, {measureTime}); !s) return s;
    out.plan = effect_->plan();
    out.timings = effect_->timings();
    out.ao = gl::readTexture(effect_->aoTexture(), 1);
    out.aoRaw = gl::readTexture(effect_->texture(gen::ResourceId::ao_raw), 2);
    if (dumpPasses) {
      if (const auto* csz = out.plan.image(gen::ResourceId::csz))
        for (std::uint32_t m = 0; m < csz->mipLevels; ++m)
          out.intermediates.push_back(
              {"csz_level" + std::to_string(m), gl::readTextureLevel(effect_->texture(gen::ResourceId::csz), m)});
      out.intermediates.push_back({"ao_raw", out.aoRaw});
      if (out.plan.image(gen::ResourceId::ao_low))  // the blurred (A, key), the upsample's input
        out.intermediates.push_back({"ao_low", gl::readTexture(effect_->texture(gen::ResourceId::ao_low), 2)});
    }
    for (const auto& m : context_->errors())
      return Status::error(StatusCode::DriverError, "GL reported: " + gl::HeadlessContext::format(m));
    return Status::success();
  }

 private:
  std::unique_ptr<gl::HeadlessContext> context_;
  std::unique_ptr<gl::Effect> effect_;
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
