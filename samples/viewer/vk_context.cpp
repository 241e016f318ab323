#include "vk_context.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

namespace sao::viewer {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

int typeRank(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

bool hasExtension(VkPhysicalDevice device, const char* name) {
  std::uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> all(n);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &n, all.data());
  return std::any_of(all.begin(), all.end(), [&](const auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::string versionText(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

}  // namespace

Status VkContext::create(GLFWwindow* window, bool validation, std::unique_ptr<VkContext>& out) {
  std::unique_ptr<VkContext> c(new VkContext());
  if (Status s = c->createInstance(validation); !s) return s;
  SAO_VIEWER_VK(glfwCreateWindowSurface(c->instance, window, nullptr, &c->surface));
  if (Status s = c->pickDevice(); !s) return s;
  if (Status s = c->createDevice(); !s) return s;
  out = std::move(c);
  return Status::success();
}

VkContext::~VkContext() {
  if (device) {
    vkDeviceWaitIdle(device);
    vkDestroyCommandPool(device, pool_, nullptr);
    vkDestroyDevice(device, nullptr);
  }
  if (surface) vkDestroySurfaceKHR(instance, surface, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance, messenger_, nullptr);
  }
  if (instance) vkDestroyInstance(instance, nullptr);
}

VKAPI_ATTR VkBool32 VKAPI_CALL VkContext::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                    VkDebugUtilsMessageTypeFlagsEXT,
                                                    const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  const std::size_t n = ++static_cast<VkContext*>(self)->validationMessages;
  if (n <= 20)
    std::fprintf(stderr, "sao-viewer: validation %s: %s\n",
                 severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning",
                 data && data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

Status VkContext::createInstance(bool validation) {
  std::uint32_t loaderVersion = VK_API_VERSION_1_0;
  vkEnumerateInstanceVersion(&loaderVersion);
  if (loaderVersion < VK_API_VERSION_1_1)
    return Status::error(StatusCode::DriverError, "the Vulkan loader offers " + versionText(loaderVersion) +
                                                      "; the effect needs Vulkan 1.1");
  apiVersion_ = std::min<std::uint32_t>(loaderVersion, VK_API_VERSION_1_3);
  std::uint32_t glfwCount = 0;
  const char** glfwExtensions = glfwGetRequiredInstanceExtensions(&glfwCount);
  if (!glfwExtensions) return Status::error(StatusCode::DriverError, "GLFW cannot present with Vulkan on this system");
  std::vector<const char*> extensions(glfwExtensions, glfwExtensions + glfwCount);
  std::vector<const char*> layers;
  if (validation) {
    std::uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> all(n);
    vkEnumerateInstanceLayerProperties(&n, all.data());
    if (std::none_of(all.begin(), all.end(), [](const auto& l) { return std::strcmp(l.layerName, kValidationLayer) == 0; }))
      return Status::error(StatusCode::DriverError, "--validation: VK_LAYER_KHRONOS_validation is not installed");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    debugUtils = true;
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "sao-viewer";
  app.apiVersion = apiVersion_;
  VkDebugUtilsMessengerCreateInfoEXT mi{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                   VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  mi.pfnUserCallback = onMessage;
  mi.pUserData = this;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledExtensionCount = std::uint32_t(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  ci.enabledLayerCount = std::uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  // Synchronization validation too: the viewer's barriers around the effect are part of the sample.
  const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  features.pNext = &mi;
  if (validation) ci.pNext = &features;
  SAO_VIEWER_VK(vkCreateInstance(&ci, nullptr, &instance));
  if (validation) {
    auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (createMessenger) SAO_VIEWER_VK(createMessenger(instance, &mi, nullptr, &messenger_));
  }
  return Status::success();
}

Status VkContext::pickDevice() {
  std::uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance, &n, nullptr);
  std::vector<VkPhysicalDevice> devices(n);
  vkEnumeratePhysicalDevices(instance, &n, devices.data());
  int bestRank = 100;
  std::string rejected;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    VkPhysicalDeviceFeatures f;
    vkGetPhysicalDeviceFeatures(d, &f);
    std::string why;
    if (p.apiVersion < VK_API_VERSION_1_1) why = "Vulkan 1.0 only";
    else if (!hasExtension(d, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) why = "no VK_KHR_swapchain";
    else if (!f.shaderStorageImageExtendedFormats) why = "no shaderStorageImageExtendedFormats";
    int queueFamily = -1;
    std::uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> families(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, families.data());
    for (std::uint32_t i = 0; i < qn && why.empty() && queueFamily < 0; ++i) {
      VkBool32 present = VK_FALSE;
      vkGetPhysicalDeviceSurfaceSupportKHR(d, i, surface, &present);
      const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
      if (present && (families[i].queueFlags & need) == need) queueFamily = int(i);
    }
    if (why.empty() && queueFamily < 0) why = "no graphics+compute queue that can present to the window";
    if (!why.empty()) {
      rejected += std::string(rejected.empty() ? "" : "; ") + p.deviceName + ": " + why;
      continue;
    }
    if (typeRank(p.deviceType) < bestRank) {
      bestRank = typeRank(p.deviceType);
      physical = d;
      family = std::uint32_t(queueFamily);
      properties = p;
    }
  }
  if (!physical)
    return Status::error(StatusCode::DriverError,
                         "no Vulkan device can run the viewer" + (rejected.empty() ? std::string() : " (" + rejected + ")"));
  vkGetPhysicalDeviceMemoryProperties(physical, &memory_);
  return Status::success();
}

Status VkContext::createDevice() {
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qi.queueFamilyIndex = family;
  qi.queueCount = 1;
  qi.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures features{};
  features.shaderStorageImageExtendedFormats = VK_TRUE;
  const char* extensions[] = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  ci.queueCreateInfoCount = 1;
  ci.pQueueCreateInfos = &qi;
  ci.enabledExtensionCount = 1;
  ci.ppEnabledExtensionNames = extensions;
  ci.pEnabledFeatures = &features;
  SAO_VIEWER_VK(vkCreateDevice(physical, &ci, nullptr, &device));
  vkGetDeviceQueue(device, family, 0, &queue);
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = family;
  SAO_VIEWER_VK(vkCreateCommandPool(device, &pi, nullptr, &pool_));
  description = std::string("Vulkan ") + versionText(std::min(properties.apiVersion, apiVersion_)) + ", " +
                properties.deviceName + " (driver " + std::to_string(properties.driverVersion) +
                "); presents through a VK_KHR_swapchain; depth: D32_SFLOAT reversed-Z, [0,1], infinite far";
  return Status::success();
}

vk::DeviceContext VkContext::deviceContext() const {
  vk::DeviceContext c;
  c.instance = instance;
  c.physicalDevice = physical;
  c.device = device;
  c.getInstanceProcAddr = vkGetInstanceProcAddr;
  c.getDeviceProcAddr = vkGetDeviceProcAddr;
  c.queueFamilyIndex = family;
  c.debugUtilsEnabled = debugUtils;
  return c;
}

int VkContext::memoryType(std::uint32_t bits, VkMemoryPropertyFlags flags) const {
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & flags) == flags) return int(i);
  return -1;
}

Status VkContext::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, vkx::Buffer& out) {
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = size;
  bi.usage = usage;
  SAO_VIEWER_VK(vkCreateBuffer(device, &bi, nullptr, &out.buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, out.buffer, &req);
  const int type = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  if (type < 0) return Status::error(StatusCode::DriverError, "no host-visible coherent memory");
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = std::uint32_t(type);
  SAO_VIEWER_VK(vkAllocateMemory(device, &ai, nullptr, &out.memory));
  SAO_VIEWER_VK(vkBindBufferMemory(device, out.buffer, out.memory, 0));
  SAO_VIEWER_VK(vkMapMemory(device, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped));
  out.size = size;
  return Status::success();
}

Status VkContext::createImage(VkFormat format, VkExtent2D extent, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                              vkx::Image& out) {
  VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = format;
  ii.extent = {extent.width, extent.height, 1};
  ii.mipLevels = 1;
  ii.arrayLayers = 1;
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.tiling = VK_IMAGE_TILING_OPTIMAL;
  ii.usage = usage;
  ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  SAO_VIEWER_VK(vkCreateImage(device, &ii, nullptr, &out.image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, out.image, &req);
  int type = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (type < 0) type = memoryType(req.memoryTypeBits, 0);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = std::uint32_t(type);
  SAO_VIEWER_VK(vkAllocateMemory(device, &ai, nullptr, &out.memory));
  SAO_VIEWER_VK(vkBindImageMemory(device, out.image, out.memory, 0));
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = out.image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = format;
  vi.subresourceRange = {aspect, 0, 1, 0, 1};
  SAO_VIEWER_VK(vkCreateImageView(device, &vi, nullptr, &out.view));
  out.format = format;
  out.extent = extent;
  return Status::success();
}

void VkContext::destroy(vkx::Buffer& b) {
  if (b.buffer) vkDestroyBuffer(device, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(device, b.memory, nullptr);
  b = {};
}

void VkContext::destroy(vkx::Image& i) {
  if (i.view) vkDestroyImageView(device, i.view, nullptr);
  if (i.image) vkDestroyImage(device, i.image, nullptr);
  if (i.memory) vkFreeMemory(device, i.memory, nullptr);
  i = {};
}

Status VkContext::oneShot(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  SAO_VIEWER_VK(vkAllocateCommandBuffers(device, &ai, &cmd));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &bi);
  record(cmd);
  vkEndCommandBuffer(cmd);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  Status s = vkx::check(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
  if (s) s = vkx::check(vkQueueWaitIdle(queue), "vkQueueWaitIdle");
  vkFreeCommandBuffers(device, pool_, 1, &cmd);
  return s;
}

}  // namespace sao::viewer
