#include "vk_msaa_depth_writer.h"

#include <stdint.h>  // uint32_t for glslangValidator's --vn headers

#include <cstring>
#include <string>
#include <vector>

#include "msaa_depth.h"
#include "msaa_depth_write_frag_spv.h"  // glslangValidator --vn output, made by the build
#include "msaa_depth_write_vert_spv.h"

namespace sao::vktest {
namespace {

Status vkFailed(const char* call, VkResult r) {
  return Status::error(StatusCode::DriverError, std::string(call) + " failed (VkResult " + std::to_string(r) + ")");
}

// Everything but the image, destroyed when the write is done (or failed).
struct Objects {
  vk::headless::Context& ctx;
  vk::headless::Buffer values;
  VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkRenderPass renderPass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  ~Objects() {
    const VkDevice d = ctx.device();
    if (pipeline) vkDestroyPipeline(d, pipeline, nullptr);
    if (framebuffer) vkDestroyFramebuffer(d, framebuffer, nullptr);
    if (renderPass) vkDestroyRenderPass(d, renderPass, nullptr);
    if (pipelineLayout) vkDestroyPipelineLayout(d, pipelineLayout, nullptr);
    if (pool) vkDestroyDescriptorPool(d, pool, nullptr);
    if (setLayout) vkDestroyDescriptorSetLayout(d, setLayout, nullptr);
    if (frag) vkDestroyShaderModule(d, frag, nullptr);
    if (vert) vkDestroyShaderModule(d, vert, nullptr);
    ctx.destroy(values);
  }
};

struct Push {
  std::int32_t width, samples, sampleIndex;
};

Status createModule(VkDevice d, const std::uint32_t* code, std::size_t bytes, VkShaderModule& out) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = bytes;
  ci.pCode = code;
  if (VkResult r = vkCreateShaderModule(d, &ci, nullptr, &out); r != VK_SUCCESS) return vkFailed("vkCreateShaderModule", r);
  return Status::success();
}

// The image, its memory (device-local when there is such a type) and a 2D view of the depth aspect.
Status createImage(vk::headless::Context& ctx, Extent extent, VkSampleCountFlagBits samples, vk::headless::Image& out) {
  const VkDevice d = ctx.device();
  out = {};
  out.format = VK_FORMAT_D32_SFLOAT;
  out.extent = extent;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = VK_FORMAT_D32_SFLOAT;
  ci.extent = {extent.width, extent.height, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = 1;
  ci.samples = samples;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (VkResult r = vkCreateImage(d, &ci, nullptr, &out.image); r != VK_SUCCESS) return vkFailed("vkCreateImage", r);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(d, out.image, &req);
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mem);
  int type = -1;
  for (std::uint32_t i = 0; i < mem.memoryTypeCount && type < 0; ++i)
    if ((req.memoryTypeBits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
      type = int(i);
  for (std::uint32_t i = 0; i < mem.memoryTypeCount && type < 0; ++i)
    if (req.memoryTypeBits & (1u << i)) type = int(i);
  if (type < 0) return Status::error(StatusCode::DriverError, "no memory type for the multisampled depth image");
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, std::uint32_t(type)};
  if (VkResult r = vkAllocateMemory(d, &ai, nullptr, &out.memory); r != VK_SUCCESS) return vkFailed("vkAllocateMemory", r);
  if (VkResult r = vkBindImageMemory(d, out.image, out.memory, 0); r != VK_SUCCESS) return vkFailed("vkBindImageMemory", r);
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = out.image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = VK_FORMAT_D32_SFLOAT;
  vi.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
  if (VkResult r = vkCreateImageView(d, &vi, nullptr, &out.view); r != VK_SUCCESS) return vkFailed("vkCreateImageView", r);
  return Status::success();
}

// Attachment 0, the depth image: cleared (a sample left unwritten would read 0.5 and show in the
// comparison), stored, and left in `layout` with its writes visible to compute-shader reads.
Status createRenderPass(VkDevice d, VkSampleCountFlagBits samples, VkImageLayout layout, VkRenderPass& out) {
  VkAttachmentDescription a{};
  a.format = VK_FORMAT_D32_SFLOAT;
  a.samples = samples;
  a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a.finalLayout = layout;
  const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.pDepthStencilAttachment = &ref;
  constexpr VkPipelineStageFlags tests =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = tests;
  deps[0].dstStageMask = tests;
  deps[0].dstAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = tests;
  deps[1].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  ci.attachmentCount = 1;
  ci.pAttachments = &a;
  ci.subpassCount = 1;
  ci.pSubpasses = &sub;
  ci.dependencyCount = 2;
  ci.pDependencies = deps;
  if (VkResult r = vkCreateRenderPass(d, &ci, nullptr, &out); r != VK_SUCCESS) return vkFailed("vkCreateRenderPass", r);
  return Status::success();
}

Status createPipeline(const Objects& o, Extent extent, VkSampleCountFlagBits samples, VkPipeline& out) {
  VkPipelineShaderStageCreateInfo stages[2]{};
  for (auto& s : stages) {
    s.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    s.pName = "main";
  }
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = o.vert;
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = o.frag;
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  // A positive height: framebuffer y = 0 (the image's row 0) is the top, as the buffer's row 0.
  const VkViewport viewport{0.0f, 0.0f, float(extent.width), float(extent.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {extent.width, extent.height}};
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.pViewports = &viewport;
  vp.scissorCount = 1;
  vp.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = samples;  // per-pixel shading; gl_SampleMask picks the sample
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_ALWAYS;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vertexInput;
  ci.pInputAssemblyState = &assembly;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &raster;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &blend;
  ci.layout = o.pipelineLayout;
  ci.renderPass = o.renderPass;
  ci.subpass = 0;
  if (VkResult r = vkCreateGraphicsPipelines(o.ctx.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &out); r != VK_SUCCESS)
    return vkFailed("vkCreateGraphicsPipelines", r);
  return Status::success();
}

// What the device must support for the write and for the effect's read.
Status checkSupport(vk::headless::Context& ctx, const DepthImage& depth, VkImageLayout layout) {
  const auto bad = [](const std::string& m) { return Status::error(StatusCode::InvalidInput, "writeMultisampledDepth: " + m); };
  if (depth.format != DepthFormat::D32F) return bad("the depth is not D32F");
  const std::uint32_t n = depth.samples;
  if (n < 2 || n > 64 || (n & (n - 1)) != 0) return bad(std::to_string(n) + " samples is not a multisample count");
  if (depth.extent.width == 0 || depth.extent.height == 0 ||
      depth.texels.size() != std::size_t(depth.extent.width) * depth.extent.height * n)
    return bad("the texels do not match the extent and sample count");
  if (layout != VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL && layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
    return bad("the layout must be DEPTH_STENCIL_READ_ONLY_OPTIMAL or SHADER_READ_ONLY_OPTIMAL");
  const auto& limits = ctx.properties().limits;
  VkImageFormatProperties fp{};
  const VkResult r = vkGetPhysicalDeviceImageFormatProperties(
      ctx.physicalDevice(), VK_FORMAT_D32_SFLOAT, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, 0, &fp);
  if (r != VK_SUCCESS || !(fp.sampleCounts & n) || !(limits.framebufferDepthSampleCounts & n) ||
      !(limits.sampledImageDepthSampleCounts & n))
    return Status::error(StatusCode::UnsupportedFormat,
                         "writeMultisampledDepth: the device cannot render and sample D32_SFLOAT with " +
                             std::to_string(n) + " samples");
  return Status::success();
}

}  // namespace

Status writeMultisampledDepth(vk::headless::Context& ctx, const DepthImage& depth, VkImageLayout layout,
                              vk::headless::Image& out) {
  out = {};
  if (Status st = checkSupport(ctx, depth, layout); !st) return st;
  const VkDevice d = ctx.device();
  const auto samples = static_cast<VkSampleCountFlagBits>(depth.samples);
  Objects o{ctx};
  const std::vector<float> values = test::sampleValues(depth);  // one per sample, in DepthImage's order
  if (Status st = ctx.createBuffer(values.size() * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, o.values); !st)
    return st;
  std::memcpy(o.values.mapped, values.data(), values.size() * sizeof(float));  // coherent; the submit makes it visible

  if (Status st = createModule(d, kMsaaDepthWriteVertSpv, sizeof kMsaaDepthWriteVertSpv, o.vert); !st) return st;
  if (Status st = createModule(d, kMsaaDepthWriteFragSpv, sizeof kMsaaDepthWriteFragSpv, o.frag); !st) return st;
  const VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo sli{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  sli.bindingCount = 1;
  sli.pBindings = &binding;
  if (VkResult r = vkCreateDescriptorSetLayout(d, &sli, nullptr, &o.setLayout); r != VK_SUCCESS)
    return vkFailed("vkCreateDescriptorSetLayout", r);
  const VkPushConstantRange range{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(Push)};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &o.setLayout;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &range;
  if (VkResult r = vkCreatePipelineLayout(d, &pli, nullptr, &o.pipelineLayout); r != VK_SUCCESS)
    return vkFailed("vkCreatePipelineLayout", r);
  const VkDescriptorPoolSize poolSize{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.maxSets = 1;
  dpi.poolSizeCount = 1;
  dpi.pPoolSizes = &poolSize;
  if (VkResult r = vkCreateDescriptorPool(d, &dpi, nullptr, &o.pool); r != VK_SUCCESS)
    return vkFailed("vkCreateDescriptorPool", r);
  VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dai.descriptorPool = o.pool;
  dai.descriptorSetCount = 1;
  dai.pSetLayouts = &o.setLayout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (VkResult r = vkAllocateDescriptorSets(d, &dai, &set); r != VK_SUCCESS) return vkFailed("vkAllocateDescriptorSets", r);
  const VkDescriptorBufferInfo bufferInfo{o.values.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = set;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  write.pBufferInfo = &bufferInfo;
  vkUpdateDescriptorSets(d, 1, &write, 0, nullptr);

  Status st = createImage(ctx, depth.extent, samples, out);
  if (st) st = createRenderPass(d, samples, layout, o.renderPass);
  if (st) {
    VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fi.renderPass = o.renderPass;
    fi.attachmentCount = 1;
    fi.pAttachments = &out.view;
    fi.width = depth.extent.width;
    fi.height = depth.extent.height;
    fi.layers = 1;
    if (VkResult r = vkCreateFramebuffer(d, &fi, nullptr, &o.framebuffer); r != VK_SUCCESS)
      st = vkFailed("vkCreateFramebuffer", r);
  }
  if (st) st = createPipeline(o, depth.extent, samples, o.pipeline);
  if (st)
    st = ctx.submit([&](VkCommandBuffer cmd) {
      VkClearValue clear{};
      clear.depthStencil = {0.5f, 0};
      VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
      bi.renderPass = o.renderPass;
      bi.framebuffer = o.framebuffer;
      bi.renderArea = {{0, 0}, {depth.extent.width, depth.extent.height}};
      bi.clearValueCount = 1;
      bi.pClearValues = &clear;
      vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, o.pipeline);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, o.pipelineLayout, 0, 1, &set, 0, nullptr);
      for (std::uint32_t s = 0; s < depth.samples; ++s) {
        const Push push{std::int32_t(depth.extent.width), std::int32_t(depth.samples), std::int32_t(s)};
        vkCmdPushConstants(cmd, o.pipelineLayout, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push, &push);
        vkCmdDraw(cmd, 3, 1, 0, 0);
      }
      vkCmdEndRenderPass(cmd);
    });
  if (!st) {
    ctx.destroy(out);
    return st;
  }
  out.layout = layout;
  return Status::success();
}

}  // namespace sao::vktest
