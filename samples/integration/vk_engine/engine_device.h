// The engine's use of a Vulkan device it was handed: one command pool, command buffer and fence of
// its own on the given queue (every submit waits for its fence), device memory, format features.
// The device, its queue and the physical device belong to whoever created them (the engine's own
// bootstrap, engine_bootstrap.h, or a test's context) and must outlive this object.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "sao/status.h"

namespace sao::vkengine {

// A failed Vulkan call as a Status naming the call.
Status vkFail(const std::string& what, VkResult r);
#define SAO_ENGINE_VK_TRY(call)                                                        \
  do {                                                                                 \
    if (VkResult r_ = (call); r_ != VK_SUCCESS) return ::sao::vkengine::vkFail(#call, r_); \
  } while (false)

// What the engine is given: a device with shaderStorageImageExtendedFormats enabled and a queue of
// a family with compute (and transfer, which compute implies).
struct DeviceHandles {
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  VkQueue queue = VK_NULL_HANDLE;
};

class Device {
 public:
  static Status create(const DeviceHandles& handles, std::unique_ptr<Device>& out);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkDevice device() const { return h_.device; }
  VkPhysicalDevice physical() const { return h_.physical; }
  const VkPhysicalDeviceProperties& properties() const { return props_; }

  // Device memory of a type with `want` among those `needs` allows.
  Status allocate(VkMemoryRequirements needs, VkMemoryPropertyFlags want, VkDeviceMemory& out) const;
  // Whether optimally tiled images of `format` have every feature of `need`.
  bool hasFeatures(VkFormat format, VkFormatFeatureFlags need) const;

  // The one command buffer, begun (which resets it: frames are recorded one at a time).
  VkCommandBuffer begin() const;
  // Ends it, submits it to the queue and waits for the fence: the work is complete on return.
  Status submitAndWait() const;
  // begin(), `record`, submitAndWait(): one-shot work (uploads, readbacks) ordered with the frames
  // by the queue.
  Status submitOnce(const std::function<void(VkCommandBuffer)>& record) const;

 private:
  explicit Device(const DeviceHandles& h) : h_(h) {}
  DeviceHandles h_;
  VkPhysicalDeviceProperties props_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace sao::vkengine
