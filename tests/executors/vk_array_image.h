// Array images on the Vulkan test context, for stereo (Frame::depthLayers; tests/vulkan/stereo_test.cpp):
// one image of several layers with one VK_IMAGE_VIEW_TYPE_2D view per layer (what sao::vk takes:
// a view cannot show a layer otherwise), a depth array uploaded from host images, one layer read back.
#pragma once
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <vector>

#include "sao/image.h"
#include "sao/status.h"

namespace sao::vktest {

struct ArrayImage {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  std::vector<VkImageView> views;  // views[i] shows layer i
  VkFormat format = VK_FORMAT_UNDEFINED;
  Extent extent;
};

// The caller's output array: written by the effect, read back by readLayer().
inline constexpr VkImageUsageFlags kOutputArrayUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;

// `layers` layers, one level, left UNDEFINED.
Status createArrayImage(VkFormat format, Extent extent, std::uint32_t layers, VkImageUsageFlags usage,
                        VkImageAspectFlags aspect, ArrayImage& out);
void destroy(ArrayImage& image);  // an empty one is a no-op; it comes back empty

// A new D32_SFLOAT array whose layer i holds *depth[i] (D32F texels, one extent), left in `layout`
// and visible to compute-shader reads.
Status uploadDepthLayers(const std::vector<const DepthImage*>& depth, VkImageLayout layout, ArrayImage& out);

// Layer `layer` of a colour array that record() left in `layout` (written at srcStages / srcAccess),
// read back as floats in its format's channels; the layer goes back to `layout`.
Status readLayer(const ArrayImage& image, std::uint32_t layer, VkImageLayout layout, VkPipelineStageFlags srcStages,
                 VkAccessFlags srcAccess, FloatImage& out);

}  // namespace sao::vktest
