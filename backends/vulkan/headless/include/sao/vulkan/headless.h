// sao::vk::headless — the project's one Vulkan bootstrap: an instance and device for tests and
// tools, and (Options::createSurface) for sao-viewer's window.
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
// Presentation: with Options::createSurface the context owns the window's surface, and a device
// qualifies only with VK_KHR_swapchain (enabled) and a graphics + compute queue family that can
// present to the surface.
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
  // Enables shaderStorageImageExtendedFormats, which sao::vk needs; false makes a device without
  // it (for the test that Effect::create() refuses such a device).
  bool storageImageExtendedFormats = true;
  const char* applicationName = "sao headless";
  std::vector<std::string> instanceExtensions;  // required, e.g. the window system's (glfwGetRequiredInstanceExtensions)
  // Makes the window's surface on a new instance; called again for the lavapipe retry.
  std::function<VkResult(VkInstance, VkSurfaceKHR*)> createSurface;
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

// A host-visible, coherent buffer, mapped for its lifetime.
struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  VkDeviceSize size = 0;
};

// The project's image barrier: levels [level, level + levels) of layer 0, no queue-family transfer.
inline VkImageMemoryBarrier imageBarrier(VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                                         VkAccessFlags srcAccess, VkAccessFlags dstAccess, std::uint32_t level = 0,
                                         std::uint32_t levels = 1) {
  VkImageMemoryBarrier b{};  // sType apart: consumers may build with -Wmissing-field-initializers
  b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, level, levels, 0, 1};
  return b;
}

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
  VkSurfaceKHR surface() const { return surface_; }  // with Options::createSurface, else null
  // Resettable command buffers of the queue's family, for callers that record their own frames.
  VkCommandPool commandPool() const { return pool_; }
  // `count` primary command buffers from commandPool() into `out` (free them with vkFreeCommandBuffers).
  Status allocateCommandBuffers(VkCommandBuffer* out, std::uint32_t count);
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
  // A sampled colour image (e.g. normals, 4 channels) in R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT
  // (octahedral normals, 2 channels: R16G16_SFLOAT or R32G32_SFLOAT)
  // (or an output format: R16_SFLOAT, R8_UNORM, R8G8B8A8_UNORM, values rounded to the nearest byte),
  // with `extraUsage` added (e.g. STORAGE for an output whose channels the effect keeps).
  Status uploadColor(const FloatImage& image, VkFormat format, VkImageLayout layout, Image& out,
                     VkImageUsageFlags extraUsage = 0);
  // An image for the effect's output when the caller owns it: STORAGE, SAMPLED, TRANSFER_SRC/DST.
  Status createStorageImage(VkFormat format, Extent extent, Image& out);
  // A 2D image, one level, in device-local memory, with one view of `viewAspect`; left UNDEFINED.
  Status createImage(VkFormat format, Extent extent, VkImageUsageFlags usage, VkImageAspectFlags viewAspect, Image& out);
  Status createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, Buffer& out);
  // Destroying an empty object is a no-op; either comes back empty.
  void destroy(Image& image);
  void destroy(Buffer& buffer);

  // Reads level `level` of a colour image (R16_SFLOAT, R32_SFLOAT, R32G32_SFLOAT,
  // R16G16B16A16_SFLOAT, R32G32B32A32_SFLOAT; R8_UNORM, R8G8B8A8_UNORM as byte / 255) into floats. The image is in `layout` and its last
  // writes happened at `srcStages` / `srcAccess`; it is left in `layout`, row 0 first.
  Status readback(VkImage image, VkFormat format, Extent levelZero, std::uint32_t level, VkImageLayout layout,
                  VkPipelineStageFlags srcStages, VkAccessFlags srcAccess, FloatImage& out);

 private:
  Context() = default;
  Status init(const Options& options);
  Status createInstance(const Options& options, bool validation);
  void destroyInstance();
  Status pickDevice(const Options& options);
  int queueFamilyFor(VkPhysicalDevice device) const;  // -1: none fits
  Status createDevice();
  int memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const;
  static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT type,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t family_ = 0;
  std::uint32_t apiVersion_ = VK_API_VERSION_1_1;
  VkPhysicalDeviceProperties props_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  VkPhysicalDeviceFeatures enabled_{};  // what vkCreateDevice enabled (DeviceContext::enabledFeatures)
  bool storageImageExtendedFormats_ = true;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer submitCmd_ = VK_NULL_HANDLE;  // submit()'s one command buffer, reused (see there)
  VkFence fence_ = VK_NULL_HANDLE;
  std::string driverFiles_;
  std::string how_;
  mutable std::mutex mutex_;
  std::vector<Message> messages_;
  std::string layerStatus_;
  bool debugUtils_ = false;
};

}  // namespace sao::vk::headless
