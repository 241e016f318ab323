// The harness's host formats as VkFormats, for the two Vulkan executors (the library's and the
// engine-side example's).
#pragma once
#include <vulkan/vulkan_core.h>

#include "harness.h"

namespace sao::exectest {

inline VkFormat vkDepth(Depth d) {
  switch (d) {
    case Depth::D16: return VK_FORMAT_D16_UNORM;
    case Depth::D24: return VK_FORMAT_X8_D24_UNORM_PACK32;
    case Depth::D24S8: return VK_FORMAT_D24_UNORM_S8_UINT;
    case Depth::D32F: return VK_FORMAT_D32_SFLOAT;
    case Depth::D32FS8: return VK_FORMAT_D32_SFLOAT_S8_UINT;
    case Depth::R32F: return VK_FORMAT_R32_SFLOAT;
  }
  return VK_FORMAT_D32_SFLOAT;
}

inline VkFormat vkTexels(Texels t) {
  switch (t) {
    case Texels::RGBA16F: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case Texels::RGBA32F: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case Texels::RG16F: return VK_FORMAT_R16G16_SFLOAT;
    case Texels::RG32F: return VK_FORMAT_R32G32_SFLOAT;
  }
  return VK_FORMAT_R16G16B16A16_SFLOAT;
}

}  // namespace sao::exectest
