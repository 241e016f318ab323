#include "dispatch.h"

#include <string>

#include "sao/vulkan/effect.h"

namespace sao::vk {

Status Dispatch::load(const DeviceContext& c) {
  if (!c.getInstanceProcAddr)
    return Status::error(StatusCode::InvalidInput, "DeviceContext::getInstanceProcAddr is null");
  if (c.instance == VK_NULL_HANDLE || c.physicalDevice == VK_NULL_HANDLE || c.device == VK_NULL_HANDLE)
    return Status::error(StatusCode::InvalidInput,
                         "DeviceContext needs a VkInstance, a VkPhysicalDevice and a VkDevice (one is VK_NULL_HANDLE)");
  vkGetInstanceProcAddr = c.getInstanceProcAddr;
  vkGetDeviceProcAddr = c.getDeviceProcAddr;
  if (!vkGetDeviceProcAddr)
    vkGetDeviceProcAddr =
        reinterpret_cast<PFN_vkGetDeviceProcAddr>(vkGetInstanceProcAddr(c.instance, "vkGetDeviceProcAddr"));
  if (!vkGetDeviceProcAddr)
    return Status::error(StatusCode::DriverError, "vkGetDeviceProcAddr could not be loaded from the instance");

#define SAO_VK_LOAD_INSTANCE(name)                                                                    \
  name = reinterpret_cast<PFN_##name>(vkGetInstanceProcAddr(c.instance, #name));                     \
  if (!name) return Status::error(StatusCode::DriverError, "the instance does not provide " #name);
  SAO_VK_INSTANCE_FUNCTIONS(SAO_VK_LOAD_INSTANCE)
#undef SAO_VK_LOAD_INSTANCE

#define SAO_VK_LOAD_DEVICE(name)                                                                    \
  name = reinterpret_cast<PFN_##name>(vkGetDeviceProcAddr(c.device, #name));                      \
  if (!name) return Status::error(StatusCode::DriverError, "the device does not provide " #name);
  SAO_VK_DEVICE_FUNCTIONS(SAO_VK_LOAD_DEVICE)
#undef SAO_VK_LOAD_DEVICE

  // Debug labels (VK_EXT_debug_utils): only when the caller says the instance enabled it.
  if (!c.debugUtilsEnabled) return Status::success();
  vkCmdBeginDebugUtilsLabelEXT = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(c.instance, "vkCmdBeginDebugUtilsLabelEXT"));
  vkCmdEndDebugUtilsLabelEXT = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(c.instance, "vkCmdEndDebugUtilsLabelEXT"));
  if (!vkCmdBeginDebugUtilsLabelEXT || !vkCmdEndDebugUtilsLabelEXT)
    vkCmdBeginDebugUtilsLabelEXT = nullptr, vkCmdEndDebugUtilsLabelEXT = nullptr;
  return Status::success();
}

const char* resultName(VkResult r) {
  switch (r) {
#define SAO_VK_CASE(x) \
  case x: return #x;
    SAO_VK_CASE(VK_SUCCESS)
    SAO_VK_CASE(VK_NOT_READY)
    SAO_VK_CASE(VK_TIMEOUT)
    SAO_VK_CASE(VK_INCOMPLETE)
    SAO_VK_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    SAO_VK_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    SAO_VK_CASE(VK_ERROR_INITIALIZATION_FAILED)
    SAO_VK_CASE(VK_ERROR_DEVICE_LOST)
    SAO_VK_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    SAO_VK_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    SAO_VK_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    SAO_VK_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    SAO_VK_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    SAO_VK_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    SAO_VK_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    SAO_VK_CASE(VK_ERROR_FRAGMENTED_POOL)
    SAO_VK_CASE(VK_ERROR_UNKNOWN)
    SAO_VK_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    SAO_VK_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    SAO_VK_CASE(VK_ERROR_FRAGMENTATION)
    SAO_VK_CASE(VK_PIPELINE_COMPILE_REQUIRED)
#undef SAO_VK_CASE
    default: return "VkResult(unknown)";
  }
}

Status vkError(const char* what, VkResult result) {
  return Status::error(StatusCode::DriverError, std::string(what) + " failed: " + resultName(result) + " (" +
                                                    std::to_string(static_cast<int>(result)) + ")");
}

}  // namespace sao::vk
