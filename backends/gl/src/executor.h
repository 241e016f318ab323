// The OpenGL executor of core's frame (sao/executor.h): effect-owned textures, programs from the
// generated GLSL, the parameter block in one uniform buffer, glMemoryBarrier for each hazard, and
// each dispatch with its bindings (binding N = texture unit N for sampled reads, image unit N for
// stores). It decides nothing: FrameState says what to create, keep and run.
#pragma once
#include "gl_functions.h"
#include "inputs.h"
#include "programs.h"
#include "resources.h"
#include "sao/executor.h"
#include "api.h"
#include "timing.h"

namespace sao::SAO_GL_NS::detail {

// The glMemoryBarrier bits that resolve `hazards` (0: none needed).
GLbitfield barrierBits(std::span<const Hazard> hazards);

struct GlObjects {
  GLuint ubo = 0;
  GLuint nearestSampler = 0;  // GL_NEAREST, compare mode none: inputs, single levels
  GLuint mipSampler = 0;      // GL_NEAREST_MIPMAP_NEAREST: whole MIP chains read at explicit lods
  GLuint scratchUnit = 1;     // where textures are bound while created (the StateGuard saves it)
  GLint maxTextureSize = 0;
};

class GlExecutor final : public Executor {
 public:
  GlExecutor(const GlFunctions& gl, const GlObjects& objects, Resources& resources, Programs& programs,
             PassTimer& timer, Stats& stats, Timings& timings)
      : gl_(gl), objects_(objects), resources_(resources), programs_(programs), timer_(timer), stats_(stats),
        timings_(timings) {}

  // This render's caller textures and whether it measures; set before FrameState runs a frame.
  void setFrame(const CheckedInputs* inputs, bool measure) {
    inputs_ = inputs;
    measure_ = measure;
  }
  // The GPU timers measured nothing this frame: FrameState::repeat() measures it again by clock.
  bool measureAgain() const { return measureAgain_; }
  // The texture that serves `id` in the last frame (input, owned image or output), 0 if none; for a
  // history, that frame's copy, or the previous frame's with `previousFrame`.
  GLuint textureFor(gen::ResourceId id, bool previousFrame = false) const;

  Status checkPlan(const Plan& plan) override;
  Status createImage(const PlannedImage& image) override;
  void destroyImage(const PlannedImage& image) noexcept override;
  Status createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) override;
  Status beginFrame(const FrameWork& frame) override;
  void barrier(std::span<const Hazard> hazards) override;
  void dispatch(const ScheduledDispatch& dispatch, std::span<const ScheduledBinding> bindings) override;
  Status endFrame() override;

 private:
  void bind(const ScheduledBinding& b, const gen::BindingInfo& declared);

  const GlFunctions& gl_;
  const GlObjects& objects_;
  Resources& resources_;
  Programs& programs_;
  PassTimer& timer_;
  Stats& stats_;
  Timings& timings_;
  const CheckedInputs* inputs_ = nullptr;
  bool measure_ = false;
  bool measureAgain_ = false;
  std::uint32_t historyParity_ = 0;
  int pass_ = -1;  // the plan pass of the last dispatch this frame
  bool haveBlock_ = false;
  ParamBlock uploaded_{};
};

}  // namespace sao::SAO_GL_NS::detail
