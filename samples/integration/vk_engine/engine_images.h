// The engine's images and buffers, its own and the effect's alike: creation in device memory,
// destruction, and the image barriers it records.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "engine_device.h"
#include "sao/plan.h"  // Extent

namespace sao::vkengine {

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView whole = VK_NULL_HANDLE;  // every level: a read of the whole chain
  std::vector<VkImageView> levels;     // one per level: a write, or a read of one level
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;  // of the views
  Extent extent;
  void destroy(VkDevice device);  // an empty Image is a no-op; it comes back empty
};

// A 2D image of `levels` levels in device-local memory, optimal tiling, one sample; its views
// select `aspect`. Left in UNDEFINED. On failure `out` holds what was made (destroy() frees it).
Status makeImage(const Device& device, VkFormat format, VkImageAspectFlags aspect, Extent extent,
                 std::uint32_t levels, VkImageUsageFlags usage, Image& out);

// Host-visible, coherent and mapped: uploads, the parameter block, readbacks.
struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  void destroy(VkDevice device);
};
Status makeBuffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, Buffer& out);

// Levels [baseLevel, baseLevel + levels) of layer 0, no queue-family transfer.
VkImageMemoryBarrier imageBarrier(VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                                  VkAccessFlags src, VkAccessFlags dst, std::uint32_t baseLevel = 0,
                                  std::uint32_t levels = VK_REMAINING_MIP_LEVELS);
// One vkCmdPipelineBarrier for all of `barriers`; none recorded when it is empty.
void cmdBarriers(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst,
                 const std::vector<VkImageMemoryBarrier>& barriers);

// The aspects a barrier on an image of `format` names: depth and stencil together for a combined
// format (without separateDepthStencilLayouts a barrier must name both), depth, or colour.
VkImageAspectFlags barrierAspects(VkFormat format);

}  // namespace sao::vkengine
