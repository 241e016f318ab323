// Small Vulkan helpers of the viewer: VkResult to Status, shader modules.
#pragma once
#include <vulkan/vulkan.h>

#include "sao/status.h"

namespace sao::viewer::vkx {

Status check(VkResult result, const char* what);
#define SAO_VIEWER_VK(expr) \
  if (::sao::Status vk_status_ = ::sao::viewer::vkx::check((expr), #expr); !vk_status_) return vk_status_

VkShaderModule shaderModule(VkDevice device, const std::uint32_t* code, std::size_t bytes);

}  // namespace sao::viewer::vkx
