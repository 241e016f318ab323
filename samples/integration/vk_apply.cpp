// The Vulkan apply step: SAO multiplied into the engine's own lit colour target in the effect's
// final pass (the target passed to record() as its output + OutputBlend::Multiply on RGB), no
// composite pass of the engine's own. The engine's frame is a stand-in: a depth buffer uploaded from a procedural floor meeting a
// back wall, and a colour target cleared to one colour. The colour is read back and checked: alpha
// untouched, R, G and B scaled alike by A in [0, 1], open floor and wall kept, the crease darkened.
// Only the installed sao::vulkan and the system's Vulkan loader are used (tests/package builds it
// against the package); the lines between the sao-apply markers are the whole integration.
// Exit status 1 on any failure.
#include <vulkan/vulkan.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include "sao/image.h"
#include "sao/presets.h"
#include "sao/vulkan/effect.h"

// An example's error handling: a failed Vulkan call ends the program.
#define SAO_VK_CHECK(call)                                                    \
  do {                                                                        \
    if (VkResult r = (call); r != VK_SUCCESS) {                               \
      std::fprintf(stderr, "%s failed: VkResult %d\n", #call, int(r));        \
      std::exit(1);                                                           \
    }                                                                         \
  } while (false)

namespace {

// The scene, in metres, camera space (looking down -z, y up): a floor at y = -1 meeting a wall at
// z = -5 (the crease), seen with a 60 degree field of view.
constexpr std::uint32_t kWidth = 320, kHeight = 180;
constexpr double kFovy = std::numbers::pi / 3, kNear = 0.1, kFloorY = -1.0, kWallZ = -5.0;

// Camera-space distance along the view axis of the surface seen at row `row`. Rows are stored from
// ndc.y = -1 (sao::Camera's convention, Vulkan's top row), i.e. from the camera's lowest ray.
double sceneDistance(std::uint32_t row) {
  const double ndcY = -1.0 + 2.0 * (row + 0.5) / kHeight;
  const double rayY = ndcY * std::tan(kFovy / 2);  // the ray's y at distance 1
  const double wall = -kWallZ;
  return rayY < 0 ? std::min(wall, kFloorY / rayY) : wall;  // the floor, where it is in front of the wall
}

// The colour target's clear value: exact binary16 values, so every texel's value before the apply
// is known without a readback.
constexpr float kLit[4] = {0.875f, 0.625f, 0.375f, 1.0f};

}  // namespace

int main() {
  // Stand-in for your engine: a Vulkan 1.1 device with a compute queue family and
  // shaderStorageImageExtendedFormats (what sao::vk needs) ...
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "sao apply example", 1, nullptr, 0,
                        VK_API_VERSION_1_1};
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

  // ... its memory, images and buffers: a depth buffer, the lit colour target (STORAGE for the
  // apply step), a host buffer to upload the depth and one to read the colour back.
  VkPhysicalDeviceMemoryProperties memoryProperties;
  vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memoryProperties);
  auto allocate = [&](VkMemoryRequirements needs, VkMemoryPropertyFlags want) {
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, needs.size, 0};
    while (info.memoryTypeIndex < memoryProperties.memoryTypeCount &&
           !((needs.memoryTypeBits & (1u << info.memoryTypeIndex)) &&
             (memoryProperties.memoryTypes[info.memoryTypeIndex].propertyFlags & want) == want))
      ++info.memoryTypeIndex;
    if (info.memoryTypeIndex == memoryProperties.memoryTypeCount)
      std::fprintf(stderr, "no memory type with flags %#x\n", unsigned(want)), std::exit(1);
    VkDeviceMemory memory;
    SAO_VK_CHECK(vkAllocateMemory(device, &info, nullptr, &memory));
    return memory;
  };
  struct Image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
  };
  auto makeImage = [&](VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {kWidth, kHeight, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.usage = usage;
    Image result;
    SAO_VK_CHECK(vkCreateImage(device, &info, nullptr, &result.image));
    VkMemoryRequirements needs;
    vkGetImageMemoryRequirements(device, result.image, &needs);
    result.memory = allocate(needs, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    SAO_VK_CHECK(vkBindImageMemory(device, result.image, result.memory, 0));
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = result.image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = {aspect, 0, 1, 0, 1};
    SAO_VK_CHECK(vkCreateImageView(device, &viewInfo, nullptr, &result.view));
    return result;
  };
  struct Buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void* data;
  };
  auto makeBuffer = [&](VkDeviceSize size, VkBufferUsageFlags usage) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, usage};
    Buffer result;
    SAO_VK_CHECK(vkCreateBuffer(device, &info, nullptr, &result.buffer));
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(device, result.buffer, &needs);
    result.memory = allocate(needs, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    SAO_VK_CHECK(vkBindBufferMemory(device, result.buffer, result.memory, 0));
    SAO_VK_CHECK(vkMapMemory(device, result.memory, 0, VK_WHOLE_SIZE, 0, &result.data));
    return result;
  };
  const Image depth = makeImage(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                VK_IMAGE_ASPECT_DEPTH_BIT);
  const Image color = makeImage(VK_FORMAT_R16G16B16A16_SFLOAT,
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                VK_IMAGE_ASPECT_COLOR_BIT);
  const Buffer upload = makeBuffer(VkDeviceSize(kWidth) * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  const Buffer readback = makeBuffer(VkDeviceSize(kWidth) * kHeight * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  // The scene's depth, reversed z with an infinite far plane: window depth = near / distance.
  std::vector<float> depthTexels(std::size_t(kWidth) * kHeight);
  for (std::uint32_t y = 0; y < kHeight; ++y)
    std::fill_n(depthTexels.begin() + std::size_t(y) * kWidth, kWidth, float(kNear / sceneDistance(y)));
  std::memcpy(upload.data, depthTexels.data(), depthTexels.size() * sizeof(float));

  // Your frame: the depth uploaded and made readable by compute, the colour "lit" (cleared) and
  // made readable by compute in GENERAL (the apply step reads each texel), ...
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, family};
  VkCommandPool pool;
  SAO_VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  VkCommandBufferAllocateInfo bufferInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                         VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  VkCommandBuffer cmd;
  SAO_VK_CHECK(vkAllocateCommandBuffers(device, &bufferInfo, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  SAO_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  const VkImageSubresourceRange depthRange{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
  const VkImageSubresourceRange colorRange{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkImageMemoryBarrier toTransfer[2];
  for (int i = 0; i < 2; ++i)
    toTransfer[i] = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                     VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_QUEUE_FAMILY_IGNORED,
                     VK_QUEUE_FAMILY_IGNORED, i ? color.image : depth.image, i ? colorRange : depthRange};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                       nullptr, 2, toTransfer);
  const VkBufferImageCopy depthCopy{0, 0, 0, {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1}, {0, 0, 0}, {kWidth, kHeight, 1}};
  vkCmdCopyBufferToImage(cmd, upload.buffer, depth.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &depthCopy);
  const VkClearColorValue lit{{kLit[0], kLit[1], kLit[2], kLit[3]}};
  vkCmdClearColorImage(cmd, color.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &lit, 1, &colorRange);
  VkImageMemoryBarrier toCompute[2];
  for (int i = 0; i < 2; ++i)
    toCompute[i] = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                    VK_ACCESS_SHADER_READ_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    i ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_QUEUE_FAMILY_IGNORED,
                    VK_QUEUE_FAMILY_IGNORED, i ? color.image : depth.image, i ? colorRange : depthRange};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                       nullptr, 2, toCompute);

  // ... then the effect: AO from the depth, multiplied into the colour's RGB, left in GENERAL for
  // the copy below (an engine would name its tone-mapping pass's stage and access instead).
  // [sao-apply]
  sao::vk::Config config;  // where the output is read afterwards
  config.outputLayout = VK_IMAGE_LAYOUT_GENERAL;
  config.outputDstStages = VK_PIPELINE_STAGE_TRANSFER_BIT;
  config.outputDstAccess = VK_ACCESS_TRANSFER_READ_BIT;
  std::unique_ptr<sao::vk::Effect> ao;
  sao::Status status = sao::vk::Effect::create(deviceContext, config, ao);
  const sao::Camera camera = sao::perspectiveCamera(kFovy, kWidth, kHeight, kNear, INFINITY, sao::ClipDepth::ZeroToOne,
                                                    /*reversedZ=*/true);
  const sao::Settings settings = sao::presetSettings(sao::Preset::Medium);
  sao::vk::Inputs inputs;
  inputs.depth = {depth.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, {kWidth, kHeight}, VK_FORMAT_D32_SFLOAT};
  inputs.outputChannels = sao::kChannelR | sao::kChannelG | sao::kChannelB;  // alpha kept
  inputs.outputBlend = sao::OutputBlend::Multiply;
  // Your lit colour target, RGB multiplied by A: its format selects the effect's final pass.
  const sao::vk::OutputImage litTarget{color.image, color.view, VK_FORMAT_R16G16B16A16_SFLOAT, {kWidth, kHeight},
                                       VK_IMAGE_LAYOUT_GENERAL};
  if (status) status = ao->record(cmd, camera, settings, inputs, &litTarget);
  // [/sao-apply]

  // The colour read back (a stand-in for the engine's next pass), made visible to the host.
  const VkBufferImageCopy colorCopy{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {kWidth, kHeight, 1}};
  vkCmdCopyImageToBuffer(cmd, color.image, VK_IMAGE_LAYOUT_GENERAL, readback.buffer, 1, &colorCopy);
  const VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                                     VK_ACCESS_HOST_READ_BIT, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED,
                                     readback.buffer, 0, VK_WHOLE_SIZE};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &toHost, 0,
                       nullptr);
  SAO_VK_CHECK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  SAO_VK_CHECK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
  SAO_VK_CHECK(vkQueueWaitIdle(queue));
  if (!status) std::fprintf(stderr, "sao: %s\n", status.message.c_str());

  // The checks. Each texel's RGB must be its lit colour times one A in [0, 1] (each channel rounded
  // once to binary16: the channels' ranges of A, widened by one binary16 step, must meet) and its
  // alpha exactly 1. By their camera-space distance d (metres) to the crease, 95% of the open
  // texels (d > 2, twice the radius) keep A >= 0.97 and those along it (d < 0.1) have a median A
  // below 0.75 (lavapipe: 100% and 0.569).
  std::size_t badAlpha = 0, badRatio = 0, badChannels = 0;
  std::vector<float> open, crease;
  const auto* texels = static_cast<const std::uint16_t*>(readback.data);
  for (std::uint32_t y = 0; status && y < kHeight; ++y) {
    const double distance = sceneDistance(y);
    const double rayY = (-1.0 + 2.0 * (y + 0.5) / kHeight) * std::tan(kFovy / 2);
    const double d = distance < -kWallZ ? -kWallZ - distance : rayY * distance - kFloorY;  // floor : wall
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::uint16_t* texel = texels + (std::size_t(y) * kWidth + x) * 4;
      badAlpha += sao::halfToFloat(texel[3]) != 1.0f;
      float lo = -INFINITY, hi = INFINITY;
      for (int c = 0; c < 3; ++c) {
        const float value = sao::halfToFloat(texel[c]), step = sao::halfToFloat(std::uint16_t(texel[c] + 1)) - value;
        lo = std::max(lo, (value - step) / kLit[c]);
        hi = std::min(hi, (value + step) / kLit[c]);
        badRatio += !(value >= 0.0f && value <= kLit[c]);
      }
      badChannels += !(lo <= hi);
      const float a = sao::halfToFloat(texel[0]) / kLit[0];
      if (d > 2.0) open.push_back(a);
      if (d < 0.1) crease.push_back(a);
    }
  }
  auto median = [](std::vector<float> v) {
    if (v.empty()) return NAN;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const auto openAbove = std::count_if(open.begin(), open.end(), [](float a) { return a >= 0.97f; });
  const double openKept = open.empty() ? 0.0 : double(openAbove) / open.size();
  const float openMedian = median(open), creaseMedian = median(crease);
  const bool ok = status && !badAlpha && !badRatio && !badChannels && openKept >= 0.95 && creaseMedian < 0.75f;
  std::printf("Vulkan apply: %s, %ux%u; alpha changed %zu, RGB/lit outside [0,1] %zu, channels apart %zu; "
              "open (%zu texels) median %.4f, %.1f%% >= 0.97; crease (%zu) median %.4f\n",
              ok ? "ok" : "failed", kWidth, kHeight, badAlpha, badRatio, badChannels, open.size(), openMedian,
              100.0 * openKept, crease.size(), creaseMedian);

  ao.reset();
  vkDestroyCommandPool(device, pool, nullptr);
  for (const Image& image : {depth, color}) {
    vkDestroyImageView(device, image.view, nullptr);
    vkDestroyImage(device, image.image, nullptr);
    vkFreeMemory(device, image.memory, nullptr);
  }
  for (const Buffer& buffer : {upload, readback}) {
    vkDestroyBuffer(device, buffer.buffer, nullptr);
    vkFreeMemory(device, buffer.memory, nullptr);
  }
  vkDestroyDevice(device, nullptr);
  vkDestroyInstance(instance, nullptr);
  return ok ? 0 : 1;
}
