// The state behind sao::vk::Effect, shared by the source files that each own one responsibility:
// resources.cpp (images and the parameter buffer from the plan), pipelines.cpp (pipelines,
// layouts, descriptor sets), record.cpp (commands and barriers), timing.cpp (timestamps and the
// fence fallback), effect.cpp (creation, validation, update).
#pragma once
#include <vulkan/vulkan_core.h>

#include <array>
#include <string>
#include <vector>

#include "allocator.h"
#include "dispatch.h"
#include "sao/vulkan/effect.h"

namespace sao::vk {

// An effect-owned image with a view of every level (storage writes, per-level reads of the mips
// pass) and one of the whole chain (the sampled reads of later passes).
struct OwnedImage {
  gen::ResourceId id{};
  VkImage image = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  Extent extent;
  std::uint32_t levels = 1;
  VkImageView fullView = VK_NULL_HANDLE;
  std::vector<VkImageView> levelViews;
};

struct Resources {
  std::vector<OwnedImage> images;
  std::vector<Allocator::Block> memory;
  const OwnedImage* find(gen::ResourceId id) const {
    for (const auto& i : images)
      if (i.id == id) return &i;
    return nullptr;
  }
};

// The parameter block: one region per ring slot (stride aligned to minUniformBufferOffsetAlignment)
// in persistently mapped, host-coherent memory. record() copies gen::SaoParams as is into its
// slot's region (when it differs from what the region holds); the slot's descriptor sets read it.
struct ParamBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  std::vector<Allocator::Block> memory;
  char* mapped = nullptr;
  VkDeviceSize stride = 0;
  std::vector<ParamBlock> written;  // per slot, what its region holds
  std::vector<bool> valid;
};

struct PipelineEntry {
  const gen::PassVariantInfo* variant = nullptr;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
};

// What a ring slot's descriptor sets were last written with.
// One descriptor set per dispatch of every planned pass (mips: one per level), per ring slot.
struct Descriptors {
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::uint32_t setsPerSlot = 0;
  std::vector<VkDescriptorSet> sets;  // [slot * setsPerSlot + k], k in plan order
};

// The output record() writes this time: the effect's own or the user's.
struct OutputTarget {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

inline constexpr std::uint32_t kMaxFramesInFlight = 16;

// Hidden: only Effect's own members are exported.
struct __attribute__((visibility("hidden"))) Effect::Impl {
  DeviceContext ctx;
  Dispatch d;
  VkPhysicalDeviceProperties props{};
  VkPhysicalDeviceFeatures features{};
  VkPhysicalDeviceMemoryProperties memoryProps{};
  VkQueueFamilyProperties family{};

  Config config;
  Plan plan;
  ParamBlock params{};

  Allocator allocator;
  Resources res;
  ParamBuffer ubo;
  VkSampler sampler = VK_NULL_HANDLE;  // nearest, clamp to edge, every level
  std::vector<PipelineEntry> pipelines;
  Descriptors desc;

  // Timestamps: one region of (passes + 1) queries per ring slot, plus one for measure().
  VkQueryPool queryPool = VK_NULL_HANDLE;
  std::uint32_t queriesPerRegion = 0;
  std::uint32_t nextSlot = 0;
  int lastTimedRegion = -1;                    // region of the last timestamped record()
  std::vector<std::string> lastTimedPasses;    // its pass names, in order

  ~Impl();
  void destroyAll();
};

// ---- resources.cpp
VkFormat vkFormat(gen::Format format);
Status createResources(Effect::Impl& e, const Plan& plan, Resources& out);  // on error: destroy `out`
void destroyResources(Effect::Impl& e, Resources& res);
Status createParamBuffer(Effect::Impl& e, std::uint32_t slots, ParamBuffer& out);  // on error: destroy `out`
void destroyParamBuffer(Effect::Impl& e, ParamBuffer& ubo);
bool sameImages(const Plan& a, const Plan& b);

// ---- pipelines.cpp
Status createSampler(Effect::Impl& e);
Status ensurePipelines(Effect::Impl& e, const Plan& plan);  // every pass variant of the plan
const PipelineEntry* findPipeline(const Effect::Impl& e, const gen::PassVariantInfo* variant);
void destroyPipelines(Effect::Impl& e);
// Pool and sets for the plan, `slots` ring slots (pipelines must exist). On error: destroy `out`.
Status createDescriptors(Effect::Impl& e, const Plan& plan, std::uint32_t slots, Descriptors& out);
void destroyDescriptors(Effect::Impl& e, Descriptors& ds);
void writeDescriptors(Effect::Impl& e, std::uint32_t slot, const Inputs& inputs, const OutputTarget& output);

// ---- record.cpp
// timingRegion < 0: no timestamps.
void recordPrologue(const Effect::Impl& e, VkCommandBuffer cmd, const OutputTarget& output, int timingRegion);
void recordPass(const Effect::Impl& e, VkCommandBuffer cmd, std::size_t passIndex, std::uint32_t slot,
                const OutputTarget& output, int timingRegion);
void recordEpilogue(const Effect::Impl& e, VkCommandBuffer cmd, const OutputTarget& output);
Status checkInputs(const Effect::Impl& e, const Inputs& inputs, const OutputImage* userOutput, OutputTarget& out);
std::uint32_t acquireSlot(Effect::Impl& e, const Inputs& inputs, const OutputTarget& output);

// ---- timing.cpp
Status ensureQueryPool(Effect::Impl& e);
bool familyHasTimestamps(const Effect::Impl& e);

}  // namespace sao::vk
