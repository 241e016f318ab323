// Recording: the parameter block, every planned pass and the barriers between them.
//
// Barriers (all VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT unless named):
//  prologue  intermediates UNDEFINED -> GENERAL (their contents are rewritten every frame), after
//            the previous frame's compute reads and writes; the output UNDEFINED -> GENERAL after
//            Config::outputDstStages (where the previous result was read).
// The parameter block is not a device write: record() copies it into its ring slot's region of
// mapped host-coherent memory, which vkQueueSubmit makes visible (no barrier).
//  dispatch  after each dispatch, the level it wrote: SHADER_WRITE -> SHADER_READ (the next mips
//            level, and the passes that read csz, ao_raw, ao_blur_h).
//  epilogue  output GENERAL -> Config::outputLayout, SHADER_WRITE -> outputDstStages/Access.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <string>

#include "effect_impl.h"

namespace sao::vk {
namespace {

VkImageMemoryBarrier imageBarrier(VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags src,
                                  VkAccessFlags dst, std::uint32_t baseLevel, std::uint32_t levels) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = src;
  b.dstAccessMask = dst;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, baseLevel, levels, 0, 1};
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

std::string extentText(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

Status checkInput(const InputImage& in, const char* name, bool wanted, const char* flag, Extent extent,
                  VkFormat format) {
  if (!wanted) {
    if (in.view != VK_NULL_HANDLE)
      return Status::error(StatusCode::InvalidInput,
                           std::string("Inputs::") + name + " is given but " + flag + " says there is none");
    return Status::success();
  }
  if (in.view == VK_NULL_HANDLE)
    return Status::error(StatusCode::InvalidInput,
                         std::string("Inputs::") + name + ".view is VK_NULL_HANDLE (required: " + flag + ")");
  if (!(in.extent == extent))
    return Status::error(StatusCode::InvalidInput, std::string("Inputs::") + name + " is " + extentText(in.extent) +
                                                       " but the plan needs the input extent " + extentText(extent) +
                                                       " (viewport + 2 * guard band)");
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

std::uint32_t firstSet(const EffectState& e, std::size_t passIndex) {
  std::uint32_t k = 0;
  for (std::size_t i = 0; i < passIndex; ++i) k += e.plan.passes[i].dispatchCount;
  return k;
}

}  // namespace

Status checkInputs(const EffectState& e, const Inputs& in, const OutputImage* userOutput, OutputTarget& out) {
  const Extent ie = e.plan.inputExtent;
  const Config& c = e.config;
  if (Status st = checkInput(in.depth, "depth", true, "always", ie, c.depthFormat); !st) return st;
  if (Status st = checkInput(in.depth2, "depth2", c.secondLayer, "Config::secondLayer", ie, c.depthFormat); !st)
    return st;
  if (Status st = checkInput(in.normals, "normals", c.normalsFormat != VK_FORMAT_UNDEFINED, "Config::normalsFormat",
                             ie, c.normalsFormat);
      !st)
    return st;
  if (!e.config.userOutput) {
    if (userOutput)
      return Status::error(StatusCode::InvalidInput,
                           "record() got an output image but Config::userOutput is false (the effect owns its output)");
    const OwnedImage* ao = e.res.find(gen::ResourceId::ao);
    out = {ao->image.get(), ao->levelViews[0].get()};
    return Status::success();
  }
  if (!userOutput)
    return Status::error(StatusCode::InvalidInput, "Config::userOutput is set but record() got no output image");
  if (userOutput->image == VK_NULL_HANDLE || userOutput->view == VK_NULL_HANDLE)
    return Status::error(StatusCode::InvalidInput, "the output image or its view is VK_NULL_HANDLE");
  if (userOutput->format != VK_FORMAT_R16_SFLOAT)
    return Status::error(StatusCode::UnsupportedFormat, "the output must be VK_FORMAT_R16_SFLOAT (the shader writes r16f), got format " +
                                                            std::to_string(userOutput->format));
  for (const auto& [input, name] : {std::pair{in.depth.view, "depth"}, std::pair{in.depth2.view, "depth2"},
                                     std::pair{in.normals.view, "normals"}})
    if (input != VK_NULL_HANDLE && input == userOutput->view)
      return Status::error(StatusCode::InvalidInput, std::string("the output view is also Inputs::") + name +
                                                         ".view; the output must be a separate image");
  if (!(userOutput->extent == e.plan.aoExtent))
    return Status::error(StatusCode::InvalidInput, "the output is " + extentText(userOutput->extent) +
                                                       " but the plan's AO extent (the viewport) is " +
                                                       extentText(e.plan.aoExtent));
  out = {userOutput->image, userOutput->view};
  return Status::success();
}

std::uint32_t acquireSlot(EffectState& e, const Inputs& in, const OutputTarget& output) {
  const std::uint32_t slot = e.nextSlot;
  e.nextSlot = (slot + 1) % e.config.framesInFlight;
  // Always rewritten: a caller may destroy a view and create another that gets the same handle
  // value, so comparing handles cannot tell whether a set is still valid (lavapipe crashed on the
  // stale set). The slot's previous command buffer has completed (the ring contract), and a few
  // dozen descriptor writes per record cost next to nothing.
  writeDescriptors(e, slot, in, output);
  // The slot's copy of the parameter block (its previous command buffer has completed: the ring
  // contract), written only when it changed.
  if (!e.ubo.valid[slot] || std::memcmp(&e.ubo.written[slot], &e.params, sizeof(ParamBlock)) != 0) {
    std::memcpy(e.ubo.mapped + slot * e.ubo.stride, &e.params, sizeof(ParamBlock));
    e.ubo.written[slot] = e.params;
    e.ubo.valid[slot] = true;
  }
  return slot;
}

void recordPrologue(const EffectState& e, VkCommandBuffer cmd, const OutputTarget& output, int timingRegion) noexcept {
  const VkQueryPool queries = e.queryPool.get();
  if (timingRegion >= 0)
    e.d.vkCmdResetQueryPool(cmd, queries, static_cast<std::uint32_t>(timingRegion) * queriesPerRegion(),
                            queriesPerRegion());
  {
    BarrierBatch images(e, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | e.config.outputDstStages,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
    for (const auto& img : e.res.images) {
      if (img.image.get() == output.image) continue;
      images.add(imageBarrier(img.image.get(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                              VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT, 0,
                              img.levels));
    }
    images.add(imageBarrier(output.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                            VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_WRITE_BIT, 0, 1));
  }
  if (timingRegion >= 0)
    e.d.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries,
                            static_cast<std::uint32_t>(timingRegion) * queriesPerRegion());
}

void recordPass(const EffectState& e, VkCommandBuffer cmd, std::size_t passIndex, std::uint32_t slot,
                const OutputTarget& output, int timingRegion) noexcept {
  const PlannedPass& p = e.plan.passes[passIndex];
  const gen::PassInfo& info = gen::pass(p.pass);
  const PipelineEntry* pipe = findPipeline(e, p.variant);
  if (e.d.vkCmdBeginDebugUtilsLabelEXT) {
    char label[64];
    std::snprintf(label, sizeof label, "sao %.*s", static_cast<int>(info.name.size()), info.name.data());
    VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT, nullptr, label, {0.4f, 0.6f, 0.9f, 1.0f}};
    e.d.vkCmdBeginDebugUtilsLabelEXT(cmd, &l);
  }
  e.d.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->pipeline.get());

  // The dispatch size follows the first written resource (docs/effect-format.md).
  gen::ResourceId first{};
  for (const auto& b : p.variant->bindings)
    if (b.write) {
      first = e.plan.resolve(p, b.resource);
      break;
    }
  const OwnedImage* firstImage = e.res.find(first);
  const Extent base = firstImage ? firstImage->extent : e.plan.aoExtent;

  const std::uint32_t setBase = slot * e.desc.setsPerSlot + firstSet(e, passIndex);
  for (std::uint32_t k = 0; k < p.dispatchCount; ++k) {
    const std::uint32_t level = info.perMip ? k + 1 : 0;
    e.d.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->layout.get(), 0, 1,
                                &e.desc.sets[setBase + k], 0, nullptr);
    const std::uint32_t w = std::max(1u, base.width >> level), h = std::max(1u, base.height >> level);
    e.d.vkCmdDispatch(cmd, (w + info.localX - 1) / info.localX, (h + info.localY - 1) / info.localY, 1);

    BarrierBatch written(e, cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
    for (const auto& b : p.variant->bindings) {
      if (!b.write) continue;
      const OwnedImage* img = e.res.find(e.plan.resolve(p, b.resource));
      if (!img || img->image.get() == output.image) continue;  // the output: the epilogue's barrier
      written.add(imageBarrier(img->image.get(), VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL,
                               VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, level, 1));
    }
  }
  if (timingRegion >= 0)
    e.d.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, e.queryPool.get(),
                            static_cast<std::uint32_t>(timingRegion) * queriesPerRegion() + 1 +
                                static_cast<std::uint32_t>(passIndex));
  if (e.d.vkCmdEndDebugUtilsLabelEXT) e.d.vkCmdEndDebugUtilsLabelEXT(cmd);
}

void recordEpilogue(const EffectState& e, VkCommandBuffer cmd, const OutputTarget& output) noexcept {
  const VkImageMemoryBarrier b =
      imageBarrier(output.image, VK_IMAGE_LAYOUT_GENERAL, e.config.outputLayout, VK_ACCESS_SHADER_WRITE_BIT,
                   e.config.outputDstAccess, 0, 1);
  e.d.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, e.config.outputDstStages, 0, 0, nullptr, 0,
                           nullptr, 1, &b);
}

Status Effect::record(VkCommandBuffer cmd, const Inputs& inputs, const OutputImage* userOutput) {
  return guarded("sao::vk::Effect::record()", [&] {
    EffectState& e = *impl_;
    if (cmd == VK_NULL_HANDLE)
      return Status::error(StatusCode::InvalidInput, "record(): the command buffer is VK_NULL_HANDLE");
    OutputTarget output;
    if (Status st = checkInputs(e, inputs, userOutput, output); !st) return st;
    // The only step that allocates, before the first command: a failure records nothing.
    const std::uint32_t slot = acquireSlot(e, inputs, output);
    const int region = e.config.timestamps && e.queryPool ? static_cast<int>(slot) : -1;
    recordPrologue(e, cmd, output, region);
    for (std::size_t i = 0; i < e.plan.passes.size(); ++i) recordPass(e, cmd, i, slot, output, region);
    recordEpilogue(e, cmd, output);
    if (region >= 0) e.lastTimedRegion = region;
    return Status::success();
  });
}

}  // namespace sao::vk
