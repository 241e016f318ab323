// sao::vk::headless — an instance and device without a window, for tests and tools.
//
// Device choice: a real GPU when one exists (discrete, then integrated, then virtual), else a
// CPU device (Mesa lavapipe). When the loader finds no device at all, or VK_DRIVER_FILES /
// VK_ICD_FILENAMES is exported but empty (which finds no driver), the helper points
// VK_DRIVER_FILES at the lavapipe ICD json (/usr/share/vulkan/icd.d/lvp_icd.*.json and the other
// standard ICD folders) and tries again. DevicePreference::Cpu asks for the CPU device even when a
// GPU exists (to compare with Mesa's llvmpipe OpenGL bit for bit).
//
// Validation: VK_LAYER_KHRONOS_validation with a VK_EXT_debug_utils messenger that collects every
// message (warnings and errors of every type, and informational messages of the validation and
// performance types; only the layer's own status report at instance creation is kept apart, see
// layerStatus()), and optionally synchronization validation (VkValidationFeaturesEXT). The
// layer's shader-validation cache file is turned off. Tests fail on any collected message.
//
// This library links the Vulkan loader; sao::vulkan itself does not.
#pragma once
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "sao/image.h"
#include "sao/status.h"
#include "sao/vulkan/effect.h"

namespace sao::vk::headless {

enum class DevicePreference {
  Auto,  // a real GPU when one exists, else the CPU device
  Cpu,   // the CPU device (lavapipe), even when a GPU exists
};

struct Options {
  bool validation = false;                 // VK_LAYER_KHRONOS_validation + the messenger
  bool synchronizationValidation = false;  // implies validation
  DevicePreference device = DevicePreference::Auto;
  std::uint32_t apiVersion = VK_API_VERSION_1_3;  // capped to what the instance and device offer (>= 1.1)
};

struct Message {
  VkDebugUtilsMessageSeverityFlagBitsEXT severity{};
  VkDebugUtilsMessageTypeFlagsEXT type = 0;
  std::string id;  // pMessageIdName
  std::string text;
};
std::string toString(const std::vector<Message>& messages);

// An image the helper created (with its memory and one view), or the caller's storage image.
struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  Extent extent;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

class Context {
 public:
  static Status create(const Options& options, std::unique_ptr<Context>& out);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queueFamily() const { return family_; }
  std::uint32_t apiVersion() const { return apiVersion_; }
  const VkPhysicalDeviceProperties& properties() const { return props_; }
  bool isCpuDevice() const { return props_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  std::string description() const;  // device name, driver, API version, how it was found
  const std::string& driverFiles() const { return driverFiles_; }  // VK_DRIVER_FILES set by us, or empty

  // For sao::vk::Effect::create (the loader's vkGetInstanceProcAddr, this device and queue family,
  // debug labels when VK_EXT_debug_utils is on).
  DeviceContext deviceContext() const;

  // The validation layer's status report at instance creation (its settings, e.g. "Current
  // Enables: VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION"); empty without the layer.
  std::string layerStatus() const {
    std::lock_guard lock(mutex_);
    return layerStatus_;
  }
  // Validation messages collected so far, and clearing them.
  std::vector<Message> takeMessages();
  std::size_t messageCount() const;

  // Records with `record`, submits to the queue and waits for it.
  Status submit(const std::function<void(VkCommandBuffer)>& record);

  // A sampled image holding `depth`: `format` D16_UNORM (DepthFormat::D16), X8_D24_UNORM_PACK32
  // or D24_UNORM_S8_UINT (D24), D32_SFLOAT or D32_SFLOAT_S8_UINT (D32F), R32_SFLOAT (LinearZ),
  // filled with vkCmdCopyBufferToImage and left in `layout`, visible to compute-shader reads. The
  // view selects the depth aspect only.
  Status uploadDepth(const DepthImage& depth, VkFormat format, VkImageLayout layout, Image& out);
  // A sampled colour image (e.g. normals, 4 channels) in R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT.
  Status uploadColor(const FloatImage& image, VkFormat format, VkImageLayout layout, Image& out);
  // An image for the effect's output when the caller owns it: STORAGE, SAMPLED, TRANSFER_SRC/DST.
  Status createStorageImage(VkFormat format, Extent extent, Image& out);
  void destroy(Image& image);

  // Reads level `level` of a colour image (R16_SFLOAT, R32_SFLOAT, R32G32_SFLOAT,
  // R16G16B16A16_SFLOAT, R32G32B32A32_SFLOAT) into floats. The image is in `layout` and its last
  // writes happened at `srcStages` / `srcAccess`; it is left in `layout`, row 0 first.
  Status readback(VkImage image, VkFormat format, Extent levelZero, std::uint32_t level, VkImageLayout layout,
                  VkPipelineStageFlags srcStages, VkAccessFlags srcAccess, FloatImage& out);

 private:
  Context() = default;
  Status init(const Options& options);
  Status createInstance(const Options& options, bool validation);
  Status pickDevice(const Options& options);
  Status createDevice(const Options& options);
  int memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const;
  Status createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, VkBuffer& buffer, VkDeviceMemory& memory);
  Status createImage(VkFormat format, Extent extent, VkImageUsageFlags usage, VkImageAspectFlags viewAspect, Image& out);
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT type,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t family_ = 0;
  std::uint32_t apiVersion_ = VK_API_VERSION_1_1;
  VkPhysicalDeviceProperties props_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  std::string driverFiles_;
  std::string how_;
  mutable std::mutex mutex_;
  std::vector<Message> messages_;
  std::string layerStatus_;
  bool debugUtils_ = false;
};

}  // namespace sao::vk::headless
