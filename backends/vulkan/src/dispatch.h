// The function table: every Vulkan entry point the library calls, loaded through the user's
// vkGetInstanceProcAddr / vkGetDeviceProcAddr (the library is built with VK_NO_PROTOTYPES and
// links no loader).
#pragma once
#include <vulkan/vulkan_core.h>

#include "sao/status.h"

namespace sao::vk {

struct DeviceContext;

#define SAO_VK_INSTANCE_FUNCTIONS(X)          \
  X(vkGetPhysicalDeviceProperties)            \
  X(vkGetPhysicalDeviceFeatures)              \
  X(vkGetPhysicalDeviceMemoryProperties)      \
  X(vkGetPhysicalDeviceFormatProperties)      \
  X(vkGetPhysicalDeviceQueueFamilyProperties)

#define SAO_VK_DEVICE_FUNCTIONS(X) \
  X(vkCreateImage)                 \
  X(vkDestroyImage)                \
  X(vkCreateImageView)             \
  X(vkDestroyImageView)            \
  X(vkCreateBuffer)                \
  X(vkDestroyBuffer)               \
  X(vkGetImageMemoryRequirements)  \
  X(vkGetBufferMemoryRequirements) \
  X(vkAllocateMemory)              \
  X(vkFreeMemory)                  \
  X(vkMapMemory)                   \
  X(vkUnmapMemory)                 \
  X(vkBindImageMemory)             \
  X(vkBindBufferMemory)            \
  X(vkCreateSampler)               \
  X(vkDestroySampler)              \
  X(vkCreateShaderModule)          \
  X(vkDestroyShaderModule)         \
  X(vkCreateDescriptorSetLayout)   \
  X(vkDestroyDescriptorSetLayout)  \
  X(vkCreatePipelineLayout)        \
  X(vkDestroyPipelineLayout)       \
  X(vkCreateComputePipelines)      \
  X(vkDestroyPipeline)             \
  X(vkCreateDescriptorPool)        \
  X(vkDestroyDescriptorPool)       \
  X(vkAllocateDescriptorSets)      \
  X(vkUpdateDescriptorSets)        \
  X(vkCreateQueryPool)             \
  X(vkDestroyQueryPool)            \
  X(vkGetQueryPoolResults)         \
  X(vkCreateCommandPool)           \
  X(vkDestroyCommandPool)          \
  X(vkAllocateCommandBuffers)      \
  X(vkFreeCommandBuffers)          \
  X(vkBeginCommandBuffer)          \
  X(vkEndCommandBuffer)            \
  X(vkQueueSubmit)                 \
  X(vkCreateFence)                 \
  X(vkDestroyFence)                \
  X(vkWaitForFences)               \
  X(vkResetFences)                 \
  X(vkCmdResetQueryPool)           \
  X(vkCmdWriteTimestamp)           \
  X(vkCmdPipelineBarrier)          \
  X(vkCmdPushConstants)            \
  X(vkCmdBindPipeline)             \
  X(vkCmdBindDescriptorSets)       \
  X(vkCmdDispatch)

struct Dispatch {
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
  PFN_vkGetDeviceProcAddr vkGetDeviceProcAddr = nullptr;
#define SAO_VK_DECLARE(name) PFN_##name name = nullptr;
  SAO_VK_INSTANCE_FUNCTIONS(SAO_VK_DECLARE)
  SAO_VK_DEVICE_FUNCTIONS(SAO_VK_DECLARE)
#undef SAO_VK_DECLARE
  // Optional (VK_EXT_debug_utils, when the instance has it): pass names in captures.
  PFN_vkCmdBeginDebugUtilsLabelEXT vkCmdBeginDebugUtilsLabelEXT = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT vkCmdEndDebugUtilsLabelEXT = nullptr;

  // Loads every function; DriverError naming the first one that is missing.
  Status load(const DeviceContext& context);
};

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" etc.
const char* resultName(VkResult result);

// DriverError "<what> failed: <VkResult>".
Status vkError(const char* what, VkResult result);

}  // namespace sao::vk
