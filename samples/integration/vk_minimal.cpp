// The smallest Vulkan integration: SAO recorded into your own command buffer. Only the installed
// sao::vulkan and the system's Vulkan loader are used (tests/package builds it against the
// package); the block between the readme markers is quoted in README.md (a test keeps the two
// identical).
#include <vulkan/vulkan.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <vector>

#include "sao/vulkan/effect.h"

// An example's error handling: a failed Vulkan call ends the program.
#define SAO_VK_CHECK(call)                                                    \
  do {                                                                 \
    if (VkResult r = (call); r != VK_SUCCESS) {                        \
      std::fprintf(stderr, "%s failed: VkResult %d\n", #call, int(r)); \
      std::exit(1);                                                    \
    }                                                                  \
  } while (false)

int main() {
  // Stand-in for your engine: what sao::vk needs of a device (Vulkan 1.1, a queue family with
  // compute, shaderStorageImageExtendedFormats enabled) ...
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "sao example", 1, nullptr, 0, VK_API_VERSION_1_1};
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &app;
  VkInstance instance;
  SAO_VK_CHECK(vkCreateInstance(&instanceInfo, nullptr, &instance));
  std::uint32_t count = 1;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;  // the first device, and its first compute family
  if (vkEnumeratePhysicalDevices(instance, &count, &physicalDevice) < 0 || !physicalDevice) return 1;
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &count, families.data());
  std::uint32_t family = 0;
  while (family < count && !(families[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;
  if (family == count) return std::fprintf(stderr, "no queue family with compute\n"), 1;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &priority};
  VkPhysicalDeviceFeatures features{};
  features.shaderStorageImageExtendedFormats = VK_TRUE;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.pEnabledFeatures = &features;
  VkDevice device;
  SAO_VK_CHECK(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device));
  VkQueue queue;
  vkGetDeviceQueue(device, family, 0, &queue);
  sao::vk::DeviceContext deviceContext{instance, physicalDevice, device, vkGetInstanceProcAddr,
                                       vkGetDeviceProcAddr, family};
  deviceContext.enabledFeatures = &features;

  // ... and a depth image, cleared to a wall facing the camera by the command buffer below.
  const std::uint32_t width = 320, height = 180;
  VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  imageInfo.imageType = VK_IMAGE_TYPE_2D;
  imageInfo.format = VK_FORMAT_D32_SFLOAT;
  imageInfo.extent = {width, height, 1};
  imageInfo.mipLevels = imageInfo.arrayLayers = 1;
  imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
  imageInfo.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  VkImage depthImage;
  SAO_VK_CHECK(vkCreateImage(device, &imageInfo, nullptr, &depthImage));
  VkMemoryRequirements needs;
  vkGetImageMemoryRequirements(device, depthImage, &needs);
  VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, needs.size, 0};
  while (!(needs.memoryTypeBits & (1u << allocation.memoryTypeIndex))) ++allocation.memoryTypeIndex;
  VkDeviceMemory depthMemory;
  SAO_VK_CHECK(vkAllocateMemory(device, &allocation, nullptr, &depthMemory));
  SAO_VK_CHECK(vkBindImageMemory(device, depthImage, depthMemory, 0));
  const VkImageSubresourceRange depthRange{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = depthImage;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = VK_FORMAT_D32_SFLOAT;
  viewInfo.subresourceRange = depthRange;
  VkImageView depthView;
  SAO_VK_CHECK(vkCreateImageView(device, &viewInfo, nullptr, &depthView));

  // [readme-vulkan]
  std::unique_ptr<sao::vk::Effect> ao;
  sao::Status status = sao::vk::Effect::create(deviceContext, {}, ao);  // Config: ring, output layout
  sao::Camera camera = sao::perspectiveCamera(std::numbers::pi / 3, width, height, 0.1, INFINITY,
                                              sao::ClipDepth::ZeroToOne, /*reversedZ=*/true);
  sao::Settings settings = sao::presetSettings(sao::Preset::Medium);
  settings.radius = 0.5f;  // metres
  sao::vk::Inputs inputs;
  inputs.depth = {depthView, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, {width, height}, VK_FORMAT_D32_SFLOAT};
  auto recordInto = [&](VkCommandBuffer cmd) { if (status) status = ao->record(cmd, camera, settings, inputs); };
  // ... recordInto(yourCommandBuffer) each frame, submit; the output is in SHADER_READ_ONLY_OPTIMAL:
  // sao::vk::OutputImage result = ao->output();
  // [/readme-vulkan]

  // Your frame: the depth cleared and made readable by compute, then the effect, then submitted.
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, family};
  VkCommandPool pool;
  SAO_VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  VkCommandBufferAllocateInfo bufferInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                         VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  VkCommandBuffer cmd;
  SAO_VK_CHECK(vkAllocateCommandBuffers(device, &bufferInfo, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  SAO_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                               VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, depthImage, depthRange};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &barrier);
  const VkClearDepthStencilValue wall{0.01f, 0};  // reversed z: 10 near planes away
  vkCmdClearDepthStencilImage(cmd, depthImage, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &wall, 1, &depthRange);
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  barrier.newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                       nullptr, 1, &barrier);
  recordInto(cmd);
  SAO_VK_CHECK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  SAO_VK_CHECK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
  SAO_VK_CHECK(vkQueueWaitIdle(queue));

  if (!status) std::fprintf(stderr, "sao: %s\n", status.message.c_str());
  std::printf("Vulkan: %s, output %ux%u\n", status ? "ok" : "failed", status ? ao->output().extent.width : 0,
              status ? ao->output().extent.height : 0);
  ao.reset();
  vkDestroyCommandPool(device, pool, nullptr);
  vkDestroyImageView(device, depthView, nullptr);
  vkDestroyImage(device, depthImage, nullptr);
  vkFreeMemory(device, depthMemory, nullptr);
  vkDestroyDevice(device, nullptr);
  vkDestroyInstance(instance, nullptr);
  return status ? 0 : 1;
}
