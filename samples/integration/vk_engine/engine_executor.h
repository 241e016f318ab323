// The engine's sao::Executor: what FrameState asks for, in raw Vulkan. Effect images and their
// views in device memory, compute pipelines from the installed .spv files (not the library's
// embedded copies), one descriptor set per dispatch, the schedule's hazards as image barriers, the
// frame recorded into the device's one command buffer and waited for in endFrame().
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine_device.h"
#include "engine_images.h"
#include "sao/executor.h"
#include "sao_effect.h"

namespace sao::vkengine {

// An engine image behind an input or the output, as the effect sees it: sampled (inputs) or stored
// to (the output, GENERAL) in `layout`, which the engine keeps; `aspects` are its barriers'.
struct Target {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkImageAspectFlags aspects = VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};
// By resource id: the engine's inputs and output this frame (empty: not supplied).
using EngineImages = std::array<Target, gen::kResources.size()>;

class EngineExecutor final : public Executor {
 public:
  EngineExecutor(const Device& device, std::string shaderDir) : device_(device), shaderDir_(std::move(shaderDir)) {}
  Status init();  // the sampler and the parameter block's buffer
  ~EngineExecutor() override;
  EngineExecutor(const EngineExecutor&) = delete;
  EngineExecutor& operator=(const EngineExecutor&) = delete;

  // The engine's images of the next frames.
  void setEngineImages(const EngineImages& images) { engine_ = images; }

  Status checkPlan(const Plan& plan) override;
  Status preparePlan(const Plan& plan, const Schedule& schedule) override;
  Status createImage(const PlannedImage& image) override;
  void destroyImage(const PlannedImage& image) noexcept override;
  Status createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) override;
  Status beginFrame(const FrameWork& frame) override;
  void barrier(std::span<const Hazard> hazards) override;
  void dispatch(const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) override;
  Status endFrame() override;

  // Copy `copy` of the effect image made for `planned` (null: none), for a readback.
  const Image* image(const PlannedImage& planned, std::uint32_t copy) const;
  // The last frame's history parity (FrameWork::historyParity): which copy it wrote.
  std::uint32_t historyParity() const { return frame_.historyParity; }
  std::uint64_t imagesMade() const { return imagesMade_; }  // device images created so far, every copy
  std::uint64_t outputsMade() const { return outputsMade_; }  // of them, the effect's output images
  std::size_t pipelineCount() const { return pipelines_.size(); }

 private:
  struct Pipeline {
    const gen::PassVariantInfo* variant;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
  };
  struct Owned {
    PlannedImage planned;
    std::vector<Image> copies;
  };

  Target target(gen::ResourceId id, bool previousFrame) const;
  const Image* ownedCopy(gen::ResourceId id, bool previousFrame) const;
  Status ensurePool(const Schedule& schedule);

  const Device& device_;
  std::string shaderDir_;
  EngineImages engine_{};
  std::vector<Owned> owned_;                               // every effect image made, one Image per copy
  std::array<const Owned*, gen::kResources.size()> current_{};  // this frame's, by resource
  std::vector<Pipeline> pipelines_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  Buffer ubo_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::array<std::uint32_t, 3> poolSize_{};  // sets, sampled and storage descriptors it holds
  FrameWork frame_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  Status error_;  // of barrier() or dispatch(), which return none: endFrame() returns it
  std::uint64_t imagesMade_ = 0, outputsMade_ = 0;
};

}  // namespace sao::vkengine
