// The viewer's Vulkan instance, window surface and device: a device that can present to the
// GLFW window's surface and run graphics and compute on one queue (a real GPU first, lavapipe
// otherwise), with the shaderStorageImageExtendedFormats feature the effect needs. Optional
// VK_LAYER_KHRONOS_validation with a messenger that prints and counts what it reports.
#pragma once
#include <vulkan/vulkan.h>

#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "sao/status.h"
#include "sao/vulkan/effect.h"
#include "vk_util.h"

struct GLFWwindow;

namespace sao::viewer {

class VkContext {
 public:
  static Status create(GLFWwindow* window, bool validation, std::unique_ptr<VkContext>& out);
  ~VkContext();
  VkContext(const VkContext&) = delete;
  VkContext& operator=(const VkContext&) = delete;

  VkInstance instance = VK_NULL_HANDLE;
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  VkPhysicalDeviceProperties properties{};
  bool debugUtils = false;
  std::string description;  // device, driver, API version
  std::atomic<std::size_t> validationMessages{0};

  vk::DeviceContext deviceContext() const;  // for sao::vk::Effect::create

  Status createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, vkx::Buffer& out);  // host-visible, mapped
  Status createImage(VkFormat format, VkExtent2D extent, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                     vkx::Image& out);  // device-local, one level, with a view
  void destroy(vkx::Buffer& buffer);
  void destroy(vkx::Image& image);
  // Records with `record` into a fresh command buffer, submits it and waits for the queue.
  Status oneShot(const std::function<void(VkCommandBuffer)>& record);
  VkCommandPool commandPool() const { return pool_; }  // resettable command buffers, the queue's family

 private:
  VkContext() = default;
  Status createInstance(bool validation);
  Status pickDevice();
  Status createDevice();
  int memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const;
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT type,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory_{};
  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::uint32_t apiVersion_ = VK_API_VERSION_1_1;
};

}  // namespace sao::viewer
