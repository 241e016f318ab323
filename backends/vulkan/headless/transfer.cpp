// Uploads (depth through vkCmdCopyBufferToImage, colour images) and read-backs of the headless
// helper.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "sao/vulkan/headless.h"

namespace sao::vk::headless {
namespace {

Status vkFail(const std::string& what, VkResult r) {
  return Status::error(StatusCode::DriverError, what + " failed: VkResult " + std::to_string(static_cast<int>(r)));
}

bool hasStencil(VkFormat f) { return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT; }
bool isDepth(VkFormat f) {
  return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_X8_D24_UNORM_PACK32 || f == VK_FORMAT_D32_SFLOAT || hasStencil(f);
}

std::uint32_t channelsOf(VkFormat f, std::uint32_t& bytes) {
  switch (f) {
    case VK_FORMAT_R16_SFLOAT: bytes = 2; return 1;
    case VK_FORMAT_R32_SFLOAT: bytes = 4; return 1;
    case VK_FORMAT_R16G16_SFLOAT: bytes = 4; return 2;
    case VK_FORMAT_R32G32_SFLOAT: bytes = 8; return 2;
    case VK_FORMAT_R16G16B16A16_SFLOAT: bytes = 8; return 4;
    case VK_FORMAT_R32G32B32A32_SFLOAT: bytes = 16; return 4;
    case VK_FORMAT_R8_UNORM: bytes = 1; return 1;
    case VK_FORMAT_R8G8B8A8_UNORM: bytes = 4; return 4;
    default: bytes = 0; return 0;
  }
}

// Level 0 of `image` (UNDEFINED) from the staging buffer, left in `layout` for compute and
// fragment reads. `barrierAspects` covers every aspect of the format, `copyAspect` the one copied.
void recordUpload(VkCommandBuffer cmd, VkBuffer staging, VkImage image, VkImageAspectFlags barrierAspects,
                  VkImageAspectFlags copyAspect, Extent extent, VkImageLayout layout) {
  const auto toDst = imageBarrier(image, barrierAspects, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                  0, VK_ACCESS_TRANSFER_WRITE_BIT);
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                       1, &toDst);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {copyAspect, 0, 0, 1};
  copy.imageExtent = {extent.width, extent.height, 1};
  vkCmdCopyBufferToImage(cmd, staging, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  const auto toRead = imageBarrier(image, barrierAspects, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layout,
                                   VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &toRead);
}

}  // namespace

int Context::memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const {
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & flags) == flags) return static_cast<int>(i);
  return -1;
}

Status Context::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, Buffer& out) {
  out = Buffer{};
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = size;
  bi.usage = usage;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  if (VkResult r = vkCreateBuffer(device_, &bi, nullptr, &out.buffer); r != VK_SUCCESS) return vkFail("vkCreateBuffer", r);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, out.buffer, &req);
  const int type = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  Status st = type < 0 ? Status::error(StatusCode::DriverError, "no host-visible coherent memory for a buffer")
                       : Status::success();
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, static_cast<std::uint32_t>(type)};
  if (st)
    if (VkResult r = vkAllocateMemory(device_, &ai, nullptr, &out.memory); r != VK_SUCCESS) st = vkFail("vkAllocateMemory", r);
  if (st)
    if (VkResult r = vkBindBufferMemory(device_, out.buffer, out.memory, 0); r != VK_SUCCESS)
      st = vkFail("vkBindBufferMemory", r);
  if (st)
    if (VkResult r = vkMapMemory(device_, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped); r != VK_SUCCESS)
      st = vkFail("vkMapMemory", r);
  if (!st) destroy(out);
  else out.size = size;
  return st;
}

void Context::destroy(Buffer& buffer) {
  if (buffer.buffer) vkDestroyBuffer(device_, buffer.buffer, nullptr);
  if (buffer.memory) vkFreeMemory(device_, buffer.memory, nullptr);  // unmaps it
  buffer = Buffer{};
}

Status Context::createImage(VkFormat format, Extent extent, VkImageUsageFlags usage, VkImageAspectFlags viewAspect,
                            Image& out) {
  out = Image{};
  out.format = format;
  out.extent = extent;
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
  if (VkResult r = vkCreateImage(device_, &ci, nullptr, &out.image); r != VK_SUCCESS) {
    out = Image{};
    return vkFail("vkCreateImage", r);
  }
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device_, out.image, &req);
  int type = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (type < 0) type = memoryType(req.memoryTypeBits, 0);
  if (type < 0) {
    destroy(out);
    return Status::error(StatusCode::DriverError, "no memory type for an image");
  }
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, static_cast<std::uint32_t>(type)};
  if (VkResult r = vkAllocateMemory(device_, &ai, nullptr, &out.memory); r != VK_SUCCESS) {
    destroy(out);
    return vkFail("vkAllocateMemory", r);
  }
  if (VkResult r = vkBindImageMemory(device_, out.image, out.memory, 0); r != VK_SUCCESS) {
    destroy(out);
    return vkFail("vkBindImageMemory", r);
  }
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = out.image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = format;
  vi.subresourceRange = {viewAspect, 0, 1, 0, 1};
  if (VkResult r = vkCreateImageView(device_, &vi, nullptr, &out.view); r != VK_SUCCESS) {
    destroy(out);
    return vkFail("vkCreateImageView", r);
  }
  return Status::success();
}

void Context::destroy(Image& image) {
  if (image.view) vkDestroyImageView(device_, image.view, nullptr);
  if (image.image) vkDestroyImage(device_, image.image, nullptr);
  if (image.memory) vkFreeMemory(device_, image.memory, nullptr);
  image = Image{};
}

Status Context::uploadDepth(const DepthImage& depth, VkFormat format, VkImageLayout layout, Image& out) {
  const std::size_t n = std::size_t(depth.extent.width) * depth.extent.height;
  if (n == 0 || depth.texels.size() != n)
    return Status::error(StatusCode::InvalidInput, "uploadDepth: the texels do not match the extent");
  bool match = false;
  switch (depth.format) {
    case DepthFormat::D16: match = format == VK_FORMAT_D16_UNORM; break;
    case DepthFormat::D24: match = format == VK_FORMAT_X8_D24_UNORM_PACK32 || format == VK_FORMAT_D24_UNORM_S8_UINT; break;
    case DepthFormat::D32F: match = format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D32_SFLOAT_S8_UINT; break;
    case DepthFormat::LinearZ: match = format == VK_FORMAT_R32_SFLOAT; break;
  }
  if (!match)
    return Status::error(StatusCode::InvalidInput, std::string("uploadDepth: a ") + sao::toString(depth.format) +
                                                       " image cannot go into VkFormat " + std::to_string(format));
  const bool depthFormat = isDepth(format);
  const VkImageAspectFlags viewAspect = depthFormat ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  const VkImageAspectFlags allAspects = hasStencil(format) ? (VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT) : viewAspect;
  const std::size_t texelBytes = format == VK_FORMAT_D16_UNORM ? 2 : 4;

  Buffer staging;
  if (Status st = createBuffer(n * texelBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, staging); !st) return st;
  void* mapped = staging.mapped;
  if (texelBytes == 2) {
    auto* p = static_cast<std::uint16_t*>(mapped);
    for (std::size_t i = 0; i < n; ++i) p[i] = static_cast<std::uint16_t>(depth.texels[i]);
  } else {
    auto* p = static_cast<std::uint32_t*>(mapped);
    const std::uint32_t mask = depth.format == DepthFormat::D24 ? 0xffffffu : 0xffffffffu;
    for (std::size_t i = 0; i < n; ++i) p[i] = depth.texels[i] & mask;
  }

  const VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                  (depthFormat ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : 0);
  if (Status st = createImage(format, depth.extent, usage, viewAspect, out); !st) {
    destroy(staging);
    return st;
  }
  Status st = submit([&](VkCommandBuffer cmd) {
    recordUpload(cmd, staging.buffer, out.image, allAspects, viewAspect, depth.extent, layout);
  });
  destroy(staging);
  if (!st) {
    destroy(out);
    return st;
  }
  out.layout = layout;
  return Status::success();
}

Status Context::uploadColor(const FloatImage& image, VkFormat format, VkImageLayout layout, Image& out,
                            VkImageUsageFlags extraUsage) {
  std::uint32_t bytes = 0;
  const std::uint32_t channels = channelsOf(format, bytes);
  const std::size_t n = std::size_t(image.extent.width) * image.extent.height;
  if (channels == 0 || image.channels != channels || image.data.size() != n * channels || n == 0)
    return Status::error(StatusCode::InvalidInput, "uploadColor: the image does not match the format's channels");
  Buffer staging;
  if (Status st = createBuffer(n * bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, staging); !st) return st;
  void* mapped = staging.mapped;
  const std::uint32_t size = bytes / channels;  // 1: 8-bit UNORM, 2: binary16, 4: float
  for (std::size_t i = 0; i < n * channels; ++i) {
    if (size == 1)
      static_cast<std::uint8_t*>(mapped)[i] =
          static_cast<std::uint8_t>(std::lround(std::clamp(image.data[i], 0.0f, 1.0f) * 255.0f));
    else if (size == 2) static_cast<std::uint16_t*>(mapped)[i] = sao::halfBits(image.data[i]);
    else static_cast<float*>(mapped)[i] = image.data[i];
  }
  if (Status st = createImage(format, image.extent,
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                  extraUsage,
                              VK_IMAGE_ASPECT_COLOR_BIT, out);
      !st) {
    destroy(staging);
    return st;
  }
  Status st = submit([&](VkCommandBuffer cmd) {
    recordUpload(cmd, staging.buffer, out.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_COLOR_BIT, image.extent,
                 layout);
  });
  destroy(staging);
  if (!st) {
    destroy(out);
    return st;
  }
  out.layout = layout;
  return Status::success();
}

Status Context::createStorageImage(VkFormat format, Extent extent, Image& out) {
  return createImage(format, extent,
                     VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                         VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                     VK_IMAGE_ASPECT_COLOR_BIT, out);
}

Status Context::readback(VkImage image, VkFormat format, Extent levelZero, std::uint32_t level, VkImageLayout layout,
                         VkPipelineStageFlags srcStages, VkAccessFlags srcAccess, FloatImage& out) {
  std::uint32_t bytes = 0;
  const std::uint32_t channels = channelsOf(format, bytes);
  if (channels == 0 || image == VK_NULL_HANDLE)
    return Status::error(StatusCode::UnsupportedFormat, "readback: unsupported format or null image");
  const Extent e = levelExtent(levelZero, level);
  const std::size_t n = std::size_t(e.width) * e.height;
  Buffer staging;
  if (Status st = createBuffer(n * bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, staging); !st) return st;
  // Always through TRANSFER_SRC_OPTIMAL (copies from GENERAL draw a performance warning).
  const VkImageLayout copyLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  Status st = submit([&](VkCommandBuffer cmd) {
    auto pre = imageBarrier(image, VK_IMAGE_ASPECT_COLOR_BIT, layout, copyLayout, srcAccess, VK_ACCESS_TRANSFER_READ_BIT,
                       level, 1);
    vkCmdPipelineBarrier(cmd, srcStages, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &pre);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
    copy.imageExtent = {e.width, e.height, 1};
    vkCmdCopyImageToBuffer(cmd, image, copyLayout, staging.buffer, 1, &copy);
    // Back to the caller's layout; later work of any stage comes after the copy.
    auto post = imageBarrier(image, VK_IMAGE_ASPECT_COLOR_BIT, copyLayout, layout, 0,
                        VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT, level, 1);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &post);
    VkBufferMemoryBarrier host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    host.buffer = staging.buffer;
    host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &host, 0,
                         nullptr);
  });
  if (!st) {
    destroy(staging);
    return st;
  }
  out = FloatImage(e, channels);
  void* mapped = staging.mapped;
  const std::uint32_t size = bytes / channels;
  for (std::size_t i = 0; i < n * channels; ++i)
    out.data[i] = size == 1   ? float(static_cast<const std::uint8_t*>(mapped)[i]) / 255.0f
                  : size == 2 ? sao::halfToFloat(static_cast<const std::uint16_t*>(mapped)[i])
                              : static_cast<const float*>(mapped)[i];
  destroy(staging);
  return Status::success();
}

}  // namespace sao::vk::headless
