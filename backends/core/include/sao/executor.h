// The effect's frame as core runs it, and the small interface whatever runs the passes implements
// (an engine's own renderer, the CPU reference, a graphics API backend): FrameState decides, per
// effect instance, the plan, the schedule, which images a new configuration keeps, the complete
// parameter block of every frame and the temporal history; an Executor only creates what it is
// asked for and records what the schedule says, in order.
//
//   FrameState frame("my-engine");
//   each frame: frame.render(settings, camera, planInputs, FrameInputs{...}, executor);
//   at the end: frame.release(executor);
//
// render() plans again only when the settings, the plan inputs or a plan-changing camera change;
// configure() and run() are its two halves, for a caller that configures apart from its frames.
//
// What an executor needs of each pass it finds in the generated tables (sao_effect.h) or, for an
// engine outside C++, in sao_passes.json beside the shader files (sao_SHADER_DIR): the bindings
// (gen::BindingInfo: set-0 binding, GL unit, read or write, format, array slots), the local size
// (gen::PassInfo::localX/Y), the push constants (PassVariantInfo::pushConstantBytes, filled with
// gen::pushConstantsOf(block)), the shared memory (PassVariantInfo::sharedBytes, to check against
// the device's limit), and one sampler for every read: nearest, clamp to edge, every level (the
// shaders only texelFetch). The parameter block (gen::SaoParams) is a uniform buffer at
// gen::kParamBlockBinding.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "sao/frame.h"
#include "sao/plan.h"
#include "sao/schedule.h"
#include "sao/temporal.h"

namespace sao {

// What one frame hands the executor before its first dispatch.
struct FrameWork {
  const Plan* plan = nullptr;
  const Schedule* schedule = nullptr;
  const ParamBlock* block = nullptr;  // the whole block of this frame: upload it, push its constants
  // The copy of a history image a binding or hazard names: imageCopy(historyParity, resource,
  // previousFrame) (sao/temporal.h); 0 for every other image.
  std::uint32_t historyParity = 0;
  // Whether the previous frame's history copy holds a frame this one reads (its contents must be
  // kept); false: the shaders ignore it (history_valid = 0), so its contents may be discarded.
  bool historyValid = false;
};

// A device's limits a plan must fit (0: not checked), named as its API names them for the messages
// ("maxImageDimension2D", "GL_MAX_TEXTURE_SIZE"). An executor's checkPlan fills it from its device.
struct DeviceLimits {
  struct Limit {
    std::uint32_t value = 0;
    const char* name = "";
  };
  Limit imageSide;             // the largest side of an image the plan allocates or reads
  Limit sharedBytes;           // a work group's shared memory (PassVariantInfo::sharedBytes)
  Limit pushConstantBytes;     // PassVariantInfo::pushConstantBytes
  Limit storageImagesPerPass;  // a pass variant's storage-image elements (a levels= write: its slots)
  Limit sampledImagesPerPass;  // its sampled reads
};

// The plan against `limits`: Ok, or DriverError naming the pass, what it needs and the limit
// (InvalidExtent "... exceeds this device's <name> ..." for an image side). Allocates only for an error.
Status checkDeviceLimits(const Plan& plan, const DeviceLimits& limits);

class Executor {
 public:
  virtual ~Executor() = default;

  // The executor's own limits (texture size, shared memory, work-group counts) against a plan,
  // before any of its images is created: a refusal leaves the current configuration as it was.
  virtual Status checkPlan(const Plan& /*plan*/) { return Status::success(); }
  // An effect-owned image of the plan: its format, level-0 extent, levels and copies (a history
  // has two). The output is one only when the plan inputs say the effect owns it (not
  // PlanInputs::userOutput); inputs never are: the executor binds the caller's own. Called for
  // each image a new plan adds or changes, while the current plan's images still exist: for a
  // while the executor may hold two images of one resource, which then differ in format, extent,
  // levels or copies (sameImage). An image the plan keeps is not created again.
  virtual Status createImage(const PlannedImage& image) = 0;
  // An image created before, named by the PlannedImage it was created for: one the new plan drops
  // or changes (once the new plan's images exist), one of a new plan that failed, or every image
  // at release().
  virtual void destroyImage(const PlannedImage& image) noexcept = 0;
  // After a new plan's images and pipelines exist and before any of the current plan's images is
  // destroyed: what else the executor needs for the plan (memory for the new images, descriptor
  // sets for the schedule), built beside what the current plan uses. A failure destroys the new
  // images and leaves the current configuration as it was.
  virtual Status preparePlan(const Plan& /*plan*/, const Schedule& /*schedule*/) { return Status::success(); }
  // The new plan is FrameState's now (the images it dropped are destroyed): swap in what
  // preparePlan() built. Cannot fail.
  virtual void planAdopted() noexcept {}

  // A compiled pass variant the plan runs (its bindings, push constants, shared memory; the
  // SPIR-V module variant.spirvBlob or the file <fileStem>.spv, the GLSL glslBlob or
  // <fileStem>.glsl). Called once per variant for the life of the FrameState, release() included:
  // a FrameState talks to one executor, which destroys its pipelines itself.
  virtual Status createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) = 0;

  // One frame: beginFrame, then barrier() for the entry hazards, barrier() and dispatch() for each
  // of the schedule's dispatches in order, barrier() for the exit hazards, endFrame(). A barrier
  // with no hazards is not called. Hazards and bindings name resources; a binding of an input or
  // the caller's output is the executor's own image of that resource (the caller's images never
  // pass through FrameState: an executor knows them from its engine).
  //  - The entry hazards come first (the span is FrameWork::schedule->entryHazards()): their
  //    earlier access is the previous frame's, the caller's own use of its images included (its
  //    readback of the output, its writes of the inputs), so their source stages are the engine's.
  //    CallerReads (the exit) is followed by whatever the caller does with the output.
  //  - Every effect image but a history's previous-frame copy is rewritten whole by the frame: its
  //    contents may be discarded at frame entry. The previous-frame copy is read, and must be kept
  //    only when FrameWork::historyValid. A new image's contents and layout are the executor's.
  //  - `dispatch` is an element of FrameWork::schedule->dispatches (its index: &dispatch - its
  //    data()), `bindings` are one to one, in order, with dispatch.variant->bindings, and the block
  //    stays valid until endFrame(). barrier() and dispatch() return nothing: an executor keeps
  //    their first error and returns it from endFrame().
  //  - FrameState does not know about frames in flight: an executor whose frames are still running
  //    waits for them (or defers) in destroyImage().
  virtual Status beginFrame(const FrameWork& frame) = 0;
  virtual void barrier(std::span<const Hazard> hazards) = 0;
  virtual void dispatch(const ScheduledDispatch& dispatch, std::span<const ScheduledBinding> bindings) = 0;
  virtual Status endFrame() = 0;
};

// One frame's inputs to FrameState::run.
struct FrameInputs {
  // This frame's camera, which must keep the plan (checkCameraKeepsPlan: TAA jitter, the other eye
  // of a stereo pair); null: the configured camera.
  const Camera* camera = nullptr;
  // Temporal accumulation: the camera the previous frame ran with, when not the one FrameState
  // kept (sao/temporal.h); `resetHistory` starts the history again (a camera cut).
  const Camera* previousCamera = nullptr;
  bool resetHistory = false;
  FrameValues values;  // region offset, frame index, output channels and blend
  // The caller's images this frame (extents and region), checked against the plan when given
  // (checkSupplied); null: not checked here (the executor should check its own).
  const SuppliedImages* images = nullptr;
};

class FrameState {
 public:
  // `who` prefixes the messages of the frame's own checks ("sao::gl", "my-engine"; plan() and the
  // camera's errors come as core gives them); it must outlive the FrameState.
  explicit FrameState(const char* who) : who_(who) {}

  // Plans for the configuration (one validation: plan()). The images the current plan holds with
  // the same format, extent, levels and copies are kept; the new plan's other images are created,
  // pipelines for the variants not created before, and only then the current plan's other images
  // destroyed (both exist for that while). The temporal history starts again. On error nothing changed but the pipelines made (a cache): the
  // current configuration, if any, still runs, and the Status says why.
  Status configure(const Settings& settings, const Camera& camera, const PlanInputs& inputs, Executor& executor);

  // Whether a frame with these settings, camera and plan inputs runs on the current configuration
  // (the same settings and plan inputs, a camera that keeps the plan). Allocates nothing.
  bool keeps(const Settings& settings, const Camera& camera, const PlanInputs& inputs) const;

  // The per-frame call: configures when keeps() says so, checking `frame` (output use, supplied
  // images) against the new plan before any image is created or destroyed, then run() with
  // `camera` as the frame's camera (frame.camera is ignored). A frame on an unchanged
  // configuration allocates nothing.
  Status render(const Settings& settings, const Camera& camera, const PlanInputs& inputs, const FrameInputs& frame,
                Executor& executor);

  // One frame through `executor` (see Executor); allocates nothing. InvalidInput without a
  // configuration, for a camera that does not keep the plan, a refused output use
  // (checkFrameOutput) or supplied images the plan cannot take (checkSupplied); the executor's
  // own error from beginFrame or endFrame. The history counts the frame only when it ran.
  Status run(const FrameInputs& frame, Executor& executor);

  // For a caller that carries the history itself from run to run (a stateless executor, the CPU
  // reference): the previous-frame copy holds a frame of this configuration, made with `camera`
  // (checked by the next run() as Inputs::previousCamera is). No effect without a configuration.
  void continueHistory(const Camera& camera);

  // The last frame run() made, again: the same block and history copies (the history is not
  // advanced twice), for an executor that measures a frame a second time. InvalidInput when no
  // frame ran on this configuration.
  Status repeat(Executor& executor);

  // Destroys every image through `executor` (pipelines are the executor's to destroy).
  void release(Executor& executor) noexcept;

  bool configured() const { return configured_; }
  const Plan& plan() const { return plan_; }
  const Schedule& schedule() const { return schedule_; }
  const Settings& settings() const { return settings_; }
  const Camera& camera() const { return camera_; }
  const PlanInputs& planInputs() const { return inputs_; }
  // The last frame's block; before a configuration's first frame, its own (FrameValues{}, no history).
  const ParamBlock& block() const { return block_; }
  const TemporalHistory& history() const { return history_; }
  std::uint64_t plans() const { return plans_; }  // configurations made so far

 private:
  Status checkFrame(const Plan& plan, const PlanInputs& inputs, const FrameInputs& frame) const;
  Status adopt(const Settings& settings, const Camera& camera, const PlanInputs& inputs, Plan next,
               Executor& executor);
  void walk(Executor& executor);

  const char* who_;
  bool configured_ = false;
  Settings settings_;
  Camera camera_;
  PlanInputs inputs_;
  Plan plan_;
  Schedule schedule_;
  ParamBlock block_{};
  TemporalHistory history_;
  std::vector<const gen::PassVariantInfo*> pipelines_;  // created through an executor
  std::uint64_t plans_ = 0;
  FrameWork lastWork_;  // what the last run() handed beginFrame (its plan and block: the members)
  bool ranOnPlan_ = false;
};

}  // namespace sao
