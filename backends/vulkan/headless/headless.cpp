// Instance, device, validation messenger and one-shot submissions of the headless helper.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "sao/vulkan/headless.h"

namespace sao::vk::headless {
namespace {

Status vkFail(const std::string& what, VkResult r) {
  return Status::error(StatusCode::DriverError, what + " failed: VkResult " + std::to_string(static_cast<int>(r)));
}

// The lavapipe ICD json in the standard ICD folders, or "".
std::string findLavapipeIcd() {
  namespace fs = std::filesystem;
  for (const char* dir : {"/usr/share/vulkan/icd.d", "/usr/local/share/vulkan/icd.d", "/etc/vulkan/icd.d"}) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("lvp_icd", 0) == 0 && name.size() > 5 && name.substr(name.size() - 5) == ".json")
        found.push_back(entry.path().string());
    }
    std::sort(found.begin(), found.end());
    // Prefer the json of this machine's architecture.
    for (const auto& f : found)
      if (f.find(".x86_64.") != std::string::npos || f.find(".aarch64.") != std::string::npos) return f;
    if (!found.empty()) return found.front();
  }
  return {};
}

bool hasLayer(const char* name) {
  std::uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  std::uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &n, ext.data());
  for (const auto& e : ext)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

bool hasInstanceExtension(const char* layer, const char* name) {
  std::uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(layer, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  vkEnumerateInstanceExtensionProperties(layer, &n, ext.data());
  for (const auto& e : ext)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

int deviceRank(VkPhysicalDeviceType t, DevicePreference pref) {
  if (pref == DevicePreference::Cpu) return t == VK_PHYSICAL_DEVICE_TYPE_CPU ? 0 : -1;
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_OTHER: return 1;
    default: return 0;  // CPU
  }
}

const char* severityName(VkDebugUtilsMessageSeverityFlagBitsEXT s) {
  switch (s) {
    case VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT: return "error";
    case VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT: return "warning";
    case VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT: return "info";
    default: return "verbose";
  }
}

}  // namespace

std::string toString(const std::vector<Message>& messages) {
  std::ostringstream s;
  for (const auto& m : messages) s << "[" << severityName(m.severity) << "] " << m.id << ": " << m.text << "\n";
  return s.str();
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT type,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  auto* c = static_cast<Context*>(self);
  // Informational messages of the loader (type GENERAL) describe the search for drivers and
  // layers; every other message is kept and fails a test.
  if (severity == VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT && type == VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT)
    return VK_FALSE;
  Message m{severity, type, data && data->pMessageIdName ? data->pMessageIdName : "",
            data && data->pMessage ? data->pMessage : ""};
  std::lock_guard lock(c->mutex_);
  // The layer's own announcement at instance creation ("Khronos Validation Layer Active: ...
  // Current Enables: ...") is its status, not a finding: kept apart.
  if (severity == VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT &&
      m.id == "UNASSIGNED-khronos-validation-createinstance-status-message") {
    c->layerStatus_ = m.text;
    return VK_FALSE;
  }
  c->messages_.push_back(std::move(m));
  return VK_FALSE;
}

std::vector<Message> Context::takeMessages() {
  std::lock_guard lock(mutex_);
  return std::exchange(messages_, {});
}

std::size_t Context::messageCount() const {
  std::lock_guard lock(mutex_);
  return messages_.size();
}

Status Context::create(const Options& options, std::unique_ptr<Context>& out) {
  out.reset();
  std::unique_ptr<Context> c(new Context());
  if (Status st = c->init(options); !st) return st;
  out = std::move(c);
  return Status::success();
}

Status Context::createInstance(const Options& o, bool validation) {
  std::uint32_t loaderVersion = VK_API_VERSION_1_0;
  vkEnumerateInstanceVersion(&loaderVersion);
  if (loaderVersion < VK_API_VERSION_1_1)
    return Status::error(StatusCode::DriverError, "the Vulkan loader offers only Vulkan 1.0; 1.1 is needed");
  apiVersion_ = std::max<std::uint32_t>(VK_API_VERSION_1_1, std::min(o.apiVersion, loaderVersion));

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = o.applicationName;
  app.pEngineName = "sao";
  app.apiVersion = apiVersion_;

  std::vector<const char*> layers, extensions;
  for (const std::string& e : o.instanceExtensions) extensions.push_back(e.c_str());
  VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = &Context::onMessage;
  messenger.pUserData = this;
  const VkValidationFeatureEnableEXT syncval = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  // No shader-validation cache file in the home directory: processes running side by side (ctest
  // -j) would share it, and a missing file is reported as a message of its own.
  const VkValidationFeatureDisableEXT noCache = VK_VALIDATION_FEATURE_DISABLE_SHADER_VALIDATION_CACHE_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = o.synchronizationValidation ? 1 : 0;
  features.pEnabledValidationFeatures = &syncval;
  features.disabledValidationFeatureCount = 1;
  features.pDisabledValidationFeatures = &noCache;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  if (validation) {
    const char* layer = "VK_LAYER_KHRONOS_validation";
    if (!hasLayer(layer))
      return Status::error(StatusCode::DriverError,
                           "validation was asked for but VK_LAYER_KHRONOS_validation is not installed "
                           "(Debian: vulkan-validationlayers)");
    layers.push_back(layer);
    if (!hasInstanceExtension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) &&
        !hasInstanceExtension(layer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME))
      return Status::error(StatusCode::DriverError, "VK_EXT_debug_utils is not available");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    debugUtils_ = true;
    info.pNext = &messenger;
    if (hasInstanceExtension(layer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
      extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
      messenger.pNext = &features;
    } else if (o.synchronizationValidation) {
      return Status::error(StatusCode::DriverError,
                           "the validation layer does not offer VK_EXT_validation_features (synchronization validation)");
    }
  } else if (hasInstanceExtension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME)) {
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);  // labels for captures
    debugUtils_ = true;
  }
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  if (VkResult r = vkCreateInstance(&info, nullptr, &instance_); r != VK_SUCCESS) {
    debugUtils_ = false;
    instance_ = VK_NULL_HANDLE;
    return vkFail("vkCreateInstance", r);
  }
  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    messenger.pNext = nullptr;
    if (!create) return Status::error(StatusCode::DriverError, "vkCreateDebugUtilsMessengerEXT is missing");
    if (VkResult r = create(instance_, &messenger, nullptr, &messenger_); r != VK_SUCCESS)
      return vkFail("vkCreateDebugUtilsMessengerEXT", r);
  }
  if (o.createSurface)
    if (VkResult r = o.createSurface(instance_, &surface_); r != VK_SUCCESS) {
      surface_ = VK_NULL_HANDLE;
      return vkFail("creating the window's surface", r);
    }
  return Status::success();
}

void Context::destroyInstance() {
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  surface_ = VK_NULL_HANDLE;
  messenger_ = VK_NULL_HANDLE;
  instance_ = VK_NULL_HANDLE;
}

// Graphics + compute first (the usual queue), else compute only; with a surface, graphics +
// compute that can present to it.
int Context::queueFamilyFor(VkPhysicalDevice device) const {
  std::uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &n, nullptr);
  std::vector<VkQueueFamilyProperties> fams(n);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &n, fams.data());
  const VkQueueFlags both = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (std::uint32_t i = 0; i < n; ++i) {
    VkBool32 present = VK_TRUE;
    if (surface_) vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface_, &present);
    if ((fams[i].queueFlags & both) == both && present) return static_cast<int>(i);
  }
  for (std::uint32_t i = 0; i < n && !surface_; ++i)
    if (fams[i].queueFlags & VK_QUEUE_COMPUTE_BIT) return static_cast<int>(i);
  return -1;
}

Status Context::pickDevice(const Options& o) {
  std::uint32_t n = 0;
  if (VkResult r = vkEnumeratePhysicalDevices(instance_, &n, nullptr); r != VK_SUCCESS && r != VK_INCOMPLETE)
    return vkFail("vkEnumeratePhysicalDevices", r);
  std::vector<VkPhysicalDevice> devices(n);
  vkEnumeratePhysicalDevices(instance_, &n, devices.data());
  int best = -1;
  std::string rejected;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    VkPhysicalDeviceFeatures f;
    vkGetPhysicalDeviceFeatures(d, &f);
    const int rank = deviceRank(p.deviceType, o.device);
    const int family = queueFamilyFor(d);
    const char* why = rank < 0                                                         ? "not a CPU device"
                      : p.apiVersion < VK_API_VERSION_1_1                              ? "Vulkan 1.0 only"
                      : !f.shaderStorageImageExtendedFormats                           ? "no shaderStorageImageExtendedFormats"
                      : surface_ && !hasDeviceExtension(d, VK_KHR_SWAPCHAIN_EXTENSION_NAME) ? "no VK_KHR_swapchain"
                      : family < 0 && surface_ ? "no graphics + compute queue that can present to the window"
                      : family < 0             ? "no compute queue"
                                               : nullptr;
    if (why) {
      rejected += std::string(rejected.empty() ? "" : "; ") + p.deviceName + ": " + why;
    } else if (rank > best) {
      best = rank;
      physical_ = d;
      props_ = p;
      family_ = static_cast<std::uint32_t>(family);
    }
  }
  if (!physical_)
    return Status::error(StatusCode::DriverError, std::to_string(n) + " Vulkan device(s) found, none suitable" +
                                                      (rejected.empty() ? "" : " (" + rejected + ")"));
  return Status::success();
}

Status Context::createDevice() {
  apiVersion_ = std::min(apiVersion_, props_.apiVersion);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  q.queueFamilyIndex = family_;
  q.queueCount = 1;
  q.pQueuePriorities = &priority;
  enabled_ = {};
  enabled_.shaderStorageImageExtendedFormats = storageImageExtendedFormats_ ? VK_TRUE : VK_FALSE;
  const char* swapchain = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &q;
  info.pEnabledFeatures = &enabled_;
  info.enabledExtensionCount = surface_ ? 1 : 0;
  info.ppEnabledExtensionNames = &swapchain;
  if (VkResult r = vkCreateDevice(physical_, &info, nullptr, &device_); r != VK_SUCCESS) {
    device_ = VK_NULL_HANDLE;
    return vkFail("vkCreateDevice", r);
  }
  vkGetDeviceQueue(device_, family_, 0, &queue_);

  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = family_;
  if (VkResult r = vkCreateCommandPool(device_, &pi, nullptr, &pool_); r != VK_SUCCESS)
    return vkFail("vkCreateCommandPool", r);
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (VkResult r = vkCreateFence(device_, &fi, nullptr, &fence_); r != VK_SUCCESS) return vkFail("vkCreateFence", r);
  return Status::success();
}

Status Context::init(const Options& o) {
  storageImageExtendedFormats_ = o.storageImageExtendedFormats;
  const bool validation = o.validation || o.synchronizationValidation;
  // An exported but empty VK_DRIVER_FILES / VK_ICD_FILENAMES makes the loader find no driver.
  for (const char* var : {"VK_DRIVER_FILES", "VK_ICD_FILENAMES"}) {
    const char* v = std::getenv(var);
    if (v && *v == '\0') {
      unsetenv(var);
      how_ += std::string(var) + " was exported empty and has been unset; ";
    }
  }
  // No driver at all makes vkCreateInstance fail (VK_ERROR_INCOMPATIBLE_DRIVER); no suitable
  // device leaves pickDevice without one. Either way, lavapipe is tried next.
  Status picked = createInstance(o, validation);
  if (picked) picked = pickDevice(o);
  if (!picked) {
    // No (suitable) device through the default search: point the loader at lavapipe.
    const std::string icd = findLavapipeIcd();
    if (icd.empty())
      return Status::error(StatusCode::DriverError,
                           picked.message + "; and no lavapipe ICD (lvp_icd.*.json) was found (Debian: mesa-vulkan-drivers)");
    destroyInstance();
    // Messages of the failed attempt (the loader finding no driver) are not about this session.
    if (const auto dropped = takeMessages(); !dropped.empty())
      how_ += std::to_string(dropped.size()) + " loader message(s) of the first attempt dropped; ";
    setenv("VK_DRIVER_FILES", icd.c_str(), 1);
    driverFiles_ = icd;
    how_ += "no suitable device by default (" + picked.message + "), VK_DRIVER_FILES=" + icd + "; ";
    if (Status st = createInstance(o, validation); !st) return st;
    if (Status st = pickDevice(o); !st) return st;
  }
  return createDevice();
}

Context::~Context() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    if (fence_) vkDestroyFence(device_, fence_, nullptr);
    if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  destroyInstance();
}

std::string Context::description() const {
  std::ostringstream s;
  s << props_.deviceName << " (" << (isCpuDevice() ? "CPU" : "GPU") << ", Vulkan " << VK_API_VERSION_MAJOR(apiVersion_)
    << "." << VK_API_VERSION_MINOR(apiVersion_) << ", queue family " << family_ << ")";
  if (!how_.empty()) s << " [" << how_.substr(0, how_.size() - 2) << "]";
  return s.str();
}

DeviceContext Context::deviceContext() const {
  DeviceContext c;
  c.instance = instance_;
  c.physicalDevice = physical_;
  c.device = device_;
  c.getInstanceProcAddr = &vkGetInstanceProcAddr;
  c.getDeviceProcAddr = &vkGetDeviceProcAddr;
  c.queueFamilyIndex = family_;
  c.debugUtilsEnabled = debugUtils_;
  c.enabledFeatures = &enabled_;
  return c;
}

Status Context::allocateCommandBuffers(VkCommandBuffer* out, std::uint32_t count) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = count;
  if (VkResult r = vkAllocateCommandBuffers(device_, &ai, out); r != VK_SUCCESS) return vkFail("vkAllocateCommandBuffers", r);
  return Status::success();
}

// One command buffer, allocated once and re-begun (the pool resets it), not one allocated and
// freed per call: the validation layer of Debian 12 (1.3.239) can destroy a freed command buffer's
// state on its queue-retire thread, erasing its debug labels without the lock that guards them
// while the next call records labels on this thread (a heap use after free under ASan;
// KhronosGroup/Vulkan-ValidationLayers#5172, fixed in 1.3.243). A command buffer that is never
// freed is never destroyed there.
Status Context::submit(const std::function<void(VkCommandBuffer)>& record) {
  if (submitCmd_ == VK_NULL_HANDLE) {
    if (Status st = allocateCommandBuffers(&submitCmd_, 1); !st) {
      submitCmd_ = VK_NULL_HANDLE;
      return st;
    }
  }
  const VkCommandBuffer cmd = submitCmd_;
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (VkResult r = vkBeginCommandBuffer(cmd, &bi); r != VK_SUCCESS) return vkFail("vkBeginCommandBuffer", r);
  record(cmd);
  if (VkResult r = vkEndCommandBuffer(cmd); r != VK_SUCCESS) return vkFail("vkEndCommandBuffer", r);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  if (VkResult r = vkQueueSubmit(queue_, 1, &si, fence_); r != VK_SUCCESS) return vkFail("vkQueueSubmit", r);
  const VkResult w = vkWaitForFences(device_, 1, &fence_, VK_TRUE, 300'000'000'000ull);
  vkResetFences(device_, 1, &fence_);
  if (w != VK_SUCCESS) return vkFail("vkWaitForFences", w);
  return Status::success();
}

}  // namespace sao::vk::headless
