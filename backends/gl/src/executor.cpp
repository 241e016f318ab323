#include "executor.h"

#include <cstring>
#include <string>

namespace sao::SAO_GL_NS::detail {

GLbitfield barrierBits(std::span<const Hazard> hazards) {
  GLbitfield bits = 0;
  for (const Hazard& h : hazards) switch (h.kind) {
      // Texel fetches after the barrier see the image stores before it.
      case HazardKind::ReadAfterWrite: bits |= GL_TEXTURE_FETCH_BARRIER_BIT; break;
      // Image stores after the barrier wait for every access before it.
      case HazardKind::WriteAfterRead:
      case HazardKind::WriteAfterWrite: bits |= GL_SHADER_IMAGE_ACCESS_BARRIER_BIT; break;
      // The caller's own shaders may have stored to an input.
      case HazardKind::CallerWrote: bits |= GL_TEXTURE_FETCH_BARRIER_BIT; break;
      // Whatever way the caller reads the result next.
      case HazardKind::CallerReads:
        bits |= GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT;
        break;
    }
  return bits;
}

GLuint GlExecutor::textureFor(gen::ResourceId id, bool previousFrame) const {
  if (inputs_ == nullptr) return 0;
  const auto& info = gen::kResources[static_cast<std::size_t>(id)];
  if (info.kind == gen::ResourceKind::Input) return inputs_->inputs[id].texture;
  if (info.kind == gen::ResourceKind::Output && inputs_->output.texture != 0) return inputs_->output.texture;
  return resources_.texture(id, imageCopy(historyParity_, id, previousFrame));
}

// Shared memory, units and work groups are checked for every pass variant at create().
Status GlExecutor::checkPlan(const Plan& plan) {
  DeviceLimits limits;
  limits.imageSide = {std::uint32_t(objects_.maxTextureSize), "GL_MAX_TEXTURE_SIZE"};
  const Status st = checkDeviceLimits(plan, limits);
  return st ? st : Status::error(st.code, std::string(kApiName) + ": " + st.message);
}

Status GlExecutor::createImage(const PlannedImage& image) {
  return resources_.create(image, objects_.scratchUnit, objects_.maxTextureSize, stats_.textureAllocations);
}

void GlExecutor::destroyImage(const PlannedImage& image) noexcept { resources_.destroy(image); }

Status GlExecutor::createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) {
  GLuint program = 0;
  return programs_.get(pass, variant, program, stats_.programsCompiled);
}

Status GlExecutor::beginFrame(const FrameWork& frame) {
  historyParity_ = frame.historyParity;
  pass_ = -1;
  gl_.BindBuffer(GL_UNIFORM_BUFFER, objects_.ubo);
  if (!haveBlock_ || std::memcmp(&uploaded_, frame.block, sizeof uploaded_) != 0) {
    gl_.BufferSubData(GL_UNIFORM_BUFFER, 0, sizeof uploaded_, frame.block);
    uploaded_ = *frame.block;
    haveBlock_ = true;
  }
  gl_.BindBufferBase(GL_UNIFORM_BUFFER, gen::kParamBlockBinding, objects_.ubo);
  timer_.beginFrame(measure_);
  return Status::success();
}

void GlExecutor::barrier(std::span<const Hazard> hazards) {
  if (const GLbitfield bits = barrierBits(hazards)) gl_.MemoryBarrier(bits);
}

// `declared`: the pass variant's own binding (the format its shader declares, whether it loads too).
void GlExecutor::bind(const ScheduledBinding& b, const gen::BindingInfo& declared) {
  const GLuint texture = textureFor(b.resource, b.previousFrame);
  if (b.write) {
    // On ES a write whose texels the pass loads but ES cannot load through the image (every format
    // but r32f) is write-only; the pass reads the texels through a texture of it (esKeptUnit).
    const bool kept = kEs && declared.esKeptUnit >= 0;
    // A levels= write is an image array: unit + j holds level baseLevel + j, the last level past the chain.
    for (std::uint32_t slot = 0; slot < declared.slots; ++slot)
      gl_.BindImageTexture(declared.glUnit + slot, texture, GLint(b.slotLevel(slot)), GL_FALSE, 0,
                           declared.readWrite && !kept ? GL_READ_WRITE : GL_WRITE_ONLY, glFormat(declared.format));
    if (kept) {
      gl_.ActiveTexture(GL_TEXTURE0 + GLuint(declared.esKeptUnit));
      gl_.BindTexture(GL_TEXTURE_2D, texture);
      gl_.BindSampler(GLuint(declared.esKeptUnit), objects_.nearestSampler);
    }
    return;
  }
  // A read sees the whole chain (lod chosen by the shader) or level 0 (create() refuses an effect
  // with a read of one level above 0 alone, which would need a view).
  gl_.ActiveTexture(GL_TEXTURE0 + declared.glUnit);
  // An input may be multisampled (sampler2DMS: the depth in linear_z's DEPTH_MULTISAMPLE variant).
  const bool input = gen::kResources[static_cast<std::size_t>(b.resource)].kind == gen::ResourceKind::Input;
  gl_.BindTexture(input ? inputs_->inputs[b.resource].target : GLenum(GL_TEXTURE_2D), texture);
  gl_.BindSampler(declared.glUnit, b.wholeChain ? objects_.mipSampler : objects_.nearestSampler);
}

void GlExecutor::dispatch(const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  if (pass_ != int(d.passIndex)) {
    if (pass_ >= 0) timer_.endPass();
    timer_.beginPass(gen::pass(d.pass).name);
    gl_.UseProgram(programs_.find(*d.variant));
    pass_ = int(d.passIndex);
  }
  // The schedule's bindings are one to one with the variant's.
  for (std::size_t i = 0; i < bindings.size(); ++i) bind(bindings[i], d.variant->bindings[i]);
  gl_.DispatchCompute(d.groupsX, d.groupsY, 1);
}

Status GlExecutor::endFrame() {
  if (pass_ >= 0) timer_.endPass();
  measureAgain_ = !timer_.endFrame(timings_);
  return Status::success();
}

}  // namespace sao::SAO_GL_NS::detail
