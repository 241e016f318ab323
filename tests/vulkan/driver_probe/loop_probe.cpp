// sao-vk-loop-probe: a plain-Vulkan program (no sao code) showing that Mesa lavapipe 22.3 keeps
// host memory for every vkCmdDispatch of a compute shader with a loop whose trip count comes from a
// uniform buffer that the loop body also reads (docs/ROBUSTNESS.md, section 7, "The frame loop").
// One 8x8 compute pass (sao's spiral-tap loop, loop_probe.comp) is recorded once into 2 command
// buffers and resubmitted for --frames frames with 2 in flight; the program prints
// mallinfo2().uordblks every 100 frames and the growth per frame after 100.
//   sao-vk-loop-probe [dynamic|constant] [--frames N] [--dispatches K]
// dynamic: the trip count (11) is read from the uniform buffer; constant: the same 11 is a
// compile-time constant. Exits 0 whatever it measures: a tool, not a test.
#include <malloc.h>
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "loop_probe_constant_spv.h"  // glslangValidator --vn output, made by the build
#include "loop_probe_dynamic_spv.h"

namespace {

[[noreturn]] void die(const char* what, VkResult r) {
  std::fprintf(stderr, "sao-vk-loop-probe: %s failed (VkResult %d)\n", what, static_cast<int>(r));
  std::exit(1);
}
#define CHECK(call)                      \
  do {                                   \
    if (VkResult r_ = (call); r_ != VK_SUCCESS) die(#call, r_); \
  } while (0)

std::uint32_t memoryType(VkPhysicalDevice pd, std::uint32_t bits, VkMemoryPropertyFlags want) {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(pd, &mp);
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return i;
  die("finding a memory type", VK_ERROR_FEATURE_NOT_PRESENT);
}

struct Image {
  VkImage image;
  VkDeviceMemory memory;
  VkImageView view;
};

Image makeImage(VkPhysicalDevice pd, VkDevice d, VkImageUsageFlags usage) {
  Image img{};
  VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = VK_FORMAT_R32_SFLOAT;
  ii.extent = {64, 64, 1};
  ii.mipLevels = ii.arrayLayers = 1;
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.tiling = VK_IMAGE_TILING_OPTIMAL;
  ii.usage = usage;
  CHECK(vkCreateImage(d, &ii, nullptr, &img.image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(d, img.image, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = memoryType(pd, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  CHECK(vkAllocateMemory(d, &ai, nullptr, &img.memory));
  CHECK(vkBindImageMemory(d, img.image, img.memory, 0));
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = img.image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = ii.format;
  vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  CHECK(vkCreateImageView(d, &vi, nullptr, &img.view));
  return img;
}

}  // namespace

int main(int argc, char** argv) {
  std::string variant = "dynamic";
  int frames = 1000, dispatches = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (a == "--dispatches" && i + 1 < argc) dispatches = std::atoi(argv[++i]);
    else if (a == "dynamic" || a == "constant") variant = a;
    else {
      std::fprintf(stderr, "usage: sao-vk-loop-probe [dynamic|constant] [--frames N] [--dispatches K]\n");
      return 2;
    }
  }
  if (frames < 200 || dispatches < 1) {
    std::fprintf(stderr, "sao-vk-loop-probe: --frames >= 200, --dispatches >= 1\n");
    return 2;
  }
  const bool constant = variant == "constant";
  const std::uint32_t* code = constant ? kConstantSpv : kDynamicSpv;
  const std::size_t codeBytes = constant ? sizeof kConstantSpv : sizeof kDynamicSpv;

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = VK_API_VERSION_1_1;
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  VkInstance instance;
  CHECK(vkCreateInstance(&ici, nullptr, &instance));
  std::uint32_t n = 1;
  VkPhysicalDevice pd;
  if (VkResult r = vkEnumeratePhysicalDevices(instance, &n, &pd); (r != VK_SUCCESS && r != VK_INCOMPLETE) || n == 0)
    die("vkEnumeratePhysicalDevices", r);
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(pd, &props);
  std::uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &families, nullptr);
  std::vector<VkQueueFamilyProperties> fams(families);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &families, fams.data());
  std::uint32_t family = 0;
  while (family < families && !(fams[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;
  const float priority = 1;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qi.queueFamilyIndex = family;
  qi.queueCount = 1;
  qi.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qi;
  VkDevice d;
  CHECK(vkCreateDevice(pd, &dci, nullptr, &d));
  VkQueue queue;
  vkGetDeviceQueue(d, family, 0, &queue);

  const Image src = makeImage(pd, d, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  const Image dst = makeImage(pd, d, VK_IMAGE_USAGE_STORAGE_BIT);
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  VkSampler sampler;
  CHECK(vkCreateSampler(d, &si, nullptr, &sampler));
  const VkDescriptorSetLayoutBinding bindings[3] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = 3;
  li.pBindings = bindings;
  VkDescriptorSetLayout setLayout;
  CHECK(vkCreateDescriptorSetLayout(d, &li, nullptr, &setLayout));
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout;
  VkPipelineLayout layout;
  CHECK(vkCreatePipelineLayout(d, &pli, nullptr, &layout));
  VkShaderModuleCreateInfo smi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  smi.codeSize = codeBytes;
  smi.pCode = code;
  VkShaderModule module;
  CHECK(vkCreateShaderModule(d, &smi, nullptr, &module));
  VkComputePipelineCreateInfo cpi{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  cpi.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main"};
  cpi.layout = layout;
  VkPipeline pipeline;
  CHECK(vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &cpi, nullptr, &pipeline));
  const VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1},
                                        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.maxSets = 1;
  dpi.poolSizeCount = 3;
  dpi.pPoolSizes = sizes;
  VkDescriptorPool pool;
  CHECK(vkCreateDescriptorPool(d, &dpi, nullptr, &pool));
  VkDescriptorSetAllocateInfo dsi{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dsi.descriptorPool = pool;
  dsi.descriptorSetCount = 1;
  dsi.pSetLayouts = &setLayout;
  VkDescriptorSet set;
  CHECK(vkAllocateDescriptorSets(d, &dsi, &set));
  // The parameters (std140): proj, then count = 11 taps (sao's medium preset), radius2, turns.
  struct Params {
    float proj[4];
    std::int32_t count;
    float radius2;
    std::int32_t turns;
    std::int32_t pad;
  };
  const Params params{{-0.02f, -0.02f, 0.64f, 0.64f}, 11, 1.0f, 7, 0};
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = sizeof params;
  bci.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  VkBuffer ubo;
  CHECK(vkCreateBuffer(d, &bci, nullptr, &ubo));
  VkMemoryRequirements ureq;
  vkGetBufferMemoryRequirements(d, ubo, &ureq);
  VkMemoryAllocateInfo uai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  uai.allocationSize = ureq.size;
  uai.memoryTypeIndex = memoryType(pd, ureq.memoryTypeBits,
                                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory uboMemory;
  CHECK(vkAllocateMemory(d, &uai, nullptr, &uboMemory));
  CHECK(vkBindBufferMemory(d, ubo, uboMemory, 0));
  void* mapped = nullptr;
  CHECK(vkMapMemory(d, uboMemory, 0, sizeof params, 0, &mapped));
  std::memcpy(mapped, &params, sizeof params);
  vkUnmapMemory(d, uboMemory);
  const VkDescriptorBufferInfo uboInfo{ubo, 0, sizeof params};
  const VkDescriptorImageInfo srcInfo{sampler, src.view, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo dstInfo{VK_NULL_HANDLE, dst.view, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet writes[3] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                    {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  for (int i = 0; i < 3; ++i) {
    writes[i].dstSet = set;
    writes[i].dstBinding = static_cast<std::uint32_t>(i);
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = bindings[i].descriptorType;
    if (i < 2) writes[i].pImageInfo = i == 0 ? &srcInfo : &dstInfo;
    else writes[i].pBufferInfo = &uboInfo;
  }
  vkUpdateDescriptorSets(d, 3, writes, 0, nullptr);

  VkCommandPoolCreateInfo cpci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  cpci.queueFamilyIndex = family;
  VkCommandPool cmdPool;
  CHECK(vkCreateCommandPool(d, &cpci, nullptr, &cmdPool));
  VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cai.commandPool = cmdPool;
  cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cai.commandBufferCount = 2;
  VkCommandBuffer cmds[2];
  CHECK(vkAllocateCommandBuffers(d, &cai, cmds));
  // Each buffer: both images UNDEFINED -> GENERAL (contents discarded every frame), the source
  // cleared, K dispatches ordered by barriers.
  for (VkCommandBuffer cmd : cmds) {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    CHECK(vkBeginCommandBuffer(cmd, &bi));
    VkImageMemoryBarrier entry[2] = {{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER}, {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER}};
    for (int i = 0; i < 2; ++i) {
      entry[i].srcAccessMask = i == 0 ? 0 : VK_ACCESS_SHADER_WRITE_BIT;  // src: after last frame's reads
      entry[i].dstAccessMask = i == 0 ? VK_ACCESS_TRANSFER_WRITE_BIT : VK_ACCESS_SHADER_WRITE_BIT;
      entry[i].oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      entry[i].newLayout = VK_IMAGE_LAYOUT_GENERAL;
      entry[i].srcQueueFamilyIndex = entry[i].dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      entry[i].image = i == 0 ? src.image : dst.image;
      entry[i].subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    }
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         2, entry);
    // Geometry everywhere (camera-space z = -1), so every invocation runs the loop.
    const VkClearColorValue depth{{-1.0f, 0.0f, 0.0f, 0.0f}};
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, src.image, VK_IMAGE_LAYOUT_GENERAL, &depth, 1, &all);
    VkMemoryBarrier cleared{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &cleared, 0,
                         nullptr, 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
    for (int k = 0; k < dispatches; ++k) {
      VkMemoryBarrier waw{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_WRITE_BIT};
      if (k) vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                                  &waw, 0, nullptr, 0, nullptr);
      vkCmdDispatch(cmd, 8, 8, 1);
    }
    CHECK(vkEndCommandBuffer(cmd));
  }
  VkFence fences[2];
  for (VkFence& f : fences) {
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
    CHECK(vkCreateFence(d, &fi, nullptr, &f));
  }

  std::printf("%s: shader '%s', %d dispatch(es) per frame, %d frames, 2 in flight\n", props.deviceName,
              variant.c_str(), dispatches, frames);
  std::size_t warm = 0;
  for (int f = 0; f < frames; ++f) {
    VkFence fence = fences[f % 2];
    CHECK(vkWaitForFences(d, 1, &fence, VK_TRUE, UINT64_MAX));
    CHECK(vkResetFences(d, 1, &fence));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmds[f % 2];
    CHECK(vkQueueSubmit(queue, 1, &submit, fence));
    if ((f + 1) % 100 == 0) {
      const std::size_t heap = mallinfo2().uordblks;
      std::printf("frame %5d: %zu bytes in use\n", f + 1, heap);
      if (f + 1 == 100) warm = heap;
    }
  }
  CHECK(vkDeviceWaitIdle(d));
  const double perFrame = (double(mallinfo2().uordblks) - double(warm)) / (frames - 100);
  std::printf("growth after 100 frames: %.1f bytes/frame (%.1f per dispatch)\n", perFrame, perFrame / dispatches);

  for (VkFence f : fences) vkDestroyFence(d, f, nullptr);
  vkDestroyCommandPool(d, cmdPool, nullptr);
  vkDestroyDescriptorPool(d, pool, nullptr);
  vkDestroyPipeline(d, pipeline, nullptr);
  vkDestroyShaderModule(d, module, nullptr);
  vkDestroyPipelineLayout(d, layout, nullptr);
  vkDestroyDescriptorSetLayout(d, setLayout, nullptr);
  vkDestroySampler(d, sampler, nullptr);
  vkDestroyBuffer(d, ubo, nullptr);
  vkFreeMemory(d, uboMemory, nullptr);
  for (const Image& i : {src, dst}) {
    vkDestroyImageView(d, i.view, nullptr);
    vkDestroyImage(d, i.image, nullptr);
    vkFreeMemory(d, i.memory, nullptr);
  }
  vkDestroyDevice(d, nullptr);
  vkDestroyInstance(instance, nullptr);
  return 0;
}
