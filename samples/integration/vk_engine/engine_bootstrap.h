// The example engine's own instance and device (a test hands the engine its context's instead):
// Vulkan 1.1, optionally the Khronos validation layer with synchronization validation and a
// messenger that prints each warning and error and counts it, the first device with a compute
// queue and r16f / rg16f storage images (shaderStorageImageExtendedFormats, enabled).
#pragma once
#include <vulkan/vulkan.h>

#include <memory>

#include "engine_device.h"

namespace sao::vkengine {

class Bootstrap {
 public:
  // `messages` counts the layer's warnings and errors; it must outlive the Bootstrap, whose
  // destruction is when the layer reports objects left behind.
  static Status create(bool validation, int& messages, std::unique_ptr<Bootstrap>& out);
  ~Bootstrap();
  Bootstrap(const Bootstrap&) = delete;
  Bootstrap& operator=(const Bootstrap&) = delete;

  DeviceHandles handles() const { return {physical_, device_, family_, queue_}; }

 private:
  Bootstrap() = default;
  Status init(bool validation, int& messages);
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  std::uint32_t family_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
};

}  // namespace sao::vkengine
