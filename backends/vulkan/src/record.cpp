// record() and measure(): the frame's configuration taken from the caller's images (each input's
// view, format and samples, the output), what only Vulkan can tell checked (layouts, the output's
// image and layer), then core's FrameState plans when it must and runs the frame through the
// Vulkan executor (executor.cpp) into the command buffer. Presence and extents against the plan are
// core's (sao::checkSupplied, in FrameState::render).
#include <string>

#include "effect_impl.h"
#include "sao/inputs.h"

namespace sao::vk {
namespace {

bool isLayoutAllowed(VkImageLayout l) {
  switch (l) {
    case VK_IMAGE_LAYOUT_GENERAL:
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL: return true;
    default: return false;
  }
}

// The Vulkan side of a given input: its declared extent and layout (a view tells neither).
Status checkInput(const InputImage& in, gen::ResourceId id, std::uint32_t maxSide) {
  // An extent beyond any image the device makes is a wrong declaration (and would let the offset
  // overflow the shader's int).
  if (in.extent.width > maxSide || in.extent.height > maxSide)
    return Status::error(StatusCode::InvalidInput, inputName(id) + ".extent " + std::to_string(in.extent.width) + "x" +
                                                       std::to_string(in.extent.height) +
                                                       " exceeds this device's maxImageDimension2D " +
                                                       std::to_string(maxSide));
  if (!isLayoutAllowed(in.layout))
    return Status::error(StatusCode::InvalidInput,
                         inputName(id) + ".layout " + std::to_string(in.layout) +
                             " is not a layout a sampled read may use (SHADER_READ_ONLY_OPTIMAL, "
                             "DEPTH_STENCIL_READ_ONLY_OPTIMAL, DEPTH_READ_ONLY_OPTIMAL, GENERAL, ...)");
  return Status::success();
}

// The frame's configuration: each given input's format (required with a view) and the depth's
// samples, the output's kind and format.
Status frameConfigOf(const EffectState& e, const Inputs& in, const OutputImage* userOutput, FrameConfig& out) {
  for (const gen::ResourceId id : gen::kInputIds) {
    const InputImage& image = in[id];
    if (image.view == VK_NULL_HANDLE) {
      if (isRequiredInput(id))
        return Status::error(StatusCode::InvalidInput, "record(): " + inputName(id) + ".view is VK_NULL_HANDLE");
      out.formats[id] = VK_FORMAT_UNDEFINED;
      continue;
    }
    if (image.format == VK_FORMAT_UNDEFINED)
      return Status::error(StatusCode::InvalidInput, "record(): " + inputName(id) +
                                                         ".format is VK_FORMAT_UNDEFINED: name the view's format");
    if (image.samples != VK_SAMPLE_COUNT_1_BIT && !mayBeMultisampled(id))
      return Status::error(StatusCode::InvalidInput, "record(): " + inputName(id) + ".samples is " +
                                                         std::to_string(image.samples) +
                                                         ": only the depth may be multisampled");
    out.formats[id] = image.format;
  }
  out.depthSamples = in.depth.samples;
  out.userOutput = userOutput != nullptr;
  out.outputFormat = userOutput ? userOutput->format : e.config.outputFormat;
  return Status::success();
}

// The caller's output, what the plan cannot tell: its handles, its layout when its texels are
// kept, its layer, that no input is it; the effect's own is resolved by the executor.
Status checkOutput(const EffectState& e, const Inputs& in, const OutputImage* userOutput, const FrameConfig& fc,
                   OutputTarget& out) {
  out = {};
  if (!userOutput) return Status::success();
  if (userOutput->image == VK_NULL_HANDLE || userOutput->view == VK_NULL_HANDLE)
    return Status::error(StatusCode::InvalidInput, "the output image or its view is VK_NULL_HANDLE");
  const bool keep = keepsChannels(outputFormatOf(fc.outputFormat), in.outputChannels, in.outputBlend);
  if (keep && (userOutput->layout == VK_IMAGE_LAYOUT_UNDEFINED || userOutput->layout == VK_IMAGE_LAYOUT_PREINITIALIZED)) {
    // A mask or blend the output cannot take is named as such (core's checks), not as a layout.
    if (Status st = checkOutputChannels(outputFormatOf(fc.outputFormat), in.outputChannels, kRecordInputs); !st)
      return st;
    if (Status st = checkOutputBlend(in.outputBlend, true, kRecordInputs); !st) return st;
    return Status::error(StatusCode::InvalidInput,
                         std::string(in.outputBlend == OutputBlend::Multiply ? "Inputs::outputBlend is multiply"
                                                                             : "Inputs::outputChannels keeps channels of the output") +
                             ", but OutputImage::layout is " + std::to_string(userOutput->layout) +
                             "; give the layout your image is in when the commands run (its texels are kept)");
  }
  for (const gen::ResourceId id : gen::kInputIds)
    if (in[id].view != VK_NULL_HANDLE && in[id].view == userOutput->view)
      return Status::error(StatusCode::InvalidInput,
                           "the output view is also " + inputName(id) + ".view; the output must be a separate image");
  // The layer cannot be checked against the image (Vulkan cannot tell its layer count); beyond the
  // device's limit it cannot be one.
  if (userOutput->layer >= e.props.limits.maxImageArrayLayers)
    return Status::error(StatusCode::InvalidInput, "OutputImage::layer " + std::to_string(userOutput->layer) +
                                                       " exceeds this device's maxImageArrayLayers " +
                                                       std::to_string(e.props.limits.maxImageArrayLayers));
  out = {userOutput->image, userOutput->view, keep ? userOutput->layout : VK_IMAGE_LAYOUT_UNDEFINED, userOutput->layer};
  return Status::success();
}

}  // namespace

Status runFrame(EffectState& e, const Camera& camera, const Settings& settings, const Inputs& inputs,
                const OutputImage* userOutput, Recording rec) {
  FrameConfig next;
  if (Status st = frameConfigOf(e, inputs, userOutput, next); !st) return st;
  PlanInputs planInputs = e.frame.planInputs();
  if (!e.frame.configured() || !(next == e.current)) {
    if (Status st = checkFrameConfig(e, next, camera, planInputs); !st) return st;
  } else if (Status st = checkColourInputs(next.formats, camera); !st) {
    return st;  // the camera's normals encoding against the same formats
  }
  const std::uint32_t maxSide = e.props.limits.maxImageDimension2D;
  for (const gen::ResourceId id : gen::kInputIds)
    if (inputs[id].view != VK_NULL_HANDLE)
      if (Status st = checkInput(inputs[id], id, maxSide); !st) return st;
  if (Status st = checkOutput(e, inputs, userOutput, next, rec.output); !st) return st;

  SuppliedImages supplied{};
  for (const gen::ResourceId id : gen::kInputIds)
    supplied[static_cast<std::size_t>(id)] = {inputs[id].view != VK_NULL_HANDLE, inputs[id].extent, inputs.region};
  if (userOutput) supplied[static_cast<std::size_t>(gen::ResourceId::ao)] = {true, userOutput->extent, {}};
  FrameInputs frame;
  frame.previousCamera = inputs.previousCamera;
  frame.resetHistory = inputs.resetHistory;
  // checkSupplied puts the offset inside the images, whose sides are at most maxImageDimension2D,
  // so it fits the shaders' int.
  frame.values = {inputs.region.value_or(Offset{}), inputs.frameIndex, inputs.outputChannels, inputs.outputBlend};
  frame.images = &supplied;

  // FrameState checks the frame before the executor records its first command: a failure records
  // nothing. A new plan may come while records are pending: what it drops waits for them.
  rec.inputs = &inputs;
  e.executor.setRecording(rec);
  if (e.frame.configured()) e.executor.retireUntil(e.records + e.config.framesInFlight - 1);
  const Status st = e.frame.render(settings, camera, planInputs, frame, e.executor);
  e.executor.retireUntil(std::nullopt);
  if (e.frame.configured() && e.frame.planInputs() == planInputs) e.current = next;
  return st;
}

Status Effect::record(VkCommandBuffer cmd, const Camera& camera, const Settings& settings, const Inputs& inputs,
                      const OutputImage* userOutput) {
  return guarded("sao::vk::Effect::record()", [&] {
    EffectState& e = *impl_;
    if (cmd == VK_NULL_HANDLE)
      return Status::error(StatusCode::InvalidInput, "record(): the command buffer is VK_NULL_HANDLE");
    const int region = e.config.timestamps && e.queryPool ? static_cast<int>(e.nextSlot) : -1;
    if (Status st = runFrame(e, camera, settings, inputs, userOutput, {cmd, nullptr, {}, region}); !st) return st;
    if (region >= 0) e.lastTimedRegion = region;
    return Status::success();
  });
}

}  // namespace sao::vk
