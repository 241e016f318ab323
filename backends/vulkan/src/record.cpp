// Recording: the schedule (sao/schedule.h) translated into commands and barriers.
//
// Barriers (all VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT unless named):
//  entry     each image the frame writes: UNDEFINED -> GENERAL (its contents are rewritten every
//            frame) after the previous frame's compute reads and writes, and for the output after
//            Config::outputDstStages (where the previous result was read); an output whose
//            channels Inputs::outputChannels keeps goes from OutputImage::layout instead. Inputs the caller wrote
//            are the caller's to synchronise (their layouts and barriers come with Inputs).
// The parameter block is not a device write: record() copies it into its ring slot's region of
// mapped host-coherent memory, which vkQueueSubmit makes visible (no barrier).
//  hazards   before a dispatch, one image barrier per hazard the schedule lists: a write then a
//            sampled read (SHADER_WRITE -> SHADER_READ), a read then a write (execution only), two
//            writes (SHADER_WRITE -> SHADER_WRITE), on exactly the levels concerned.
//  exit      the output GENERAL -> Config::outputLayout, SHADER_WRITE -> outputDstStages/Access.
// Barriers on the caller's output cover its layer OutputImage::layer only: the other layers of an
// array may belong to another record of the same command buffer (stereo, one layer per eye). The
// entry barriers of a second record in one command buffer order its writes of the shared
// intermediates after the first record's reads and writes, as between frames.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <string>

#include "effect_impl.h"

namespace sao::vk {
namespace {

// vkCmdPushConstants reads pushConstantBytes from the generated mirror of the shaders' block.
static_assert(sizeof(gen::PushConstants) >= gen::kPushConstantBytes);

// `layer`: the array layer; the caller's output may be one layer of an array (OutputImage::layer),
// the effect's own images have one.
VkImageMemoryBarrier imageBarrier(VkImage image, std::uint32_t layer, VkImageLayout from, VkImageLayout to,
                                  VkAccessFlags src, VkAccessFlags dst, std::uint32_t baseLevel, std::uint32_t levels) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src;
  b.dstAccessMask = dst;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, baseLevel, levels, layer, 1};
  return b;
}

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
Status checkInput(const InputImage& in, const char* name, VkFormat format, std::uint32_t maxSide) {
  if (in.view == VK_NULL_HANDLE) return Status::success();
  // A view cannot tell its size: an extent beyond any image the device makes is a wrong
  // declaration (and would let the offset overflow the shader's int).
  if (in.extent.width > maxSide || in.extent.height > maxSide)
    return Status::error(StatusCode::InvalidInput, std::string("Inputs::") + name + ".extent " +
                                                       std::to_string(in.extent.width) + "x" +
                                                       std::to_string(in.extent.height) +
                                                       " exceeds this device's maxImageDimension2D " +
                                                       std::to_string(maxSide));
  if (in.format != VK_FORMAT_UNDEFINED && in.format != format)
    return Status::error(StatusCode::InvalidInput, std::string("Inputs::") + name + ".format " +
                                                       std::to_string(in.format) + " is not the format Config names (" +
                                                       std::to_string(format) + ")");
  if (!isLayoutAllowed(in.layout))
    return Status::error(StatusCode::InvalidInput,
                         std::string("Inputs::") + name + ".layout " + std::to_string(in.layout) +
                             " is not a layout a sampled read may use (SHADER_READ_ONLY_OPTIMAL, "
                             "DEPTH_STENCIL_READ_ONLY_OPTIMAL, DEPTH_READ_ONLY_OPTIMAL, GENERAL, ...)");
  return Status::success();
}

// Image barriers gathered on the stack (recording allocates nothing), issued as one
// vkCmdPipelineBarrier per batch: when full (never with the effect's few images) and at the end.
class BarrierBatch {
 public:
  BarrierBatch(const EffectState& e, VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst) noexcept
      : e_(e), cmd_(cmd), src_(src), dst_(dst) {}
  ~BarrierBatch() { flush(); }
  BarrierBatch(const BarrierBatch&) = delete;
  BarrierBatch& operator=(const BarrierBatch&) = delete;
  void add(const VkImageMemoryBarrier& b) noexcept {
    if (count_ == list_.size()) flush();
    list_[count_++] = b;
  }
  void flush() noexcept {
    if (count_) e_.d.vkCmdPipelineBarrier(cmd_, src_, dst_, 0, 0, nullptr, 0, nullptr, count_, list_.data());
    count_ = 0;
  }

 private:
  const EffectState& e_;
  VkCommandBuffer cmd_;
  VkPipelineStageFlags src_, dst_;
  std::array<VkImageMemoryBarrier, 16> list_;
  std::uint32_t count_ = 0;
};

}  // namespace

Status checkInputs(const EffectState& e, const Inputs& in, const OutputImage* userOutput, OutputTarget& out) {
  const Config& c = e.config;
  SuppliedImages supplied{};
  auto add = [&](gen::ResourceId id, VkImageView view, Extent extent, std::optional<Offset> region) {
    supplied[static_cast<std::size_t>(id)] = {view != VK_NULL_HANDLE, extent, region};
  };
  add(gen::ResourceId::depth, in.depth.view, in.depth.extent, in.region);
  add(gen::ResourceId::depth2, in.depth2.view, in.depth2.extent, in.region);
  add(gen::ResourceId::normals, in.normals.view, in.normals.extent, in.region);
  add(gen::ResourceId::motion, in.motion.view, in.motion.extent, in.region);
  if (userOutput) add(gen::ResourceId::ao, userOutput->view, userOutput->extent, {});
  if (userOutput && (userOutput->image == VK_NULL_HANDLE || userOutput->view == VK_NULL_HANDLE))
    return Status::error(StatusCode::InvalidInput, "the output image or its view is VK_NULL_HANDLE");
  if (userOutput && !c.userOutput)
    return Status::error(StatusCode::InvalidInput,
                         "record() got an output image but Config::userOutput is false (the effect owns its output)");
  if (Status st = checkSupplied(e.plan, supplied, c.userOutput, "sao::vk::Effect::record()"); !st) return st;
  const std::uint32_t maxSide = e.props.limits.maxImageDimension2D;
  if (Status st = checkInput(in.depth, "depth", c.depthFormat, maxSide); !st) return st;
  if (Status st = checkInput(in.depth2, "depth2", c.depthFormat, maxSide); !st) return st;
  if (Status st = checkInput(in.normals, "normals", c.normalsFormat, maxSide); !st) return st;
  if (Status st = checkInput(in.motion, "motion", c.motionFormat, maxSide); !st) return st;
  const FrameValues frame{{}, 0, in.outputChannels, in.outputBlend};
  if (Status st = checkFrameOutput(e.plan, e.planInputs, frame, "sao::vk::Effect::record() Inputs"); !st) return st;
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
  if (keep && (userOutput->layout == VK_IMAGE_LAYOUT_UNDEFINED || userOutput->layout == VK_IMAGE_LAYOUT_PREINITIALIZED))
    return Status::error(StatusCode::InvalidInput,
                         std::string(in.outputBlend == OutputBlend::Multiply ? "Inputs::outputBlend is multiply"
                                                                             : "Inputs::outputChannels keeps channels of the output") +
                             ", but OutputImage::layout is " +
                             std::to_string(userOutput->layout) +
                             "; give the layout your image is in when the commands run (its texels are kept)");
  for (const auto& [input, name] : {std::pair{in.depth.view, "depth"}, std::pair{in.depth2.view, "depth2"},
                                     std::pair{in.normals.view, "normals"}, std::pair{in.motion.view, "motion"}})
    if (input != VK_NULL_HANDLE && input == userOutput->view)
      return Status::error(StatusCode::InvalidInput, std::string("the output view is also Inputs::") + name +
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

std::uint32_t acquireSlot(EffectState& e, const Inputs& in, const OutputTarget& output, ParamBlock* cameraBlock) {
  const std::uint32_t slot = e.nextSlot;
  e.nextSlot = (slot + 1) % e.config.framesInFlight;
  // Always rewritten: a caller may destroy a view and create another that gets the same handle
  // value, so comparing handles cannot tell whether a set is still valid (lavapipe crashed on the
  // stale set). The slot's previous command buffer has completed (the ring contract), and a few
  // dozen descriptor writes per record cost next to nothing.
  writeDescriptors(e, slot, in, output);
  // The region's offset and the frame index are per record (checkInputs put the offset inside the
  // textures, whose sides are at most maxImageDimension2D, so it fits the shader's int). params()
  // shows the last record's; Inputs::camera's block goes into this slot only.
  const FrameValues frame{in.region.value_or(Offset{}), in.frameIndex, in.outputChannels, in.outputBlend};
  completeFrame(e.params, e.planInputs, frame);
  ParamBlock* block = &e.params;
  if (cameraBlock) {
    completeFrame(*cameraBlock, e.planInputs, frame);
    block = cameraBlock;
  }
  // The slot's copy of the parameter block (its previous command buffer has completed: the ring
  // contract), written only when it changed.
  if (!e.ubo.valid[slot] || std::memcmp(&e.ubo.written[slot], block, sizeof(ParamBlock)) != 0) {
    std::memcpy(e.ubo.mapped + slot * e.ubo.stride, block, sizeof(ParamBlock));
    e.ubo.written[slot] = *block;
    e.ubo.valid[slot] = true;
  }
  return slot;
}

namespace {

// The image (and array layer) behind a resource this frame: owned (layer 0), or the caller's output.
struct Target {
  VkImage image = VK_NULL_HANDLE;
  std::uint32_t layer = 0;
};
Target imageOf(const EffectState& e, gen::ResourceId id, const OutputTarget& output, bool previousFrame = false) {
  if (const OwnedImage* img = e.res.find(id, imageCopy(e.temporal.parity, id, previousFrame))) return {img->image.get(), 0};
  if (gen::kResources[static_cast<std::size_t>(id)].kind == gen::ResourceKind::Output) return {output.image, output.layer};
  return {};
}

VkImageMemoryBarrier hazardBarrier(Target t, const Hazard& h) {
  VkAccessFlags src = VK_ACCESS_SHADER_WRITE_BIT, dst = VK_ACCESS_SHADER_WRITE_BIT;
  if (h.kind == HazardKind::ReadAfterWrite) dst = VK_ACCESS_SHADER_READ_BIT;
  if (h.kind == HazardKind::WriteAfterRead) src = 0;  // an execution dependency is enough
  return imageBarrier(t.image, t.layer, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL, src, dst, h.baseLevel,
                      h.levelCount);
}

}  // namespace

void recordPrologue(const EffectState& e, VkCommandBuffer cmd, const OutputTarget& output, int timingRegion) noexcept {
  const VkQueryPool queries = e.queryPool.get();
  if (timingRegion >= 0)
    e.d.vkCmdResetQueryPool(cmd, queries, static_cast<std::uint32_t>(timingRegion) * queriesPerRegion(),
                            queriesPerRegion());
  {
    BarrierBatch images(e, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | e.config.outputDstStages,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
    for (const Hazard& h : e.schedule.entryHazards()) {
      if (h.kind == HazardKind::CallerWrote) continue;  // the caller's barrier (see above)
      const Target t = imageOf(e, h.resource, output, h.previousFrame);
      if (h.previousFrame) {  // the history the frame before wrote: kept when this frame reads it
        images.add(imageBarrier(t.image, t.layer, e.historyValid ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_GENERAL, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                                h.baseLevel, h.levelCount));
        continue;
      }
      const bool isOutput = t.image == output.image;
      // The output's kept channels are read by the final pass: its contents must survive.
      const VkImageLayout from = isOutput ? output.keepFrom : VK_IMAGE_LAYOUT_UNDEFINED;
      images.add(imageBarrier(t.image, t.layer, from, VK_IMAGE_LAYOUT_GENERAL, VK_ACCESS_SHADER_WRITE_BIT,
                              isOutput && from == VK_IMAGE_LAYOUT_UNDEFINED
                                  ? VK_ACCESS_SHADER_WRITE_BIT
                                  : VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                              h.baseLevel, h.levelCount));
    }
  }
  if (timingRegion >= 0)
    e.d.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries,
                            static_cast<std::uint32_t>(timingRegion) * queriesPerRegion());
}

void recordDispatches(const EffectState& e, VkCommandBuffer cmd, std::uint32_t slot, const OutputTarget& output,
                      int timingRegion, int onlyPass) noexcept {
  const auto& dispatches = e.schedule.dispatches;
  const PipelineEntry* pipe = nullptr;
  for (std::uint32_t k = 0; k < dispatches.size(); ++k) {
    const ScheduledDispatch& d = dispatches[k];
    if (onlyPass >= 0 && d.passIndex != static_cast<std::uint32_t>(onlyPass)) continue;
    const bool firstOfPass = k == 0 || dispatches[k - 1].passIndex != d.passIndex;
    const bool lastOfPass = k + 1 == dispatches.size() || dispatches[k + 1].passIndex != d.passIndex;
    if (firstOfPass) {
      if (e.d.vkCmdBeginDebugUtilsLabelEXT) {
        const std::string_view name = gen::pass(d.pass).name;
        char label[64];
        std::snprintf(label, sizeof label, "sao %.*s", static_cast<int>(name.size()), name.data());
        VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT, nullptr, label, {0.4f, 0.6f, 0.9f, 1.0f}};
        e.d.vkCmdBeginDebugUtilsLabelEXT(cmd, &l);
      }
      pipe = findPipeline(e, d.variant);
      e.d.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->pipeline.get());
      if (d.variant->pushConstantBytes > 0) {
        const gen::PushConstants constants = gen::pushConstantsOf(e.params);
        e.d.vkCmdPushConstants(cmd, pipe->layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, d.variant->pushConstantBytes,
                               &constants);
      }
    }
    {
      BarrierBatch hazards(e, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
      for (const Hazard& h : e.schedule.hazardsBefore(d))
        if (const Target t = imageOf(e, h.resource, output, h.previousFrame); t.image) hazards.add(hazardBarrier(t, h));
    }
    e.d.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->layout.get(), 0, 1,
                                &e.desc.sets[slot * e.desc.setsPerSlot + k], 0, nullptr);
    e.d.vkCmdDispatch(cmd, d.groupsX, d.groupsY, 1);
    if (lastOfPass) {
      if (timingRegion >= 0)
        e.d.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, e.queryPool.get(),
                                static_cast<std::uint32_t>(timingRegion) * queriesPerRegion() + 1 + d.passIndex);
      if (e.d.vkCmdEndDebugUtilsLabelEXT) e.d.vkCmdEndDebugUtilsLabelEXT(cmd);
    }
  }
}

void recordEpilogue(const EffectState& e, VkCommandBuffer cmd, const OutputTarget& output) noexcept {
  for (const Hazard& h : e.schedule.exitHazards()) {
    const Target t = imageOf(e, h.resource, output);
    const VkImageMemoryBarrier b = imageBarrier(t.image, t.layer, VK_IMAGE_LAYOUT_GENERAL, e.config.outputLayout,
                                                VK_ACCESS_SHADER_WRITE_BIT, e.config.outputDstAccess, h.baseLevel,
                                                h.levelCount);
    e.d.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, e.config.outputDstStages, 0, 0, nullptr, 0,
                             nullptr, 1, &b);
  }
}

Status Effect::record(VkCommandBuffer cmd, const Inputs& inputs, const OutputImage* userOutput) {
  return guarded("sao::vk::Effect::record()", [&] {
    EffectState& e = *impl_;
    if (cmd == VK_NULL_HANDLE)
      return Status::error(StatusCode::InvalidInput, "record(): the command buffer is VK_NULL_HANDLE");
    OutputTarget output;
    if (Status st = checkInputs(e, inputs, userOutput, output); !st) return st;
    ParamBlock recordBlock{};
    bool ownBlock = false;
    if (Status st = recordParams(e, inputs, recordBlock, ownBlock); !st) return st;
    // The only step that allocates, before the first command: a failure records nothing.
    const std::uint32_t slot = acquireSlot(e, inputs, output, ownBlock ? &recordBlock : nullptr);
    const int region = e.config.timestamps && e.queryPool ? static_cast<int>(slot) : -1;
    recordPrologue(e, cmd, output, region);
    recordDispatches(e, cmd, slot, output, region);
    recordEpilogue(e, cmd, output);
    recordDone(e, inputs);
    if (region >= 0) e.lastTimedRegion = region;
    return Status::success();
  });
}

}  // namespace sao::vk
