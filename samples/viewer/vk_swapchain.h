// The window's swapchain, the render pass the composite and ImGui draw in (one colour attachment,
// left in PRESENT_SRC_KHR) and a framebuffer and a "render finished" semaphore per image.
#pragma once
#include <vulkan/vulkan.h>

#include <vector>

#include "sao/vulkan/headless.h"
#include "vk_util.h"

namespace sao::viewer {

class VkSwapchain {
 public:
  // Creates the render pass (once) and the swapchain for the surface's current size (or
  // `width` x `height` where the surface leaves it to us); recreates when called again.
  Status create(vk::headless::Context& context, std::uint32_t width, std::uint32_t height, bool vsync);
  void destroy();  // everything, the render pass included

  VkSwapchainKHR handle = VK_NULL_HANDLE;
  VkRenderPass renderPass = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{0, 0};
  std::uint32_t minImageCount = 2;
  bool transferSrc = false;  // images can be copied from (screenshots)
  bool bgra = false;         // B8G8R8A8 byte order
  std::vector<VkImage> images;
  std::vector<VkFramebuffer> framebuffers;
  std::vector<VkSemaphore> renderFinished;

 private:
  Status createRenderPass();
  void destroyImages();
  vk::headless::Context* context_ = nullptr;
  std::vector<VkImageView> views_;
};

}  // namespace sao::viewer
