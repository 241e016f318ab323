// The Vulkan depth-only prepass: the scene mesh drawn by a pipeline without a fragment shader into
// a D32_SFLOAT image (reversed-Z: cleared to 0, GREATER), left in DEPTH_STENCIL_READ_ONLY_OPTIMAL
// and visible to compute and fragment shaders, where sao::vk::Effect and the composite read it.
#pragma once
#include <glm/glm.hpp>

#include "sao/scenes/mesh.h"
#include "vk_context.h"

namespace sao::viewer {

class VkPrepass {
 public:
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

  Status init(VkContext& context);
  void destroy();
  Status setMesh(const scenes::Mesh& mesh);  // not while a frame that draws it is pending
  Status resize(VkExtent2D extent);          // not while a frame that uses the depth is pending
  void record(VkCommandBuffer cmd, const glm::dmat4& mvp);  // outside a render pass
  VkImageView depthView() const { return depth_.view; }
  VkExtent2D extent() const { return depth_.extent; }

 private:
  Status createRenderPass();
  Status createPipeline();
  VkContext* context_ = nullptr;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  vkx::Image depth_;
  vkx::Buffer vertices_, indices_;
  std::uint32_t indexCount_ = 0;
};

}  // namespace sao::viewer
