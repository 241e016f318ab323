// Images and buffers for the Vulkan prepass, allocated on the device of a headless context (the
// context's own helpers are private to it). Every object is destroyed by destroy(); destroying a
// default-constructed one is a no-op.
#pragma once
#include <vulkan/vulkan_core.h>

#include <string>

#include "sao/plan.h"
#include "sao/status.h"

namespace sao::prepass::detail {

Status vkCheck(VkResult result, const std::string& what);

struct VkImageRes {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

struct VkBufferRes {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;  // host-visible, coherent, mapped for its lifetime
  VkDeviceSize size = 0;
};

class VkAllocator {
 public:
  void init(VkPhysicalDevice physical, VkDevice device);
  // A 2D optimal-tiling image in device-local memory with one view of `aspect`.
  Status createImage(VkFormat format, Extent extent, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                     VkImageRes& out) const;
  // A host-visible, coherent, persistently mapped buffer.
  Status createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, VkBufferRes& out) const;
  void destroy(VkImageRes& image) const;
  void destroy(VkBufferRes& buffer) const;
  VkDevice device() const { return device_; }

 private:
  int memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const;
  VkDevice device_ = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory_{};
};

}  // namespace sao::prepass::detail
