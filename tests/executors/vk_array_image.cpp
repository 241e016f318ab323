// Moved from tests/vulkan/stereo_test.cpp; readLayer() copies the layer into a plain 2D image so
// the context's readback (layer 0 only) decodes every output format.
#include "vk_array_image.h"

#include <cstring>
#include <string>

#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Buffer;
using vk::headless::Image;

Status vkFail(const char* what, VkResult r) {
  return Status::error(StatusCode::DriverError, std::string(what) + " failed: VkResult " + std::to_string(int(r)));
}

VkImageMemoryBarrier layerBarrier(VkImage image, VkImageAspectFlags aspect, std::uint32_t layer, std::uint32_t layers,
                                  VkImageLayout from, VkImageLayout to, VkAccessFlags src, VkAccessFlags dst) {
  VkImageMemoryBarrier b = vk::headless::imageBarrier(image, aspect, from, to, src, dst);
  b.subresourceRange.baseArrayLayer = layer;
  b.subresourceRange.layerCount = layers;
  return b;
}

}  // namespace

void destroy(ArrayImage& a) {
  const VkDevice device = context().device();
  for (VkImageView v : a.views)
    if (v) vkDestroyImageView(device, v, nullptr);
  if (a.image) vkDestroyImage(device, a.image, nullptr);
  if (a.memory) vkFreeMemory(device, a.memory, nullptr);
  a = ArrayImage{};
}

Status createArrayImage(VkFormat format, Extent extent, std::uint32_t layers, VkImageUsageFlags usage,
                        VkImageAspectFlags aspect, ArrayImage& out) {
  destroy(out);
  const VkDevice device = context().device();
  out.format = format;
  out.extent = extent;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {extent.width, extent.height, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = layers;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (VkResult r = vkCreateImage(device, &ci, nullptr, &out.image); r != VK_SUCCESS) return vkFail("vkCreateImage", r);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, out.image, &req);
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(context().physicalDevice(), &mp);
  std::uint32_t type = 0;
  while (type < mp.memoryTypeCount && !(req.memoryTypeBits & (1u << type))) ++type;
  if (type == mp.memoryTypeCount) return Status::error(StatusCode::DriverError, "no memory type for the array image");
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
  if (VkResult r = vkAllocateMemory(device, &ai, nullptr, &out.memory); r != VK_SUCCESS)
    return vkFail("vkAllocateMemory", r);
  if (VkResult r = vkBindImageMemory(device, out.image, out.memory, 0); r != VK_SUCCESS)
    return vkFail("vkBindImageMemory", r);
  out.views.assign(layers, VK_NULL_HANDLE);
  for (std::uint32_t layer = 0; layer < layers; ++layer) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = out.image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {aspect, 0, 1, layer, 1};
    if (VkResult r = vkCreateImageView(device, &vi, nullptr, &out.views[layer]); r != VK_SUCCESS)
      return vkFail("vkCreateImageView", r);
  }
  return Status::success();
}

Status uploadDepthLayers(const std::vector<const DepthImage*>& depth, VkImageLayout layout, ArrayImage& out) {
  const Extent extent = depth.at(0)->extent;
  const auto layers = std::uint32_t(depth.size());
  const std::size_t n = std::size_t(extent.width) * extent.height;
  if (Status st = createArrayImage(VK_FORMAT_D32_SFLOAT, extent, layers,
                                   VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                   VK_IMAGE_ASPECT_DEPTH_BIT, out);
      !st)
    return st;
  Buffer staging;
  if (Status st = context().createBuffer(layers * n * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, staging); !st) return st;
  for (std::uint32_t layer = 0; layer < layers; ++layer)
    std::memcpy(static_cast<std::uint32_t*>(staging.mapped) + layer * n, depth[layer]->texels.data(), n * 4);
  const Status st = context().submit([&](VkCommandBuffer cmd) {
    const auto toDst = layerBarrier(out.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, layers, VK_IMAGE_LAYOUT_UNDEFINED,
                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &toDst);
    std::vector<VkBufferImageCopy> copies(layers);
    for (std::uint32_t layer = 0; layer < layers; ++layer) {
      copies[layer].bufferOffset = layer * n * 4;
      copies[layer].imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, layer, 1};
      copies[layer].imageExtent = {extent.width, extent.height, 1};
    }
    vkCmdCopyBufferToImage(cmd, staging.buffer, out.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layers, copies.data());
    const auto toRead = layerBarrier(out.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, layers, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                     layout, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &toRead);
  });
  context().destroy(staging);
  return st;
}

Status readLayer(const ArrayImage& image, std::uint32_t layer, VkImageLayout layout, VkPipelineStageFlags srcStages,
                 VkAccessFlags srcAccess, FloatImage& out) {
  Image copy;
  if (Status st = context().createStorageImage(image.format, image.extent, copy); !st) return st;
  Status st = context().submit([&](VkCommandBuffer cmd) {
    const VkImageMemoryBarrier pre[2] = {
        layerBarrier(image.image, VK_IMAGE_ASPECT_COLOR_BIT, layer, 1, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     srcAccess, VK_ACCESS_TRANSFER_READ_BIT),
        vk::headless::imageBarrier(copy.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT)};
    vkCmdPipelineBarrier(cmd, srcStages, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 2, pre);
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, layer, 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.extent = {image.extent.width, image.extent.height, 1};
    vkCmdCopyImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, copy.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   1, &region);
    // Back to `layout`; later work of any stage comes after the copy.
    const auto post = layerBarrier(image.image, VK_IMAGE_ASPECT_COLOR_BIT, layer, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   layout, 0, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &post);
  });
  if (st)
    st = context().readback(copy.image, image.format, image.extent, 0, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, out);
  context().destroy(copy);
  return st;
}

}  // namespace sao::vktest
