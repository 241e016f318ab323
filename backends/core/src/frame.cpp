#include "sao/frame.h"

#include <string>

#include "sao/output.h"

namespace sao {
namespace {

// Where a camera meets the plan: its extents and its csz levels (plan() reads nothing else of it).
struct CameraPlanKey {
  std::uint32_t width = 0, height = 0, guardBand = 0, cszLevels = 0;
  bool operator==(const CameraPlanKey&) const = default;
};

Status planKey(const Settings& settings, const Camera& camera, CameraPlanKey& out) {
  DepthModel model;
  if (Status st = analyze(camera, model); !st) return st;
  out = {camera.width, camera.height, camera.guardBand, mipLevelsNeeded(settings, camera, model)};
  return Status::success();
}

}  // namespace

void completeFrame(ParamBlock& block, const PlanInputs& inputs, const FrameValues& frame) {
  block.input_offset = {static_cast<std::int32_t>(frame.inputOffset.x), static_cast<std::int32_t>(frame.inputOffset.y)};
  block.output_mask = outputMaskParam(frame.outputChannels);
  block.output_blend = static_cast<std::int32_t>(frame.outputBlend);
  block.depth_samples = static_cast<std::int32_t>(inputs.depthSamples);  // DEPTH_MULTISAMPLE's sample count
  setFrameIndex(block, frame.frameIndex);
}

Status checkFrameOutput(const Plan& plan, const PlanInputs& inputs, const FrameValues& frame, const char* who) {
  if (Status st = checkOutputChannels(inputs.outputFormat, frame.outputChannels, who); !st) return st;
  if (Status st = checkOutputBlend(frame.outputBlend, inputs.userOutput, who); !st) return st;
  // BENT_NORMALS stores (bent normal, A) into all four channels: a mask that keeps some, or the
  // multiply blend, would leave a texel half bent normal, half the caller's.
  if (plan.variants[static_cast<std::size_t>(gen::VariantId::BENT_NORMALS)] != 0 &&
      keepsChannels(inputs.outputFormat, frame.outputChannels, frame.outputBlend))
    return Status::error(StatusCode::InvalidInput,
                         std::string(who) + ": bent_normals writes the bent normal into R, G, B and A into A of every "
                                            "output texel: it needs the output channel mask kAllChannels (15, got " +
                             std::to_string(frame.outputChannels) + ") and output blend replace (got " +
                             toString(frame.outputBlend) + ")");
  if (!inputs.userOutput && keepsChannels(inputs.outputFormat, frame.outputChannels))
    return Status::error(StatusCode::InvalidInput,
                         std::string(who) + ": the output channel mask " + std::to_string(frame.outputChannels) +
                             " keeps channels of the output, which only your own image has: give your own output "
                             "or use kAllChannels");
  return Status::success();
}

Status frameConstants(const Settings& settings, const Camera& camera, const PlanInputs& inputs,
                      const FrameValues& frame, ParamBlock& out) {
  if (Status st = computeConstants(settings, camera, inputs.depthEncoding, out); !st) return st;
  completeFrame(out, inputs, frame);
  return Status::success();
}

Status checkCameraKeepsPlan(const Settings& settings, const Camera& planned, const Camera& next) {
  CameraPlanKey a, b;
  if (Status st = planKey(settings, next, b); !st) return st;
  if (Status st = planKey(settings, planned, a); !st)
    return Status::error(StatusCode::InvalidInput, "the planned camera is invalid: " + st.message);
  if (a.width != b.width || a.height != b.height || a.guardBand != b.guardBand) {
    auto size = [](const CameraPlanKey& k) {
      return std::to_string(k.width) + "x" + std::to_string(k.height) + " with guard band " + std::to_string(k.guardBand);
    };
    return Status::error(StatusCode::InvalidInput, "is " + size(b) + " but the plan's camera is " + size(a) +
                                                       ": a new size or guard band changes every image");
  }
  if (a.cszLevels != b.cszLevels)
    return Status::error(StatusCode::InvalidInput,
                         "needs " + std::to_string(b.cszLevels) + " csz MIP levels but the plan has " +
                             std::to_string(a.cszLevels) +
                             " (the largest projected radius, from the projection scale, near distance, projection "
                             "kind and metersToViewUnits, selects them): this camera changes the plan");
  return Status::success();
}

bool cameraKeepsPlan(const Settings& settings, const Camera& planned, const Camera& next) {
  CameraPlanKey a, b;
  return planKey(settings, planned, a) && planKey(settings, next, b) && a == b;
}

}  // namespace sao
