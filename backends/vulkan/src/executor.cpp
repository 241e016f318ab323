// The Vulkan executor of core's frame (sao/executor.h): FrameState decides what to create, keep and
// run; this translates it into Vulkan objects, barriers and commands.
//
// Barriers (all VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT unless named):
//  entry     each image the frame writes: UNDEFINED -> GENERAL (its contents are rewritten every
//            frame) after the previous frame's compute reads and writes, and for the output after
//            Config::outputDstStages (where the previous result was read); an output whose
//            channels Inputs::outputChannels keeps goes from OutputImage::layout instead; the
//            history the frame before wrote is kept when this frame reads it. Inputs the caller
//            wrote are the caller's to synchronise (their layouts and barriers come with Inputs).
// The parameter block is not a device write: beginFrame copies it into its ring slot's region of
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

// The image (and array layer) behind a resource this frame: owned (layer 0), or the caller's output.
struct Target {
  VkImage image = VK_NULL_HANDLE;
  std::uint32_t layer = 0;
};
Target imageOf(const EffectState& e, std::uint32_t parity, gen::ResourceId id, const OutputTarget& output,
               bool previousFrame = false) {
  if (const OwnedImage* img = e.res.find(id, imageCopy(parity, id, previousFrame))) return {img->image.get(), 0};
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

// Descriptor sets follow the dispatches and their pass variants (set layouts).
bool sameDispatches(const Schedule& a, const Schedule& b) {
  return std::equal(a.dispatches.begin(), a.dispatches.end(), b.dispatches.begin(), b.dispatches.end(),
                    [](const ScheduledDispatch& x, const ScheduledDispatch& y) { return x.variant == y.variant; });
}

}  // namespace

// ---- configuration

Status VkFrameExecutor::checkPlan(const Plan& plan) {
  const VkPhysicalDeviceLimits& l = e_.props.limits;
  DeviceLimits limits;
  limits.imageSide = {l.maxImageDimension2D, "maxImageDimension2D"};
  limits.sharedBytes = {l.maxComputeSharedMemorySize, "maxComputeSharedMemorySize"};
  limits.pushConstantBytes = {l.maxPushConstantsSize, "maxPushConstantsSize"};
  limits.storageImagesPerPass = {l.maxPerStageDescriptorStorageImages, "maxPerStageDescriptorStorageImages"};
  limits.sampledImagesPerPass = {std::min(l.maxPerStageDescriptorSamplers, l.maxPerStageDescriptorSampledImages),
                                 "maxPerStageDescriptorSamplers or SampledImages"};
  return checkDeviceLimits(plan, limits);
}

Status VkFrameExecutor::createImage(const PlannedImage& image) { return createImages(e_, image); }

bool VkFrameExecutor::retiring() const noexcept {
  return retireUntil_ && !e_.retired.empty() && e_.retired.back().until == *retireUntil_;
}

void VkFrameExecutor::destroyImage(const PlannedImage& image) noexcept {
  auto& images = e_.res.images;
  const auto dropped = std::stable_partition(images.begin(), images.end(), [&](const OwnedImage& i) {
    return !(i.id() == image.resource && sameImage(i.planned, image));
  });
  // Kept for the records that may still read it (room reserved by preparePlan: no allocation here).
  if (retiring()) std::move(dropped, images.end(), std::back_inserter(e_.retired.back().images));
  images.erase(dropped, images.end());
}

Status VkFrameExecutor::createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) {
  return ensurePipeline(e_, pass, variant);
}

// Memory and views for the new images; descriptor sets when the dispatches changed,
// built beside the current ones.
Status VkFrameExecutor::preparePlan(const Plan&, const Schedule& schedule) {
  if (Status st = bindImages(e_); !st) return st;
  // Where the commit puts what it drops: room made now (the commit cannot fail), the entry added
  // last, so that a failed plan's own images are destroyed by its undo, not retired.
  std::optional<EffectState::Retired> entry;
  if (retireUntil_) {
    entry.emplace(EffectState::Retired{*retireUntil_, {}, {}});
    entry->images.reserve(e_.res.images.size());
    e_.retired.reserve(e_.retired.size() + 1);
  }
  newSets_ = !e_.frame.configured() || !sameDispatches(e_.schedule(), schedule);
  if (newSets_)
    if (Status st = createDescriptors(e_, schedule, e_.config.framesInFlight, preparedSets_); !st) return st;
  if (entry) e_.retired.push_back(std::move(*entry));  // within the capacity reserved: no throw
  return Status::success();
}

void VkFrameExecutor::planAdopted() noexcept {
  if (newSets_) {
    std::swap(e_.desc, preparedSets_);
    if (retiring())
      std::swap(e_.retired.back().sets, preparedSets_);  // pending records may still bind them
    else
      e_.nextSlot = 0;  // the first plan: nothing is pending
    preparedSets_ = Descriptors{};
    e_.lastTimedRegion = -1;
    newSets_ = false;
  }
  // A new owned output image, or none now: the caller's descriptors of output() must be rewritten.
  const OwnedImage* ao = e_.res.find(gen::ResourceId::ao);
  const VkImage output = ao ? ao->image.get() : VK_NULL_HANDLE;
  if (output != e_.adoptedOutput) ++e_.outputGeneration;
  e_.adoptedOutput = output;
}

// ---- a frame

Status VkFrameExecutor::beginFrame(const FrameWork& frame) {
  // What a re-plan kept for pending records goes once they have completed (the ring contract).
  std::erase_if(e_.retired, [&](const EffectState::Retired& r) { return r.until <= e_.records; });
  ++e_.records;
  work_ = frame;
  error_ = Status::success();
  if (rec_.output.image == VK_NULL_HANDLE)  // the effect's own output, of the plan just run
    if (const OwnedImage* ao = e_.res.find(gen::ResourceId::ao))
      rec_.output = {ao->image.get(), ao->levelViews[0].get()};
  stamped_ = false;
  slot_ = e_.nextSlot;
  e_.nextSlot = (slot_ + 1) % e_.config.framesInFlight;
  // Always rewritten: a caller may destroy a view and create another that gets the same handle
  // value, so comparing handles cannot tell whether a set is still valid (lavapipe crashed on the
  // stale set). The slot's previous command buffer has completed (the ring contract), and a few
  // dozen descriptor writes per record cost next to nothing.
  writeDescriptors(e_, slot_, frame.historyParity, *rec_.inputs, rec_.output);
  // The slot's copy of the parameter block, written only when it changed.
  ParamBuffer& ubo = e_.ubo;
  if (!ubo.valid[slot_] || std::memcmp(&ubo.written[slot_], frame.block, sizeof(ParamBlock)) != 0) {
    std::memcpy(ubo.mapped + slot_ * ubo.stride, frame.block, sizeof(ParamBlock));
    ubo.written[slot_] = *frame.block;
    ubo.valid[slot_] = true;
  }
  if (rec_.timingRegion >= 0)
    e_.d.vkCmdResetQueryPool(rec_.cmd, e_.queryPool.get(), static_cast<std::uint32_t>(rec_.timingRegion) * queriesPerRegion(),
                             queriesPerRegion());
  return Status::success();
}

void VkFrameExecutor::stampBegin() noexcept {
  if (rec_.timingRegion >= 0 && !stamped_)
    e_.d.vkCmdWriteTimestamp(rec_.cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, e_.queryPool.get(),
                             static_cast<std::uint32_t>(rec_.timingRegion) * queriesPerRegion());
  stamped_ = true;
}

void VkFrameExecutor::prologue(std::span<const Hazard> entry) noexcept {
  const OutputTarget& output = rec_.output;
  {
    BarrierBatch images(e_, rec_.cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | e_.config.outputDstStages,
                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
    for (const Hazard& h : entry) {
      if (h.kind == HazardKind::CallerWrote) continue;  // the caller's barrier (see above)
      const Target t = imageOf(e_, work_.historyParity, h.resource, output, h.previousFrame);
      if (h.previousFrame) {  // the history the frame before wrote: kept when this frame reads it
        images.add(imageBarrier(t.image, t.layer, work_.historyValid ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED,
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
  stampBegin();
  if (rec_.perPass) submitPerPass(nullptr, true);  // the prologue untimed
}

void VkFrameExecutor::epilogue(std::span<const Hazard> exit) noexcept {
  for (const Hazard& h : exit) {
    const Target t = imageOf(e_, work_.historyParity, h.resource, rec_.output);
    const VkImageMemoryBarrier b = imageBarrier(t.image, t.layer, VK_IMAGE_LAYOUT_GENERAL, e_.config.outputLayout,
                                                VK_ACCESS_SHADER_WRITE_BIT, e_.config.outputDstAccess, h.baseLevel,
                                                h.levelCount);
    e_.d.vkCmdPipelineBarrier(rec_.cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, e_.config.outputDstStages, 0, 0, nullptr,
                              0, nullptr, 1, &b);
  }
}

void VkFrameExecutor::barrier(std::span<const Hazard> hazards) {
  if (!error_.ok()) return;
  const Schedule& s = *work_.schedule;
  if (hazards.data() == s.entryHazards().data()) return prologue(hazards);
  if (hazards.data() == s.exitHazards().data()) return epilogue(hazards);
  BarrierBatch batch(e_, rec_.cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  for (const Hazard& h : hazards)
    if (const Target t = imageOf(e_, work_.historyParity, h.resource, rec_.output, h.previousFrame); t.image)
      batch.add(hazardBarrier(t, h));
}

void VkFrameExecutor::dispatch(const ScheduledDispatch& d, std::span<const ScheduledBinding>) {
  if (!error_.ok()) return;
  stampBegin();
  const auto& dispatches = work_.schedule->dispatches;
  const std::size_t k = static_cast<std::size_t>(&d - dispatches.data());
  const bool firstOfPass = k == 0 || dispatches[k - 1].passIndex != d.passIndex;
  const bool lastOfPass = k + 1 == dispatches.size() || dispatches[k + 1].passIndex != d.passIndex;
  const PipelineEntry* pipe = findPipeline(e_, d.variant);
  const VkCommandBuffer cmd = rec_.cmd;
  if (firstOfPass && e_.d.vkCmdBeginDebugUtilsLabelEXT) {
    const std::string_view name = gen::pass(d.pass).name;
    char label[64];
    std::snprintf(label, sizeof label, "sao %.*s", static_cast<int>(name.size()), name.data());
    VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT, nullptr, label, {0.4f, 0.6f, 0.9f, 1.0f}};
    e_.d.vkCmdBeginDebugUtilsLabelEXT(cmd, &l);
  }
  e_.d.vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->pipeline.get());
  if (d.variant->pushConstantBytes > 0) {
    const gen::PushConstants constants = gen::pushConstantsOf(*work_.block);
    e_.d.vkCmdPushConstants(cmd, pipe->layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, d.variant->pushConstantBytes,
                            &constants);
  }
  e_.d.vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipe->layout.get(), 0, 1,
                               &e_.desc.sets[slot_ * e_.desc.setsPerSlot + k], 0, nullptr);
  e_.d.vkCmdDispatch(cmd, d.groupsX, d.groupsY, 1);
  if (!lastOfPass) return;
  if (rec_.timingRegion >= 0)
    e_.d.vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, e_.queryPool.get(),
                             static_cast<std::uint32_t>(rec_.timingRegion) * queriesPerRegion() + 1 + d.passIndex);
  if (e_.d.vkCmdEndDebugUtilsLabelEXT) e_.d.vkCmdEndDebugUtilsLabelEXT(cmd);
  // measure()'s fallback: each pass its own submission (the last one ends with the exit barrier).
  if (rec_.perPass && k + 1 < dispatches.size()) submitPerPass(&d.pass, true);
}

Status VkFrameExecutor::endFrame() {
  if (rec_.perPass && error_.ok() && !work_.schedule->dispatches.empty())
    submitPerPass(&work_.schedule->dispatches.back().pass, false);
  return error_;
}

void VkFrameExecutor::submitPerPass(const gen::PassId* pass, bool beginNext) noexcept {
  if (!error_.ok()) return;
  error_ = guarded("sao::vk::Effect::measure()", [&] {
    double ms = 0;
    if (Status st = rec_.perPass->submitAndWait(rec_.queue, rec_.cmd, &ms); !st) return st;
    if (pass) rec_.times->passes.push_back({std::string(gen::pass(*pass).name), ms});
    return beginNext ? rec_.perPass->begin(rec_.cmd) : Status::success();
  });
}

}  // namespace sao::vk
