#include "sao/executor.h"

#include <algorithm>
#include <string>

namespace sao {
namespace {

bool holdsImage(const Plan& plan, const PlannedImage& image) {
  const PlannedImage* same = plan.image(image.resource);
  return same != nullptr && sameImage(*same, image);
}

std::string passText(const PlannedPass& p) { return "pass '" + std::string(gen::pass(p.pass).name) + "'"; }

Status overLimit(const PlannedPass& p, const std::string& needs, const DeviceLimits::Limit& limit) {
  return Status::error(StatusCode::DriverError, passText(p) + " " + needs + ", above this device's " + limit.name + " " +
                                                    std::to_string(limit.value));
}

bool exceeds(std::uint32_t need, const DeviceLimits::Limit& limit) { return limit.value != 0 && need > limit.value; }

}  // namespace

Status checkDeviceLimits(const Plan& plan, const DeviceLimits& limits) {
  for (const PlannedPass& p : plan.passes) {
    std::uint32_t storage = 0, sampled = 0;
    for (const gen::BindingInfo& b : p.variant->bindings) (b.write ? storage : sampled) += b.slots;
    if (exceeds(storage, limits.storageImagesPerPass))
      return overLimit(p, "binds " + std::to_string(storage) + " storage images", limits.storageImagesPerPass);
    if (exceeds(sampled, limits.sampledImagesPerPass))
      return overLimit(p, "binds " + std::to_string(sampled) + " sampled images", limits.sampledImagesPerPass);
    if (exceeds(p.variant->sharedBytes, limits.sharedBytes))
      return overLimit(p, "declares " + std::to_string(p.variant->sharedBytes) + " bytes of shared memory",
                       limits.sharedBytes);
    if (exceeds(p.variant->pushConstantBytes, limits.pushConstantBytes))
      return overLimit(p, "takes " + std::to_string(p.variant->pushConstantBytes) + " bytes of push constants",
                       limits.pushConstantBytes);
  }
  // The input extent is the largest any image of the plan has (csz, the caller's depth).
  const Extent ie = plan.inputExtent;
  if (exceeds(std::max(ie.width, ie.height), limits.imageSide))
    return Status::error(StatusCode::InvalidExtent, "the input extent " + std::to_string(ie.width) + "x" +
                                                        std::to_string(ie.height) + " exceeds this device's " +
                                                        limits.imageSide.name + " " +
                                                        std::to_string(limits.imageSide.value));
  return Status::success();
}

Status FrameState::configure(const Settings& settings, const Camera& camera, const PlanInputs& inputs,
                             Executor& executor) {
  Plan next;
  if (Status st = sao::plan(settings, camera, inputs, next); !st) return st;
  return adopt(settings, camera, inputs, std::move(next), executor);
}

bool FrameState::keeps(const Settings& settings, const Camera& camera, const PlanInputs& inputs) const {
  return configured_ && settings == settings_ && inputs == inputs_ &&
         (camera == camera_ || cameraKeepsPlan(settings, camera_, camera));
}

Status FrameState::render(const Settings& settings, const Camera& camera, const PlanInputs& inputs,
                          const FrameInputs& frame, Executor& executor) {
  if (!keeps(settings, camera, inputs)) {
    Plan next;
    if (Status st = sao::plan(settings, camera, inputs, next); !st) return st;
    if (Status st = checkFrame(next, inputs, frame); !st) return st;
    if (Status st = adopt(settings, camera, inputs, std::move(next), executor); !st) return st;
  }
  FrameInputs f = frame;
  f.camera = &camera;
  return run(f, executor);
}

Status FrameState::checkFrame(const Plan& plan, const PlanInputs& inputs, const FrameInputs& frame) const {
  if (Status st = checkFrameOutput(plan, inputs, frame.values, who_); !st) return st;
  if (frame.images)
    if (Status st = checkSupplied(plan, *frame.images, inputs.userOutput, who_); !st) return st;
  return Status::success();
}

Status FrameState::adopt(const Settings& settings, const Camera& camera, const PlanInputs& inputs, Plan next,
                         Executor& executor) {
  ParamBlock configured{};  // the configuration's block, block() until its first frame
  if (Status st = frameConstants(settings, camera, inputs, FrameValues{}, configured); !st) return st;
  if (Status st = executor.checkPlan(next); !st) return st;
  Schedule schedule = makeSchedule(next);
  auto isNew = [&](const PlannedImage& image) { return !(configured_ && holdsImage(plan_, image)); };
  // What the new plan adds or changes is created beside the current images, so that a failure (an
  // error or an exception) destroys only what it made and the configuration stays as it was.
  std::size_t made = 0;  // next.images[0, made) that are new exist
  auto undo = [&]() noexcept {
    for (std::size_t i = 0; i < made; ++i)
      if (isNew(next.images[i])) executor.destroyImage(next.images[i]);
  };
  try {
    for (; made < next.images.size(); ++made) {
      const PlannedImage& image = next.images[made];
      if (!isNew(image)) continue;
      if (Status st = executor.createImage(image); !st) {
        undo();
        return st;
      }
    }
    // Pipelines are a cache: those made stay made, whatever happens next.
    for (const PlannedPass& p : next.passes) {
      if (std::find(pipelines_.begin(), pipelines_.end(), p.variant) != pipelines_.end()) continue;
      if (Status st = executor.createPipeline(gen::pass(p.pass), *p.variant); !st) {
        undo();
        return st;
      }
      pipelines_.push_back(p.variant);
    }
    if (Status st = executor.preparePlan(next, schedule); !st) {
      undo();
      return st;
    }
  } catch (...) {
    undo();
    throw;
  }
  // Commit: the images the new plan drops or changes go; nothing below fails.
  if (configured_)
    for (const PlannedImage& image : plan_.images)
      if (!holdsImage(next, image)) executor.destroyImage(image);
  // A new configuration starts the history again (sao/temporal.h): render() makes one only when
  // the settings, the plan inputs or the camera's plan change.
  history_ = TemporalHistory{};
  block_ = configured;
  plan_ = std::move(next);
  schedule_ = std::move(schedule);
  settings_ = settings;
  camera_ = camera;
  inputs_ = inputs;
  configured_ = true;
  ranOnPlan_ = false;
  ++plans_;
  executor.planAdopted();
  return Status::success();
}

Status FrameState::run(const FrameInputs& frame, Executor& executor) {
  if (!configured_)
    return Status::error(StatusCode::InvalidInput, std::string(who_) + ": no configuration: configure() first");
  const Camera& camera = frame.camera ? *frame.camera : camera_;
  if (frame.camera && !(camera == camera_))
    if (Status st = checkCameraKeepsPlan(settings_, camera_, camera); !st)
      return Status::error(st.code, std::string(who_) + ": this frame's camera " + st.message);
  if (Status st = checkFrame(plan_, inputs_, frame); !st) return st;
  ParamBlock block{};  // block_ changes only for a frame that runs
  if (Status st = frameConstants(settings_, camera, inputs_, frame.values, block); !st) return st;
  // Without the temporal setting the history's inputs are ignored (sao/temporal.h).
  if (settings_.temporal)
    if (Status st = prepareTemporalFrame(history_, settings_, camera, frame.previousCamera, frame.resetHistory, block);
        !st)
      return st;
  block_ = block;

  lastWork_.plan = &plan_;
  lastWork_.schedule = &schedule_;
  lastWork_.block = &block_;
  lastWork_.historyParity = history_.parity;
  lastWork_.historyValid = block_.history_valid != 0;
  if (Status st = executor.beginFrame(lastWork_); !st) return st;
  walk(executor);
  if (Status st = executor.endFrame(); !st) return st;
  ranOnPlan_ = true;
  if (settings_.temporal) finishTemporalFrame(history_, settings_, camera);
  return Status::success();
}

void FrameState::continueHistory(const Camera& camera) {
  if (!configured_) return;
  history_.holdsFrame = true;
  history_.camera = camera;
  history_.settings = settings_;
}

Status FrameState::repeat(Executor& executor) {
  if (!configured_ || !ranOnPlan_)
    return Status::error(StatusCode::InvalidInput, std::string(who_) + ": no frame ran on this configuration");
  if (Status st = executor.beginFrame(lastWork_); !st) return st;
  walk(executor);
  return executor.endFrame();
}

void FrameState::walk(Executor& executor) {
  if (!schedule_.entryHazards().empty()) executor.barrier(schedule_.entryHazards());
  for (const ScheduledDispatch& d : schedule_.dispatches) {
    if (!schedule_.hazardsBefore(d).empty()) executor.barrier(schedule_.hazardsBefore(d));
    executor.dispatch(d, schedule_.bindingsOf(d));
  }
  if (!schedule_.exitHazards().empty()) executor.barrier(schedule_.exitHazards());
}

void FrameState::release(Executor& executor) noexcept {
  if (configured_)
    for (const PlannedImage& image : plan_.images) executor.destroyImage(image);
  configured_ = false;
  ranOnPlan_ = false;
  plan_ = Plan{};
  schedule_ = Schedule{};
  history_ = TemporalHistory{};
}

}  // namespace sao
