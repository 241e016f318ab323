#include "engine_images.h"

namespace sao::vkengine {

void Image::destroy(VkDevice device) {
  for (VkImageView v : levels) vkDestroyImageView(device, v, nullptr);
  vkDestroyImageView(device, whole, nullptr);
  vkDestroyImage(device, image, nullptr);
  vkFreeMemory(device, memory, nullptr);
  *this = {};
}

Status makeImage(const Device& device, VkFormat format, VkImageAspectFlags aspect, Extent extent,
                 std::uint32_t levels, VkImageUsageFlags usage, Image& out) {
  const VkDevice d = device.device();
  out.format = format;
  out.aspect = aspect;
  out.extent = extent;
  const VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, nullptr, 0, VK_IMAGE_TYPE_2D, format,
                               {extent.width, extent.height, 1}, levels, 1, VK_SAMPLE_COUNT_1_BIT,
                               VK_IMAGE_TILING_OPTIMAL, usage};
  SAO_ENGINE_VK_TRY(vkCreateImage(d, &info, nullptr, &out.image));
  VkMemoryRequirements needs;
  vkGetImageMemoryRequirements(d, out.image, &needs);
  if (Status st = device.allocate(needs, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, out.memory); !st) return st;
  SAO_ENGINE_VK_TRY(vkBindImageMemory(d, out.image, out.memory, 0));
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, out.image, VK_IMAGE_VIEW_TYPE_2D,
                             format, {}, {aspect, 0, levels, 0, 1}};
  SAO_ENGINE_VK_TRY(vkCreateImageView(d, &view, nullptr, &out.whole));
  out.levels.assign(levels, VK_NULL_HANDLE);
  for (std::uint32_t m = 0; m < levels; ++m) {
    view.subresourceRange = {aspect, m, 1, 0, 1};
    SAO_ENGINE_VK_TRY(vkCreateImageView(d, &view, nullptr, &out.levels[m]));
  }
  return Status::success();
}

void Buffer::destroy(VkDevice device) {
  vkDestroyBuffer(device, buffer, nullptr);
  vkFreeMemory(device, memory, nullptr);  // unmaps it
  *this = {};
}

Status makeBuffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, Buffer& out) {
  const VkDevice d = device.device();
  const VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, usage};
  SAO_ENGINE_VK_TRY(vkCreateBuffer(d, &info, nullptr, &out.buffer));
  VkMemoryRequirements needs;
  vkGetBufferMemoryRequirements(d, out.buffer, &needs);
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if (Status st = device.allocate(needs, host, out.memory); !st) return st;
  SAO_ENGINE_VK_TRY(vkBindBufferMemory(d, out.buffer, out.memory, 0));
  SAO_ENGINE_VK_TRY(vkMapMemory(d, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped));
  return Status::success();
}

VkImageMemoryBarrier imageBarrier(VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                                  VkAccessFlags src, VkAccessFlags dst, std::uint32_t baseLevel, std::uint32_t levels) {
  return {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, src, dst, from, to, VK_QUEUE_FAMILY_IGNORED,
          VK_QUEUE_FAMILY_IGNORED, image, {aspect, baseLevel, levels, 0, 1}};
}

void cmdBarriers(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst,
                 const std::vector<VkImageMemoryBarrier>& barriers) {
  if (!barriers.empty())
    vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, std::uint32_t(barriers.size()), barriers.data());
}

VkImageAspectFlags barrierAspects(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D32_SFLOAT: return VK_IMAGE_ASPECT_DEPTH_BIT;
    default: return VK_IMAGE_ASPECT_COLOR_BIT;
  }
}

}  // namespace sao::vkengine
