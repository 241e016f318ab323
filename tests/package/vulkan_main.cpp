// sao::vulkan from a consumer's point of view: an instance and a device of our own (the first one
// with compute; lavapipe here), a D32_SFLOAT depth image cleared to the far plane (sky), the effect
// recorded into our command buffer with the frame's camera and settings (the first record() plans),
// the R16_SFLOAT result copied back (1.0 everywhere), bad inputs (no depth, a view without its
// format) rejected without a plan and a header version mismatch reported. The library gets every
// entry point from vkGetInstanceProcAddr; this program links the loader.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include "sao/vulkan/effect.h"
#include "consumer_check.h"

#define VK(call) CHECK((call) == VK_SUCCESS)

namespace {

std::uint32_t memoryType(VkPhysicalDevice pd, std::uint32_t bits, VkMemoryPropertyFlags flags) {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(pd, &mp);
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & flags) == flags) return i;
  return UINT32_MAX;
}

}  // namespace

int main() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "sao consumer";
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  VK(vkCreateInstance(&ici, nullptr, &instance));

  std::uint32_t count = 0;
  VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  CHECK(count > 0);
  std::vector<VkPhysicalDevice> devices(count);
  VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  VkPhysicalDevice pd = VK_NULL_HANDLE;
  std::uint32_t family = UINT32_MAX;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceFeatures f;
    vkGetPhysicalDeviceFeatures(d, &f);
    std::uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &n, nullptr);
    std::vector<VkQueueFamilyProperties> fams(n);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &n, fams.data());
    for (std::uint32_t i = 0; i < n && family == UINT32_MAX; ++i)
      if (f.shaderStorageImageExtendedFormats && (fams[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
        pd = d;
        family = i;
      }
    if (pd) break;
  }
  CHECK(pd != VK_NULL_HANDLE);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(pd, &props);
  std::printf("Vulkan device: %s\n", props.deviceName);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = family;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures features{};
  features.shaderStorageImageExtendedFormats = VK_TRUE;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.pEnabledFeatures = &features;
  VkDevice device = VK_NULL_HANDLE;
  VK(vkCreateDevice(pd, &dci, nullptr, &device));
  VkQueue queue = VK_NULL_HANDLE;
  vkGetDeviceQueue(device, family, 0, &queue);

  sao::Camera camera = sao::perspectiveCamera(std::numbers::pi / 3, 64, 36, 0.1, 100.0, sao::ClipDepth::ZeroToOne, false);
  camera.guardBand = 4;
  const VkExtent3D extent{72, 44, 1};

  // The depth image: D32_SFLOAT, sampled, cleared by a transfer.
  VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = VK_FORMAT_D32_SFLOAT;
  ii.extent = extent;
  ii.mipLevels = ii.arrayLayers = 1;
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  VkImage depth = VK_NULL_HANDLE;
  VK(vkCreateImage(device, &ii, nullptr, &depth));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, depth, &req);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = memoryType(pd, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  CHECK(mai.memoryTypeIndex != UINT32_MAX);
  VkDeviceMemory depthMemory = VK_NULL_HANDLE;
  VK(vkAllocateMemory(device, &mai, nullptr, &depthMemory));
  VK(vkBindImageMemory(device, depth, depthMemory, 0));
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = depth;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = VK_FORMAT_D32_SFLOAT;
  vi.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
  VkImageView depthView = VK_NULL_HANDLE;
  VK(vkCreateImageView(device, &vi, nullptr, &depthView));

  // Read-back buffer for the R16_SFLOAT output.
  const VkDeviceSize bytes = 64 * 36 * sizeof(std::uint16_t);
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = bytes;
  bci.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  VK(vkCreateBuffer(device, &bci, nullptr, &buffer));
  vkGetBufferMemoryRequirements(device, buffer, &req);
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = memoryType(pd, req.memoryTypeBits,
                                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  CHECK(mai.memoryTypeIndex != UINT32_MAX);
  VkDeviceMemory bufferMemory = VK_NULL_HANDLE;
  VK(vkAllocateMemory(device, &mai, nullptr, &bufferMemory));
  VK(vkBindBufferMemory(device, buffer, bufferMemory, 0));

  sao::vk::DeviceContext ctx{instance, pd, device, vkGetInstanceProcAddr, vkGetDeviceProcAddr, family};
  ctx.enabledFeatures = &features;  // what vkCreateDevice enabled (create() checks it)
  sao::vk::Config config;
  config.outputLayout = VK_IMAGE_LAYOUT_GENERAL;
  config.outputDstStages = VK_PIPELINE_STAGE_TRANSFER_BIT;
  config.outputDstAccess = VK_ACCESS_TRANSFER_READ_BIT;
  {
    std::unique_ptr<sao::vk::Effect> wrong;
    const sao::Status st = sao::vk::Effect::create(ctx, config, wrong, SAO_VERSION + 1);
    CHECK(st.code == sao::StatusCode::VersionMismatch && !wrong);
  }
  std::unique_ptr<sao::vk::Effect> effect;
  const sao::Status created = sao::vk::Effect::create(ctx, config, effect);
  if (!created) std::fprintf(stderr, "create: %s\n", created.message.c_str());
  CHECK(created.ok());

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.queueFamilyIndex = family;
  VkCommandPool pool = VK_NULL_HANDLE;
  VK(vkCreateCommandPool(device, &pci, nullptr, &pool));
  VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cai.commandPool = pool;
  cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK(vkAllocateCommandBuffers(device, &cai, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK(vkBeginCommandBuffer(cmd, &begin));

  VkImageMemoryBarrier toClear{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  toClear.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toClear.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  toClear.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  toClear.srcQueueFamilyIndex = toClear.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toClear.image = depth;
  toClear.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &toClear);
  const VkClearDepthStencilValue far{1.0f, 0};
  vkCmdClearDepthStencilImage(cmd, depth, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &far, 1, &toClear.subresourceRange);
  VkImageMemoryBarrier toRead = toClear;
  toRead.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toRead.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  toRead.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  toRead.newLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &toRead);

  const sao::Settings settings;  // the defaults
  sao::vk::Inputs bad;  // no depth view: rejected, nothing recorded
  const sao::Status rejected = effect->record(cmd, camera, settings, bad);
  CHECK(rejected.code == sao::StatusCode::InvalidInput && !rejected.message.empty());
  sao::vk::Inputs noFormat;  // a view without its format: rejected, nothing recorded
  noFormat.depth = {depthView, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, {72, 44}};
  const sao::Status unformatted = effect->record(cmd, camera, settings, noFormat);
  if (unformatted) std::fprintf(stderr, "record accepted a depth view without its format\n");
  CHECK(!unformatted.ok() && !unformatted.message.empty());
  CHECK(effect->plans() == 0);

  sao::vk::Inputs in;
  in.depth = {depthView, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, {72, 44}, VK_FORMAT_D32_SFLOAT};
  const sao::Status recorded = effect->record(cmd, camera, settings, in);
  if (!recorded) std::fprintf(stderr, "record: %s\n", recorded.message.c_str());
  CHECK(recorded.ok());
  const sao::vk::OutputImage out = effect->output();
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {64, 36, 1};
  vkCmdCopyImageToBuffer(cmd, out.image, out.layout, buffer, 1, &region);
  VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  toHost.srcQueueFamilyIndex = toHost.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  toHost.buffer = buffer;
  toHost.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &toHost, 0,
                       nullptr);
  VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
  VK(vkQueueWaitIdle(queue));

  void* mapped = nullptr;
  VK(vkMapMemory(device, bufferMemory, 0, VK_WHOLE_SIZE, 0, &mapped));
  std::vector<std::uint16_t> ao(64 * 36);
  std::memcpy(ao.data(), mapped, bytes);
  vkUnmapMemory(device, bufferMemory);
  for (std::uint16_t a : ao) CHECK(a == 0x3C00);  // half 1.0: nothing occludes the sky

  effect.reset();
  vkDestroyCommandPool(device, pool, nullptr);
  vkDestroyBuffer(device, buffer, nullptr);
  vkFreeMemory(device, bufferMemory, nullptr);
  vkDestroyImageView(device, depthView, nullptr);
  vkDestroyImage(device, depth, nullptr);
  vkFreeMemory(device, depthMemory, nullptr);
  vkDestroyDevice(device, nullptr);
  vkDestroyInstance(instance, nullptr);
  std::printf("sao::vulkan: version check, bad input rejected, sky records A = 1 everywhere: ok\n");
  return 0;
}
