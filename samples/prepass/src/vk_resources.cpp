#include "vk_resources.h"

namespace sao::prepass::detail {

Status vkCheck(VkResult r, const std::string& what) {
  if (r == VK_SUCCESS) return Status::success();
  return Status::error(StatusCode::DriverError, "prepass: " + what + " failed: VkResult " + std::to_string(int(r)));
}

void VkAllocator::init(VkPhysicalDevice physical, VkDevice device) {
  device_ = device;
  vkGetPhysicalDeviceMemoryProperties(physical, &memory_);
}

int VkAllocator::memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const {
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & flags) == flags) return int(i);
  return -1;
}

Status VkAllocator::createImage(VkFormat format, Extent extent, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                                VkImageRes& out) const {
  out = VkImageRes{};
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {extent.width, extent.height, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (Status s = vkCheck(vkCreateImage(device_, &ci, nullptr, &out.image), "vkCreateImage"); !s) return s;
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device_, out.image, &req);
  int type = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (type < 0) type = memoryType(req.memoryTypeBits, 0);
  if (type < 0) {
    destroy(out);
    return Status::error(StatusCode::DriverError, "prepass: no memory type for an image");
  }
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, std::uint32_t(type)};
  Status s = vkCheck(vkAllocateMemory(device_, &ai, nullptr, &out.memory), "vkAllocateMemory (image)");
  if (s) s = vkCheck(vkBindImageMemory(device_, out.image, out.memory, 0), "vkBindImageMemory");
  if (s) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = out.image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {aspect, 0, 1, 0, 1};
    s = vkCheck(vkCreateImageView(device_, &vi, nullptr, &out.view), "vkCreateImageView");
  }
  if (!s) destroy(out);
  return s;
}

Status VkAllocator::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, VkBufferRes& out) const {
  out = VkBufferRes{};
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = size;
  bi.usage = usage;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  if (Status s = vkCheck(vkCreateBuffer(device_, &bi, nullptr, &out.buffer), "vkCreateBuffer"); !s) return s;
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, out.buffer, &req);
  const int type =
      memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  if (type < 0) {
    destroy(out);
    return Status::error(StatusCode::DriverError, "prepass: no host-visible coherent memory for a buffer");
  }
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, std::uint32_t(type)};
  Status s = vkCheck(vkAllocateMemory(device_, &ai, nullptr, &out.memory), "vkAllocateMemory (buffer)");
  if (s) s = vkCheck(vkBindBufferMemory(device_, out.buffer, out.memory, 0), "vkBindBufferMemory");
  if (s) s = vkCheck(vkMapMemory(device_, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped), "vkMapMemory");
  if (!s) {
    destroy(out);
    return s;
  }
  out.size = size;
  return Status::success();
}

void VkAllocator::destroy(VkImageRes& i) const {
  if (i.view) vkDestroyImageView(device_, i.view, nullptr);
  if (i.image) vkDestroyImage(device_, i.image, nullptr);
  if (i.memory) vkFreeMemory(device_, i.memory, nullptr);
  i = VkImageRes{};
}

void VkAllocator::destroy(VkBufferRes& b) const {
  if (b.buffer) vkDestroyBuffer(device_, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(device_, b.memory, nullptr);  // unmaps implicitly
  b = VkBufferRes{};
}

}  // namespace sao::prepass::detail
