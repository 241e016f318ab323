// Small Vulkan helpers of the viewer: VkResult to Status, buffers and images with their memory.
#pragma once
#include <vulkan/vulkan.h>

#include "sao/status.h"

namespace sao::viewer::vkx {

Status check(VkResult result, const char* what);
#define SAO_VIEWER_VK(expr) \
  if (::sao::Status vk_status_ = ::sao::viewer::vkx::check((expr), #expr); !vk_status_) return vk_status_

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;  // host-visible, coherent, persistently mapped
  VkDeviceSize size = 0;
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{0, 0};
};

// A barrier for one image's first mip level and array layer.
VkImageMemoryBarrier imageBarrier(VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                                  VkAccessFlags srcAccess, VkAccessFlags dstAccess);

VkShaderModule shaderModule(VkDevice device, const std::uint32_t* code, std::size_t bytes);

}  // namespace sao::viewer::vkx
