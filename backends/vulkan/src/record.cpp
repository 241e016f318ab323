// record(): the caller's images checked against the configuration (sao::checkSupplied for their
// presence and extents, then what only Vulkan can tell: formats, layouts, the output's image), then
// the frame run by core's FrameState through the Vulkan executor (executor.cpp) into the caller's
// command buffer.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <string>

#include "effect_impl.h"

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

// The Vulkan side of an input the plan reads (presence and extent: sao::checkSupplied).
Status checkInput(const InputImage& in, std::string_view name, VkFormat format, std::uint32_t maxSide) {
  if (in.view == VK_NULL_HANDLE) return Status::success();
  // A view cannot tell its size: an extent beyond any image the device makes is a wrong
  // declaration (and would let the offset overflow the shader's int).
  if (in.extent.width > maxSide || in.extent.height > maxSide)
    return Status::error(StatusCode::InvalidInput, "Inputs::" + std::string(name) + ".extent " +
                                                       std::to_string(in.extent.width) + "x" +
                                                       std::to_string(in.extent.height) +
                                                       " exceeds this device's maxImageDimension2D " +
                                                       std::to_string(maxSide));
  if (in.format != VK_FORMAT_UNDEFINED && in.format != format)
    return Status::error(StatusCode::InvalidInput, "Inputs::" + std::string(name) + ".format " +
                                                       std::to_string(in.format) + " is not the format Config names (" +
                                                       std::to_string(format) + ")");
  if (!isLayoutAllowed(in.layout))
    return Status::error(StatusCode::InvalidInput,
                         "Inputs::" + std::string(name) + ".layout " + std::to_string(in.layout) +
                             " is not a layout a sampled read may use (SHADER_READ_ONLY_OPTIMAL, "
                             "DEPTH_STENCIL_READ_ONLY_OPTIMAL, DEPTH_READ_ONLY_OPTIMAL, GENERAL, ...)");
  return Status::success();
}

Status checkInputs(const EffectState& e, const Inputs& in, const OutputImage* userOutput, OutputTarget& out) {
  const Config& c = e.config;
  SuppliedImages supplied{};
  for (const gen::ResourceId id : gen::kInputIds)
    supplied[static_cast<std::size_t>(id)] = {in[id].view != VK_NULL_HANDLE, in[id].extent, in.region};
  if (userOutput) supplied[static_cast<std::size_t>(gen::ResourceId::ao)] = {userOutput->view != VK_NULL_HANDLE, userOutput->extent, {}};
  if (userOutput && (userOutput->image == VK_NULL_HANDLE || userOutput->view == VK_NULL_HANDLE))
    return Status::error(StatusCode::InvalidInput, "the output image or its view is VK_NULL_HANDLE");
  if (userOutput && !c.userOutput)
    return Status::error(StatusCode::InvalidInput,
                         "record() got an output image but Config::userOutput is false (the effect owns its output)");
  if (Status st = checkSupplied(e.plan(), supplied, c.userOutput, "sao::vk::Effect::record()"); !st) return st;
  const std::uint32_t maxSide = e.props.limits.maxImageDimension2D;
  for (const gen::ResourceId id : gen::kInputIds)
    if (Status st = checkInput(in[id], gen::kResources[static_cast<std::size_t>(id)].name, e.inputFormats[id], maxSide);
        !st)
      return st;
  // The output's mask and blend: FrameState::run (checkFrameOutput), before anything is recorded.
  if (!c.userOutput) {
    const OwnedImage* ao = e.res.find(gen::ResourceId::ao);
    out = {ao->image.get(), ao->levelViews[0].get()};
    return Status::success();
  }
  if (userOutput->format != c.outputFormat) {
    const gen::Format f = outputFormatOf(userOutput->format);
    return Status::error(StatusCode::UnsupportedFormat,
                         "the output is VkFormat " + std::to_string(userOutput->format) +
                             (isOutputFormat(f) ? std::string(" (") + sao::formatName(f) + ")" : std::string()) +
                             " but Config::outputFormat is " + std::to_string(c.outputFormat) +
                             "; the effect writes VK_FORMAT_R16_SFLOAT, R8_UNORM, R8G8B8A8_UNORM or "
                             "R16G16B16A16_SFLOAT, the one Config names (its pipelines are built for it)");
  }
  const bool keep = keepsChannels(outputFormatOf(c.outputFormat), in.outputChannels, in.outputBlend);
  if (keep && (userOutput->layout == VK_IMAGE_LAYOUT_UNDEFINED || userOutput->layout == VK_IMAGE_LAYOUT_PREINITIALIZED)) {
    // A mask or blend the output cannot take is named as such (FrameState's check), not as a layout.
    if (Status st = checkFrameOutput(e.plan(), e.frame.planInputs(), frameInputsOf(in).values, kRecordInputs); !st)
      return st;
    return Status::error(StatusCode::InvalidInput,
                         std::string(in.outputBlend == OutputBlend::Multiply ? "Inputs::outputBlend is multiply"
                                                                             : "Inputs::outputChannels keeps channels of the output") +
                             ", but OutputImage::layout is " +
                             std::to_string(userOutput->layout) +
                             "; give the layout your image is in when the commands run (its texels are kept)");
  }
  for (const gen::ResourceId id : gen::kInputIds)
    if (in[id].view != VK_NULL_HANDLE && in[id].view == userOutput->view)
      return Status::error(StatusCode::InvalidInput,
                           "the output view is also Inputs::" + std::string(gen::kResources[static_cast<std::size_t>(id)].name) +
                               ".view; the output must be a separate image");
  // The layer cannot be checked against the image (Vulkan cannot tell its layer count); beyond the
  // device's limit it cannot be one.
  if (userOutput->layer >= e.props.limits.maxImageArrayLayers)
    return Status::error(StatusCode::InvalidInput, "OutputImage::layer " + std::to_string(userOutput->layer) +
                                                       " exceeds this device's maxImageArrayLayers " +
                                                       std::to_string(e.props.limits.maxImageArrayLayers));
  out = {userOutput->image, userOutput->view, keep ? userOutput->layout : VK_IMAGE_LAYOUT_UNDEFINED, userOutput->layer};
  return Status::success();
}

// Inputs::camera against Config's: create()'s checks and messages, and core's rule for a camera
// that keeps the plan, named as record()'s. Allocates nothing on success.
Status checkRecordCamera(const EffectState& e, const Camera& camera) {
  const Config& c = e.config;
  // Messages are built only on the error paths.
  auto invalid = [](Status st) { return Status::error(st.code, "record(): Inputs::camera: " + st.message); };
  ParamBlock block{};  // computeConstants' checks of the camera, create()'s messages
  if (Status st = computeConstants(c.settings, camera, e.frame.planInputs().depthEncoding, block); !st)
    return invalid(st);
  if (Status st = checkColourInputs(e.inputFormats, camera); !st) return invalid(st);
  if (Status st = checkCameraKeepsPlan(c.settings, c.camera, camera); !st)
    return Status::error(st.code, "record(): Inputs::camera " + st.message + "; the plan is Config::camera's: call update()");
  return Status::success();
}

}  // namespace

FrameInputs frameInputsOf(const Inputs& in) {
  FrameInputs f;
  f.camera = in.camera;
  f.previousCamera = in.previousCamera;
  f.resetHistory = in.resetHistory;
  // checkInputs put the offset inside the images, whose sides are at most maxImageDimension2D, so
  // it fits the shaders' int.
  f.values = {in.region.value_or(Offset{}), in.frameIndex, in.outputChannels, in.outputBlend};
  return f;
}

Status checkFrame(const EffectState& e, const char* call, const Inputs& inputs, const OutputImage* userOutput,
                  OutputTarget& output) {
  if (!e.frame.configured())
    return Status::error(StatusCode::InvalidInput,
                         std::string(call) + ": nothing is planned yet (create() had no Config::camera): record with "
                                             "the frame's camera and settings, record(cmd, camera, settings, inputs), "
                                             "or call update() first");
  if (Status st = checkInputs(e, inputs, userOutput, output); !st) return st;
  return inputs.camera ? checkRecordCamera(e, *inputs.camera) : Status::success();
}

Status recordFrame(EffectState& e, VkCommandBuffer cmd, const Inputs& inputs, const OutputImage* userOutput) {
  if (cmd == VK_NULL_HANDLE)
    return Status::error(StatusCode::InvalidInput, "record(): the command buffer is VK_NULL_HANDLE");
  OutputTarget output;
  if (Status st = checkFrame(e, "record()", inputs, userOutput, output); !st) return st;
  const int region = e.config.timestamps && e.queryPool ? static_cast<int>(e.nextSlot) : -1;
  // FrameState checks the frame before the executor records its first command: a failure records nothing.
  e.executor.setRecording({cmd, &inputs, output, region});
  if (Status st = e.frame.run(frameInputsOf(inputs), e.executor); !st) return st;
  if (region >= 0) e.lastTimedRegion = region;
  return Status::success();
}

Status Effect::record(VkCommandBuffer cmd, const Inputs& inputs, const OutputImage* userOutput) {
  return guarded("sao::vk::Effect::record()", [&] { return recordFrame(*impl_, cmd, inputs, userOutput); });
}

}  // namespace sao::vk
