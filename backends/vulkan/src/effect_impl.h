// The state behind sao::vk::Effect, shared by the source files that each own one responsibility:
// resources.cpp (images and the parameter buffer from the plan), pipelines.cpp (pipelines,
// layouts, descriptor sets), record.cpp (commands and barriers), timing.cpp (timestamps and the
// fence fallback), effect.cpp (creation, validation, update). Every Vulkan object is held by a
// Handle (handle.h) or an Allocator::Block, so whatever is dropped is destroyed.
#pragma once
#include <vulkan/vulkan_core.h>

#include <array>
#include <exception>
#include <string>
#include <vector>

#include "allocator.h"
#include "dispatch.h"
#include "handle.h"
#include "sao/frame.h"
#include "sao/schedule.h"
#include "sao/temporal.h"
#include "sao/vulkan/effect.h"

namespace sao::vk {

// An effect-owned image with a view of every level (storage writes: a levels= write binds one per
// slot; a levels=A..B read of level A - 1) and one of the whole chain (the sampled reads of later
// passes). The views are declared after
// the image, so they go first.
struct OwnedImage {
  gen::ResourceId id{};
  Handle<VkImage> image;
  VkFormat format = VK_FORMAT_UNDEFINED;
  Extent extent;
  std::uint32_t levels = 1;
  std::uint32_t copy = 0;  // a history's copy 0 or 1 (PlannedImage::copies, sao/temporal.h)
  Handle<VkImageView> fullView;
  std::vector<Handle<VkImageView>> levelViews;
};

// The images go before the memory they are bound to.
struct Resources {
  std::vector<Allocator::Block> memory;
  std::vector<OwnedImage> images;
  const OwnedImage* find(gen::ResourceId id, std::uint32_t copy = 0) const {
    for (const auto& i : images)
      if (i.id == id && i.copy == copy) return &i;
    return nullptr;
  }
};

// The parameter block: one region per ring slot (stride aligned to minUniformBufferOffsetAlignment)
// in persistently mapped, host-coherent memory. record() copies gen::SaoParams as is into its
// slot's region (when it differs from what the region holds); the slot's descriptor sets read it.
struct ParamBuffer {
  std::vector<Allocator::Block> memory;
  Handle<VkBuffer> buffer;
  char* mapped = nullptr;
  VkDeviceSize stride = 0;
  std::vector<ParamBlock> written;  // per slot, what its region holds
  std::vector<bool> valid;
};

struct PipelineEntry {
  const gen::PassVariantInfo* variant = nullptr;
  Handle<VkDescriptorSetLayout> setLayout;
  Handle<VkPipelineLayout> layout;
  Handle<VkPipeline> pipeline;
};

// One descriptor set per dispatch of the schedule, per ring slot; the sets go with the pool. The
// write structures of one slot are sized here once, so record() fills them without allocating.
struct Descriptors {
  Handle<VkDescriptorPool> pool;
  std::uint32_t setsPerSlot = 0;
  std::vector<VkDescriptorSet> sets;  // [slot * setsPerSlot + k], k = the dispatch's index
  std::vector<VkWriteDescriptorSet> writes;    // one slot's: a buffer write per set, then one per binding
  std::vector<VkDescriptorImageInfo> images;   // one per binding of every dispatch
  std::vector<VkDescriptorBufferInfo> buffers; // one per set
};

// The output record() writes this time: the effect's own or the user's.
struct OutputTarget {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  // Where the prologue transitions it from: UNDEFINED (contents discarded), or the caller's layout
  // when Inputs::outputChannels keeps channels (or blends).
  VkImageLayout keepFrom = VK_IMAGE_LAYOUT_UNDEFINED;
  std::uint32_t layer = 0;  // the array layer `view` shows (OutputImage::layer); 0 for the effect's own
};

inline constexpr std::uint32_t kMaxFramesInFlight = 16;

// Everything Effect holds. Members are destroyed in reverse order: the descriptor sets, the images,
// the parameter buffer, the pipelines, the query pool, the sampler (the set layouts' immutable
// sampler), and last the allocator that counts the memory blocks.
struct __attribute__((visibility("hidden"))) EffectState {
  DeviceContext ctx;
  Owner owner;  // ctx.device and ctx.allocator, for Handle
  Dispatch d;
  VkPhysicalDeviceProperties props{};
  VkPhysicalDeviceFeatures features{};
  VkPhysicalDeviceMemoryProperties memoryProps{};
  VkQueueFamilyProperties family{};

  Config config;
  PlanInputs planInputs;  // of `config`: what completeFrame (sao/frame.h) reads per record
  Plan plan;
  Schedule schedule;  // of `plan`: what record() translates
  ParamBlock params{};

  Allocator allocator;
  Handle<VkSampler> sampler;  // nearest, clamp to edge, every level
  // Timestamps: one region of (passes + 1) queries per ring slot, plus one for measure().
  Handle<VkQueryPool> queryPool;
  std::vector<PipelineEntry> pipelines;
  ParamBuffer ubo;
  Resources res;
  Descriptors desc;

  std::uint32_t nextSlot = 0;
  std::uint64_t outputGeneration = 0;  // Effect::outputGeneration()
  int lastTimedRegion = -1;  // region of the last timestamped record(); its passes are plan.passes
  // The history images' state (sao/temporal.h), and whether the record being made reads them
  // (its prologue keeps the previous frame's copy instead of discarding it).
  TemporalHistory temporal;
  bool historyValid = false;

  EffectState() = default;
  EffectState(const EffectState&) = delete;
  EffectState& operator=(const EffectState&) = delete;
};

// Defined here, not in the public header: the library's own type.
struct __attribute__((visibility("hidden"))) Effect::Impl : EffectState {};

// ---- resources.cpp
VkFormat vkFormat(gen::Format format);
// The effect's format of a VkFormat the output may have; Depth (never an output format) otherwise.
gen::Format outputFormatOf(VkFormat format);
Status createResources(EffectState& e, const Plan& plan, Resources& out);  // on error: `out` unchanged
Status createParamBuffer(EffectState& e, std::uint32_t slots, ParamBuffer& out);  // on error: `out` unchanged

// ---- pipelines.cpp
Status createSampler(EffectState& e);
Status ensurePipelines(EffectState& e, const Plan& plan);  // every pass variant of the plan
const PipelineEntry* findPipeline(const EffectState& e, const gen::PassVariantInfo* variant);
// Pool and sets for the schedule, `slots` ring slots (pipelines must exist). On error: `out` unchanged.
Status createDescriptors(EffectState& e, const Schedule& schedule, std::uint32_t slots, Descriptors& out);
void writeDescriptors(EffectState& e, std::uint32_t slot, const Inputs& inputs, const OutputTarget& output);

// ---- record.cpp
// timingRegion < 0: no timestamps. These three record commands only: they allocate nothing and
// cannot fail, so a record() that fails has recorded nothing.
void recordPrologue(const EffectState& e, VkCommandBuffer cmd, const OutputTarget& output, int timingRegion) noexcept;
// Every dispatch of the schedule, or those of plan pass `onlyPass` (>= 0), with the barriers their
// hazards need.
void recordDispatches(const EffectState& e, VkCommandBuffer cmd, std::uint32_t slot, const OutputTarget& output,
                      int timingRegion, int onlyPass = -1) noexcept;
void recordEpilogue(const EffectState& e, VkCommandBuffer cmd, const OutputTarget& output) noexcept;
Status checkInputs(const EffectState& e, const Inputs& inputs, const OutputImage* userOutput, OutputTarget& out);
// The next ring slot, its descriptor sets and its copy of the parameter block: `cameraBlock` (from
// cameraParams, Inputs::camera) when given, else the Config camera's e.params; this record's
// region offset goes into either.
std::uint32_t acquireSlot(EffectState& e, const Inputs& inputs, const OutputTarget& output, ParamBlock* cameraBlock);

// ---- frame_camera.cpp
// The parameter block of a record with Inputs::camera: Ok only for a valid camera (create()'s
// checks and messages) that plans exactly as Config::camera does. Allocates nothing on success.
Status cameraParams(const EffectState& e, const Camera& camera, ParamBlock& out);
// The block of one record() or measure() that differs from e.params (Inputs::camera's, or any
// with temporal accumulation, whose previous-frame members are per frame): `own` then says to
// pass `out` to acquireSlot. Sets e.historyValid. Allocates nothing.
Status recordParams(EffectState& e, const Inputs& inputs, ParamBlock& out, bool& own);
// After a record() or measure() was made: its frame wrote the history (when temporal is on).
void recordDone(EffectState& e, const Inputs& inputs);

// ---- timing.cpp
// The timestamp pool for `framesInFlight` ring slots; none (and success) where the queue family
// has no timestamps. On error: `out` unchanged.
Status createQueryPool(const EffectState& e, std::uint32_t framesInFlight, Handle<VkQueryPool>& out);
std::uint32_t queriesPerRegion();
bool familyHasTimestamps(const EffectState& e);

// ---- effect.cpp
// What the depth input holds: R32_SFLOAT is linear z, every other depth format hardware depth.
inline DepthEncoding depthEncodingOf(VkFormat depthFormat) {
  return depthFormat == VK_FORMAT_R32_SFLOAT ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
}
// The normals contract (sao::checkNormalsChannels) of Config::normalsFormat for `encoding`; Ok
// without normals. Builds a message only on failure (record() with Inputs::camera calls it).
Status checkNormalsFormat(VkFormat normalsFormat, NormalsEncoding encoding);
// DriverError "<where>: <what>"; without memory for that, a message that needs none.
Status exceptionStatus(const char* where, const char* what) noexcept;

// Runs `body` (returning a Status) and turns an exception (std::bad_alloc, std::length_error, ...)
// into a DriverError naming `where`: no exception crosses the API.
template <typename Body>
Status guarded(const char* where, Body&& body) noexcept {
  try {
    return body();
  } catch (const std::exception& x) {
    return exceptionStatus(where, x.what());
  } catch (...) {
    return exceptionStatus(where, "unknown exception");
  }
}

}  // namespace sao::vk
