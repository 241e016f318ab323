#include "engine_bootstrap.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace sao::vkengine {
namespace {

// Subscribed to warnings and errors only (not the layer's createinstance-status-message, an
// info): each one is a finding.
VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void* counter) {
  ++*static_cast<int*>(counter);
  const bool error = severity == VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  std::fprintf(stderr, "[validation %s] %s\n", error ? "error" : "warning", data->pMessage);
  return VK_FALSE;
}

}  // namespace

Status Bootstrap::create(bool validation, int& messages, std::unique_ptr<Bootstrap>& out) {
  std::unique_ptr<Bootstrap> b(new Bootstrap);
  if (Status st = b->init(validation, messages); !st) return st;  // b's destructor frees what was made
  out = std::move(b);
  return Status::success();
}

Bootstrap::~Bootstrap() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyDevice(device_, nullptr);  // the layer reports every object left here
  }
  if (messenger_)
    reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"))(instance_, messenger_, nullptr);
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

Status Bootstrap::init(bool validation, int& messages) {
  std::uint32_t loader = VK_API_VERSION_1_0;
  vkEnumerateInstanceVersion(&loader);
  if (loader < VK_API_VERSION_1_1) return Status::error(StatusCode::DriverError, "the Vulkan loader offers only 1.0");
  const VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "sao-example-vulkan-engine", 1, nullptr, 0,
                              VK_API_VERSION_1_1};
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME};
  const VkValidationFeatureEnableEXT syncval = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  // No shader-validation cache file in the home directory, shared by every process that validates.
  const VkValidationFeatureDisableEXT noCache = VK_VALIDATION_FEATURE_DISABLE_SHADER_VALIDATION_CACHE_EXT;
  const VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, nullptr, 1, &syncval, 1, &noCache};
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT, &features};
  messengerInfo.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messengerInfo.pfnUserCallback = &onMessage;
  messengerInfo.pUserData = &messages;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, nullptr, 0, &app};
  if (validation) {
    std::uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    if (std::none_of(layers.begin(), layers.end(), [&](auto& l) { return std::strcmp(l.layerName, layer) == 0; }))
      return Status::error(StatusCode::DriverError, "VK_LAYER_KHRONOS_validation is not installed (Debian: "
                                                    "vulkan-validationlayers); --no-validation runs without it");
    info = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, &messengerInfo, 0, &app, 1, &layer, 2, extensions};
  }
  SAO_ENGINE_VK_TRY(vkCreateInstance(&info, nullptr, &instance_));  // the chained messenger also sees its messages
  if (validation) {
    messengerInfo.pNext = nullptr;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    SAO_ENGINE_VK_TRY(create(instance_, &messengerInfo, nullptr, &messenger_));
  }

  // The first device of Vulkan 1.1+ with a compute queue and r16f / rg16f storage images.
  std::uint32_t n = 0;
  SAO_ENGINE_VK_TRY(vkEnumeratePhysicalDevices(instance_, &n, nullptr));
  std::vector<VkPhysicalDevice> devices(n);
  SAO_ENGINE_VK_TRY(vkEnumeratePhysicalDevices(instance_, &n, devices.data()));
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceFeatures f;
    vkGetPhysicalDeviceFeatures(d, &f);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(d, &props);
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &count, families.data());
    for (family_ = 0; family_ < count && !(families[family_].queueFlags & VK_QUEUE_COMPUTE_BIT);) ++family_;
    if (props.apiVersion >= VK_API_VERSION_1_1 && f.shaderStorageImageExtendedFormats && family_ < count) {
      physical_ = d;
      break;
    }
  }
  if (!physical_)
    return Status::error(StatusCode::DriverError, std::to_string(n) + " Vulkan device(s), none with Vulkan 1.1, a "
                                                  "compute queue and shaderStorageImageExtendedFormats");
  const float priority = 1.0f;
  const VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family_, 1, &priority};
  VkPhysicalDeviceFeatures enabled{};
  enabled.shaderStorageImageExtendedFormats = VK_TRUE;
  const VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, nullptr, 0, 1, &queueInfo,
                                      0, nullptr, 0, nullptr, &enabled};
  SAO_ENGINE_VK_TRY(vkCreateDevice(physical_, &deviceInfo, nullptr, &device_));
  vkGetDeviceQueue(device_, family_, 0, &queue_);
  return Status::success();
}

}  // namespace sao::vkengine
