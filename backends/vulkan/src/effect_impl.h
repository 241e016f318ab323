// The state behind sao::vk::Effect, shared by the source files that each own one responsibility:
// executor.cpp (the Vulkan executor of core's frame, sao/executor.h: what FrameState asks for),
// resources.cpp (images and the parameter buffer), pipelines.cpp (pipelines, layouts, descriptor
// sets), record.cpp (record(): the caller's images checked, the frame run into its command
// buffer), timing.cpp (timestamps and the fence fallback), effect.cpp (creation, validation).
// The plan, the schedule, the block and the history are core's FrameState. Every Vulkan
// object is held by a Handle (handle.h) or an Allocator::Block, so whatever is dropped is destroyed.
#pragma once
#include <vulkan/vulkan_core.h>

#include <array>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "allocator.h"
#include "dispatch.h"
#include "handle.h"
#include "sao/executor.h"
#include "sao/frame.h"
#include "sao/schedule.h"
#include "sao/temporal.h"
#include "sao/vulkan/effect.h"

namespace sao::vk {

// An effect-owned image (one copy of a PlannedImage) with a view of every level (storage writes: a
// levels= write binds one per slot; a levels=A..B read of level A - 1) and one of the whole chain
// (the sampled reads of later passes). FrameState creates it (createImage: the VkImage), then
// preparePlan binds the memory of every new image of a plan at once (one block per memory type,
// shared by those images) and makes the views. Members go in reverse order: views, image, memory.
struct OwnedImage {
  PlannedImage planned;
  std::uint32_t copy = 0;  // a history's copy 0 or 1 (PlannedImage::copies, sao/temporal.h)
  VkFormat format = VK_FORMAT_UNDEFINED;
  bool bound = false;  // memory and views made (preparePlan)
  // The blocks of the plan that made it (one per memory type), shared by that plan's new images.
  std::vector<std::shared_ptr<Allocator::Block>> memoryBlocks;
  Handle<VkImage> image;
  Handle<VkImageView> fullView;
  std::vector<Handle<VkImageView>> levelViews;
  gen::ResourceId id() const { return planned.resource; }
};

struct Resources {
  std::vector<OwnedImage> images;
  // This frame's copy of resource `id` (there is one image per resource outside a configuration).
  const OwnedImage* find(gen::ResourceId id, std::uint32_t copy = 0) const {
    for (const auto& i : images)
      if (i.id() == id && i.copy == copy) return &i;
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
  std::uint32_t slots = 0;  // ring slots (Config::framesInFlight) the sets are made for
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
// Each input's VkFormat, VK_FORMAT_UNDEFINED where the configuration has none.
using InputFormats = gen::InputSet<VkFormat>;

// What a frame's images give the configuration beside its settings and camera: each input's format,
// the depth's samples, whose output it is and its format. Another one is checked again (and may
// plan again, when its plan inputs differ).
struct FrameConfig {
  InputFormats formats;
  VkSampleCountFlagBits depthSamples = VK_SAMPLE_COUNT_1_BIT;
  bool userOutput = false;
  VkFormat outputFormat = VK_FORMAT_UNDEFINED;
  bool operator==(const FrameConfig&) const = default;
};
// How FrameState names record()'s inputs in its messages (and checkInputs where it checks first).
inline constexpr const char* kRecordInputs = "sao::vk::Effect::record() Inputs";

struct EffectState;

// measure()'s command pool (its command buffers go with it) and fence (timing.cpp).
struct Submitter {
  const EffectState& e;
  Handle<VkCommandPool> pool;
  Handle<VkFence> fence;
  explicit Submitter(const EffectState& state) : e(state) {}
  Status init();
  Status begin(VkCommandBuffer& cmd);
  // Ends, submits and waits; `ms` gets the wall time from submission to the fence.
  Status submitAndWait(VkQueue queue, VkCommandBuffer cmd, double* ms);
};

// What record() or measure() hands the executor for the frame FrameState runs next.
struct Recording {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  const Inputs* inputs = nullptr;
  OutputTarget output;
  int timingRegion = -1;  // -1: no timestamps
  // measure()'s fallback: each pass on its own submission, timed by a steady clock into `times`.
  Submitter* perPass = nullptr;
  VkQueue queue = VK_NULL_HANDLE;
  Timings* times = nullptr;
};

// The Vulkan executor of core's frame (sao/executor.h). Configuration: images (memory bound per
// plan in preparePlan), pipelines, descriptor sets sized for the schedule (built aside, swapped in
// by planAdopted). Frames: the ring slot's descriptors and block (beginFrame), the entry and exit
// barriers of the synchronisation contract (executor.cpp's header), one image barrier per hazard,
// each dispatch with its pipeline, push constants, set, timestamps and debug label.
class __attribute__((visibility("hidden"))) VkFrameExecutor final : public Executor {
 public:
  explicit VkFrameExecutor(EffectState& e) : e_(e) {}
  void setRecording(const Recording& r) { rec_ = r; }
  // A record() that plans again while records may be pending: what the new plan drops
  // (images, descriptor sets) is kept until the record numbered `until` is made, when the ring
  // contract says every record that could read it has completed. Off: dropped at once (the first plan).
  void retireUntil(std::optional<std::uint64_t> until) { retireUntil_ = until; }
  std::uint32_t slot() const { return slot_; }  // the ring slot of the last frame

  Status checkPlan(const Plan& plan) override;
  Status createImage(const PlannedImage& image) override;
  void destroyImage(const PlannedImage& image) noexcept override;
  Status createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) override;
  Status preparePlan(const Plan& plan, const Schedule& schedule) override;
  void planAdopted() noexcept override;
  Status beginFrame(const FrameWork& frame) override;
  void barrier(std::span<const Hazard> hazards) override;
  void dispatch(const ScheduledDispatch& dispatch, std::span<const ScheduledBinding> bindings) override;
  Status endFrame() override;

 private:
  // Whether what the commit drops goes to preparePlan's retired entry (else it is destroyed).
  bool retiring() const noexcept;
  void prologue(std::span<const Hazard> entry) noexcept;
  void epilogue(std::span<const Hazard> exit) noexcept;
  // The frame's first timestamp (once, before its first dispatch).
  void stampBegin() noexcept;
  // measure()'s fallback: the command buffer so far submitted and waited for (its time into
  // `times` under `pass` unless null), and with `beginNext` a new one begun.
  void submitPerPass(const gen::PassId* pass, bool beginNext) noexcept;

  EffectState& e_;
  Recording rec_;
  std::optional<std::uint64_t> retireUntil_;
  Descriptors preparedSets_;  // preparePlan's, for planAdopted
  bool newSets_ = false;
  FrameWork work_;
  std::uint32_t slot_ = 0;
  bool stamped_ = false;
  Status error_;  // of dispatch() or barrier(): endFrame() returns it
};

// Everything Effect holds. Members are destroyed in reverse order: the executor (its prepared
// descriptor sets), the descriptor sets, the images, the parameter buffer, the pipelines, the
// query pool, the sampler (the set layouts' immutable sampler), and last the allocator that counts
// the memory blocks.
struct __attribute__((visibility("hidden"))) EffectState {
  DeviceContext ctx;
  Owner owner;  // ctx.device and ctx.allocator, for Handle
  Dispatch d;
  VkPhysicalDeviceProperties props{};
  VkPhysicalDeviceFeatures features{};
  VkPhysicalDeviceMemoryProperties memoryProps{};
  VkQueueFamilyProperties family{};

  Config config;
  FrameConfig current;  // what the configuration (FrameState's plan) is made for

  // The plan, the schedule, the images kept, the parameter block and the temporal history: core's.
  FrameState frame{kRecordInputs};

  Allocator allocator;
  Handle<VkSampler> sampler;  // nearest, clamp to edge, every level
  // Timestamps: one region of (passes + 1) queries per ring slot, plus one for measure().
  Handle<VkQueryPool> queryPool;
  std::vector<PipelineEntry> pipelines;
  ParamBuffer ubo;
  Resources res;
  Descriptors desc;
  // What a re-plan dropped while records were pending (retireUntil above).
  struct Retired {
    std::uint64_t until = 0;
    std::vector<OwnedImage> images;
    Descriptors sets;
  };
  std::vector<Retired> retired;
  std::uint64_t records = 0;  // frames recorded (record() and measure()): the ring's count

  std::uint32_t nextSlot = 0;
  std::uint64_t outputGeneration = 0;  // Effect::outputGeneration()
  VkImage adoptedOutput = VK_NULL_HANDLE;  // the owned output of the plan adopted last
  int lastTimedRegion = -1;  // region of the last timestamped record(); its passes are the plan's
  VkFrameExecutor executor{*this};

  const Plan& plan() const { return frame.plan(); }
  const Schedule& schedule() const { return frame.schedule(); }

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
// The VkImage of each copy of `planned` (no memory yet), appended to e.res.images; on error none.
Status createImages(EffectState& e, const PlannedImage& planned);
// Memory for every image not bound yet (one block per memory type, shared), then their views.
Status bindImages(EffectState& e);
Status createParamBuffer(EffectState& e, std::uint32_t slots, ParamBuffer& out);  // on error: `out` unchanged

// ---- pipelines.cpp
Status createSampler(EffectState& e);
Status ensurePipeline(EffectState& e, const gen::PassInfo& pass, const gen::PassVariantInfo& variant);
const PipelineEntry* findPipeline(const EffectState& e, const gen::PassVariantInfo* variant);
// Pool and sets for the schedule, `slots` ring slots (pipelines must exist). On error: `out` unchanged.
Status createDescriptors(EffectState& e, const Schedule& schedule, std::uint32_t slots, Descriptors& out);
void writeDescriptors(EffectState& e, std::uint32_t slot, std::uint32_t historyParity, const Inputs& inputs,
                      const OutputTarget& output);

// ---- record.cpp
// record()'s and measure()'s body: the frame's configuration from its images, checked, planned
// when it must be (FrameState::render) and run into `rec` (its command buffer, timestamps, ...).
Status runFrame(EffectState& e, const Camera& camera, const Settings& settings, const Inputs& inputs,
                const OutputImage* userOutput, Recording rec);

// ---- timing.cpp
// The timestamp pool for `framesInFlight` ring slots; none (and success) where the queue family
// has no timestamps. On error: `out` unchanged.
Status createQueryPool(const EffectState& e, std::uint32_t framesInFlight, Handle<VkQueryPool>& out);
std::uint32_t queriesPerRegion();
bool familyHasTimestamps(const EffectState& e);

// ---- effect.cpp
// "Inputs::<name>": how messages name an input.
inline std::string inputName(gen::ResourceId id) {
  return "Inputs::" + std::string(gen::kResources[static_cast<std::size_t>(id)].name);
}
// A frame configuration against the device and the effect's contract (sao/inputs.h): each input's
// format, the depth's samples, the output's format; and the plan inputs it gives.
Status checkFrameConfig(const EffectState& e, const FrameConfig& frame, const Camera& camera, PlanInputs& out);
// What the depth input holds: R32_SFLOAT is linear z, every other depth format hardware depth.
inline DepthEncoding depthEncodingOf(VkFormat depthFormat) {
  return depthFormat == VK_FORMAT_R32_SFLOAT ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
}
// The colour inputs' formats against the channels `camera` reads (sao/inputs.h: the normals'
// follow Camera::normalsEncoding). Builds a message only on failure (every record() calls it).
Status checkColourInputs(const InputFormats& formats, const Camera& camera);
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
