// The harness's OpenGL half: sao::gl::Effect::render() on the headless context of tests/gl.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

#include "gl_msaa_depth_writer.h"
#include "gl_support.h"
#include "gl_family.h"
#include "harness_apis.h"
#include "msaa_depth.h"
#include "sao/cpu/reference.h"

namespace sao::exectest {
namespace {

gl::GlDepth glDepth(Depth d) {
  switch (d) {
    case Depth::D16: return gl::GlDepth::D16;
    case Depth::D24: return gl::GlDepth::D24;
    case Depth::D24S8: return gl::GlDepth::D24S8;
    case Depth::D32F: return gl::GlDepth::D32F;
    case Depth::D32FS8: return gl::GlDepth::D32FS8;
    case Depth::R32F: return gl::GlDepth::R32F;
  }
  return gl::GlDepth::D32F;
}


// A texture of `internal` holding `image` (its channels), uploaded as gl_family.h's hostTexels says.
GLuint uploadColor(const FloatImage& image, GLenum internal) {
  const GLuint t = gl::makeTexture(internal, image.extent);
  const HostTexels texels = hostTexels(image, internal);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t, 0, 0, 0, GLsizei(image.extent.width), GLsizei(image.extent.height), texels.layout, texels.type,
                      texels.data());
  return t;
}

// Every call that touches GL makes the GL context current first: a program's GLES executor, or the
// fixture of a GLES test, may have left its own context current.
void makeCurrent() {
  const Status st = gltest::context().makeCurrent();
  if (!st) ADD_FAILURE() << st.message;
}

class GlExecutor final : public Executor {
 public:
  ~GlExecutor() override {
    makeCurrent();
    effect_.reset();
    releaseInputs();
  }
  Api api() const override { return Api::Gl; }

  Status upload(const Frame& f) override {
    makeCurrent();
    releaseInputs();
    if (!f.depthLayers.empty()) {  // stereo: immutable GL_TEXTURE_2D_ARRAYs, Inputs::layer picks one
      if (Status st = checkLayers(f); !st) return st;
      format_ = gl::internalFormat(glDepth(f.format));
      depth_ = gltest::uploadDepthArray(format_, f.depthLayers);
      layers_ = std::uint32_t(f.depthLayers.size());
      outputExtent_ = {f.camera.width, f.camera.height};
      output_ = gltest::makeTextureArray(gen::formatInfo(f.output.format).glInternalFormat, outputExtent_, layers_);
      outputChannels_ = channelsOf(f.output.format);
      return Status::success();
    }
    if (f.depth == nullptr) return Status::error(StatusCode::InvalidInput, "harness: the frame has no depth");
    format_ = gl::internalFormat(glDepth(f.format));
    if (f.depth->samples > 1) {
      if (f.format != Depth::D32F || f.depth->samples != std::uint32_t(gltest::kWriterSamples))
        return Status::error(StatusCode::InvalidInput, "harness: multisampled depth is 4-sample D32F");
      depth_ = gltest::writeSamples(f.depth->extent, test::sampleValues(*f.depth));
    } else if (Status st = gl::uploadDepth(*f.depth, glDepth(f.format), depth_); !st) {
      return st;
    }
    if (f.depth2)
      if (Status st = gl::uploadDepth(*f.depth2, glDepth(f.format), depth2_); !st) return st;
    if (f.normals)
      normals_ = uploadColor(withChannels(*f.normals, channelsOf(f.normalsTexels)), texelsFormat(f.normalsTexels));
    if (f.motion)
      motion_ = uploadColor(withChannels(*f.motion, channelsOf(f.motionTexels)), texelsFormat(f.motionTexels));
    if (f.output.callerOwned) {
      const GLenum internal = gen::formatInfo(f.output.format).glInternalFormat;
      const Extent e{f.camera.width, f.camera.height};
      output_ = f.output.initial ? uploadColor(*f.output.initial, internal) : gl::makeTexture(internal, e);
    }
    outputChannels_ = channelsOf(f.output.callerOwned ? f.output.format : gen::Format::R16F);
    return Status::success();
  }

  Status run(const Frame& f) override {
    makeCurrent();
    if (!effect_)
      if (Status st = gl::Effect::create(gl::HeadlessContext::getProcAddress(), effect_); !st) return st;
    gl::Inputs in = frameInputs<gl::Inputs>(f, format_, depth_, depth2_, normals_, motion_, output_);
    in.layer = f.layer;
    const Status st = effect_->render(f.camera, f.settings, in);
    glFinish();
    if (st) lastLayer_ = f.layer;
    return st;
  }

  FloatImage output() override {
    makeCurrent();
    if (layers_ == 0) return gl::readTexture(effect_->aoTexture(), outputChannels_);
    // One layer of the caller's array (readTexture reads level 0 of a 2D texture).
    FloatImage img(outputExtent_, outputChannels_);
    const GLenum layout = outputChannels_ == 1 ? GL_RED : outputChannels_ == 2 ? GL_RG : GL_RGBA;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(output_, 0, 0, 0, GLint(lastLayer_), GLsizei(outputExtent_.width), GLsizei(outputExtent_.height),
                         1, layout, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
    return img;
  }

  FloatImage image(gen::ResourceId resource, std::uint32_t level) override {
    makeCurrent();
    const PlannedImage* planned = effect_->plan().image(resource);
    if (planned == nullptr) return {};
    return gl::readTextureLevel(effect_->texture(resource), level, channelsOf(planned->format));
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
  void releaseInputs() {
    for (GLuint* t : {&depth_, &depth2_, &normals_, &motion_, &output_}) {
      gl::deleteTexture(*t);
      *t = 0;
    }
    layers_ = 0;
  }
  std::unique_ptr<gl::Effect> effect_;
  GLuint depth_ = 0, depth2_ = 0, normals_ = 0, motion_ = 0, output_ = 0;
  std::uint32_t format_ = 0, outputChannels_ = 1;
  std::uint32_t layers_ = 0, lastLayer_ = 0;  // stereo: the arrays' layers (0: plain textures), the last run's
  Extent outputExtent_;
};

}  // namespace

std::unique_ptr<Executor> makeGlExecutor() {
  gltest::context();
  return std::make_unique<GlExecutor>();
}

void glMessagesBefore() {
  ASSERT_TRUE(gltest::context().makeCurrent().ok());
  gltest::context().clearMessages();
}

void glMessagesAfter() {
  for (const auto& m : gltest::context().errors()) ADD_FAILURE() << "GL debug message: " << gl::HeadlessContext::format(m);
  gltest::context().clearMessages();
}

}  // namespace sao::exectest
