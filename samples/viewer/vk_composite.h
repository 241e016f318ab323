// The Vulkan composite: shaders/composite.frag on a fullscreen triangle in the swapchain's render
// pass, with the depth, the effect's output and intermediates (own views of its images) and the
// reference bound as combined image samplers; missing inputs get a 1x1 white image.
#pragma once
#include "sao/image.h"
#include "viewer_types.h"
#include "sao/vulkan/headless.h"
#include "vk_util.h"

namespace sao::viewer {

struct VkCompositeInputs {
  VkImageView depth = VK_NULL_HANDLE;  // DEPTH_STENCIL_READ_ONLY_OPTIMAL
  VkImageView ao = VK_NULL_HANDLE;     // SHADER_READ_ONLY_OPTIMAL; null: white
  VkImageView aoRaw = VK_NULL_HANDLE;  // GENERAL; null: white
  VkImageView csz = VK_NULL_HANDLE;    // GENERAL, every level; null: white
  // Split-resolution: the reduced-resolution AO (ao is the full one), SHADER_READ_ONLY_OPTIMAL; null: white
  VkImageView aoReduced = VK_NULL_HANDLE;
};

class VkComposite {
 public:
  Status init(vk::headless::Context& context, VkRenderPass renderPass);
  void destroy();
  // Not while a frame that uses them is pending; setInputs() before the set is bound in the
  // frame's command buffer.
  Status setReference(const FloatImage* reference);
  void setInputs(const VkCompositeInputs& inputs);
  // Inside the render pass.
  void record(VkCommandBuffer cmd, const CompositeParams& params, VkExtent2D extent);

 private:
  Status createDescriptors();
  Status createPipeline(VkRenderPass renderPass);
  void writeDescriptors();
  vk::headless::Context* context_ = nullptr;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkSampler sampler_ = VK_NULL_HANDLE;
  vk::headless::Buffer params_;
  vk::headless::Image white_, reference_;
  VkCompositeInputs inputs_;
  bool written_ = false;
};

}  // namespace sao::viewer
