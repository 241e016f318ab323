#include "sao/prepass/vk_prepass.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "frame.h"
#include "kPrepassFragSpv.h"
#include "kPrepassPeelFragSpv.h"
#include "kPrepassVertSpv.h"

namespace sao::prepass {
namespace {

Status clipError() {
  return Status::error(StatusCode::InvalidCamera,
                       "prepass: Vulkan's clip depth is [0, 1]; a camera with ClipDepth::NegativeOneToOne cannot be "
                       "rendered here (use ClipDepth::ZeroToOne)");
}

}  // namespace

using vk::headless::Buffer;
using vk::headless::Image;

namespace {

Status vkCheck(VkResult r, const std::string& what) {
  if (r == VK_SUCCESS) return Status::success();
  return Status::error(StatusCode::DriverError, "prepass: " + what + " failed: VkResult " + std::to_string(int(r)));
}

constexpr VkFormat kColorFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

VkFormat vkDepthFormat(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return VK_FORMAT_D16_UNORM;
    case DepthFormat::D24: return VK_FORMAT_X8_D24_UNORM_PACK32;
    case DepthFormat::D32F: return VK_FORMAT_D32_SFLOAT;
    default: return VK_FORMAT_UNDEFINED;
  }
}

const char* vkFormatName(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return "VK_FORMAT_D16_UNORM";
    case DepthFormat::D24: return "VK_FORMAT_X8_D24_UNORM_PACK32";
    case DepthFormat::D32F: return "VK_FORMAT_D32_SFLOAT";
    default: return "(no Vulkan depth format)";
  }
}

std::uint32_t depthBytes(DepthFormat f) { return f == DepthFormat::D16 ? 2 : 4; }

VkDeviceSize align16(VkDeviceSize v) { return (v + 15) & ~VkDeviceSize(15); }

}  // namespace

struct VkPrepass::State {
  vk::headless::Context* alloc = nullptr;  // images and buffers
  VkDevice device = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkPhysicalDeviceLimits limits{};
  VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE, peelFrag = VK_NULL_HANDLE;
  VkDescriptorSetLayout layerSetLayout = VK_NULL_HANDLE, peelSetLayout = VK_NULL_HANDLE;
  VkPipelineLayout layerLayout = VK_NULL_HANDLE, peelLayout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet layerSet = VK_NULL_HANDLE, peelSet = VK_NULL_HANDLE;
  VkSampler sampler = VK_NULL_HANDLE;
  Buffer ubo;

  // Per (format, reversed): the render pass and both pipelines.
  bool pipelinesMade = false;
  DepthFormat pipelineFormat = DepthFormat::D32F;
  bool pipelineReversed = false;
  VkRenderPass renderPass = VK_NULL_HANDLE;
  VkPipeline layerPipeline = VK_NULL_HANDLE, peelPipeline = VK_NULL_HANDLE;

  // Per (extent, format, second layer, render pass): images, framebuffers, the read-back buffer.
  struct Layer {
    Image depth, position, normal;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
  } layers[2];
  bool targetsMade = false;
  Extent extent;
  DepthFormat targetFormat = DepthFormat::D32F;
  bool targetSecond = false;
  Buffer readback;
  VkDeviceSize depthOffset[2]{}, positionOffset[2]{}, normalOffset[2]{};

  // record(): a depth-only render pass and pipeline per (format, reversed), the image per extent.
  struct FrameTarget {
    bool made = false;
    DepthFormat format = DepthFormat::D32F;
    bool reversed = false;
    VkRenderPass pass = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    Image depth;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
  } frameTarget;

  // The expanded mesh.
  Buffer vertices;
  std::uint32_t vertexCount = 0;
  std::uint64_t meshDigest = 0;
  bool haveMesh = false;

  void destroyTargets() {
    for (Layer& l : layers) {
      if (l.framebuffer) vkDestroyFramebuffer(device, l.framebuffer, nullptr);
      alloc->destroy(l.depth);
      alloc->destroy(l.position);
      alloc->destroy(l.normal);
      l = Layer{};
    }
    alloc->destroy(readback);
    targetsMade = false;
  }
  void destroyPipelines() {
    if (layerPipeline) vkDestroyPipeline(device, layerPipeline, nullptr);
    if (peelPipeline) vkDestroyPipeline(device, peelPipeline, nullptr);
    if (renderPass) vkDestroyRenderPass(device, renderPass, nullptr);
    layerPipeline = peelPipeline = VK_NULL_HANDLE;
    renderPass = VK_NULL_HANDLE;
    pipelinesMade = false;
  }
  void destroyFrameTarget() {
    FrameTarget& t = frameTarget;
    if (t.framebuffer) vkDestroyFramebuffer(device, t.framebuffer, nullptr);
    alloc->destroy(t.depth);
    if (t.pipeline) vkDestroyPipeline(device, t.pipeline, nullptr);
    if (t.pass) vkDestroyRenderPass(device, t.pass, nullptr);
    t = FrameTarget{};
  }
  void destroyAll() {
    if (!device) return;
    destroyFrameTarget();
    destroyTargets();
    destroyPipelines();
    alloc->destroy(vertices);
    alloc->destroy(ubo);
    if (sampler) vkDestroySampler(device, sampler, nullptr);
    if (pool) vkDestroyDescriptorPool(device, pool, nullptr);
    if (layerLayout) vkDestroyPipelineLayout(device, layerLayout, nullptr);
    if (peelLayout) vkDestroyPipelineLayout(device, peelLayout, nullptr);
    if (layerSetLayout) vkDestroyDescriptorSetLayout(device, layerSetLayout, nullptr);
    if (peelSetLayout) vkDestroyDescriptorSetLayout(device, peelSetLayout, nullptr);
    for (VkShaderModule m : {vert, frag, peelFrag})
      if (m) vkDestroyShaderModule(device, m, nullptr);
    device = VK_NULL_HANDLE;
  }

  Status createShaders() {
    auto make = [&](const std::uint32_t* code, std::size_t bytes, VkShaderModule& out) {
      VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
      ci.codeSize = bytes;
      ci.pCode = code;
      return vkCheck(vkCreateShaderModule(device, &ci, nullptr, &out), "vkCreateShaderModule");
    };
    if (Status s = make(kPrepassVertSpv, sizeof kPrepassVertSpv, vert); !s) return s;
    if (Status s = make(kPrepassFragSpv, sizeof kPrepassFragSpv, frag); !s) return s;
    return make(kPrepassPeelFragSpv, sizeof kPrepassPeelFragSpv, peelFrag);
  }

  Status createLayouts() {
    VkDescriptorSetLayoutBinding bindings[2]{};
    bindings[0] = {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                   nullptr};
    bindings[1] = {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo dl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    dl.bindingCount = 1;
    dl.pBindings = bindings;
    if (Status s = vkCheck(vkCreateDescriptorSetLayout(device, &dl, nullptr, &layerSetLayout), "vkCreateDescriptorSetLayout");
        !s)
      return s;
    dl.bindingCount = 2;
    if (Status s = vkCheck(vkCreateDescriptorSetLayout(device, &dl, nullptr, &peelSetLayout), "vkCreateDescriptorSetLayout");
        !s)
      return s;
    VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pl.setLayoutCount = 1;
    pl.pSetLayouts = &layerSetLayout;
    if (Status s = vkCheck(vkCreatePipelineLayout(device, &pl, nullptr, &layerLayout), "vkCreatePipelineLayout"); !s)
      return s;
    pl.pSetLayouts = &peelSetLayout;
    if (Status s = vkCheck(vkCreatePipelineLayout(device, &pl, nullptr, &peelLayout), "vkCreatePipelineLayout"); !s)
      return s;

    const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2},
                                           {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1}};
    VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pi.maxSets = 2;
    pi.poolSizeCount = 2;
    pi.pPoolSizes = sizes;
    if (Status s = vkCheck(vkCreateDescriptorPool(device, &pi, nullptr, &pool), "vkCreateDescriptorPool"); !s) return s;
    const VkDescriptorSetLayout setLayouts[2] = {layerSetLayout, peelSetLayout};
    VkDescriptorSet sets[2]{};
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 2;
    ai.pSetLayouts = setLayouts;
    if (Status s = vkCheck(vkAllocateDescriptorSets(device, &ai, sets), "vkAllocateDescriptorSets"); !s) return s;
    layerSet = sets[0];
    peelSet = sets[1];

    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = VK_FILTER_NEAREST;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    if (Status s = vkCheck(vkCreateSampler(device, &si, nullptr, &sampler), "vkCreateSampler"); !s) return s;

    if (Status s = alloc->createBuffer(sizeof(detail::Uniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, ubo); !s) return s;
    VkDescriptorBufferInfo bufferInfo{ubo.buffer, 0, sizeof(detail::Uniforms)};
    VkWriteDescriptorSet writes[2]{};
    for (int i = 0; i < 2; ++i) {
      writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[i].dstSet = sets[i];
      writes[i].dstBinding = 0;
      writes[i].descriptorCount = 1;
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
      writes[i].pBufferInfo = &bufferInfo;
    }
    vkUpdateDescriptorSets(device, 2, writes, 0, nullptr);
    return Status::success();
  }

  Status createRenderPass(VkFormat depthFormat, VkRenderPass& out) {
    VkAttachmentDescription att[3]{};
    for (int i = 0; i < 3; ++i) {
      att[i].format = i < 2 ? kColorFormat : depthFormat;
      att[i].samples = VK_SAMPLE_COUNT_1_BIT;
      att[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      att[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      att[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
      att[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
      att[i].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      // Everything goes to the copies first; the peeling pass then samples the first layer's
      // depth in DEPTH_STENCIL_READ_ONLY_OPTIMAL (a barrier in record()).
      att[i].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    const VkAttachmentReference colors[2] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                             {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
    const VkAttachmentReference depth{2, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 2;
    sub.pColorAttachments = colors;
    sub.pDepthStencilAttachment = &depth;
    VkSubpassDependency deps[2]{};
    // Before: the previous call's copies and peeling reads of these images (write-after-read).
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                           VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    // After: the peeling pass samples the depth; the copies read everything.
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                           VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    ci.attachmentCount = 3;
    ci.pAttachments = att;
    ci.subpassCount = 1;
    ci.pSubpasses = &sub;
    ci.dependencyCount = 2;
    ci.pDependencies = deps;
    return vkCheck(vkCreateRenderPass(device, &ci, nullptr, &out), "vkCreateRenderPass");
  }

  // record()'s pass: depth only, left for the caller's compute and fragment shaders to read.
  Status createFramePass(VkFormat depthFormat, VkRenderPass& out) {
    VkAttachmentDescription att{};
    att.format = depthFormat;
    att.samples = VK_SAMPLE_COUNT_1_BIT;
    att.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    att.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    att.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    att.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.pDepthStencilAttachment = &ref;
    const VkPipelineStageFlags readers = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    const VkPipelineStageFlags tests =
        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    VkSubpassDependency deps[2]{};
    // Before: the previous frame's reads of the depth (write-after-read).
    deps[0] = {VK_SUBPASS_EXTERNAL, 0, readers, tests, 0,
               VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, 0};
    // After: this frame's reads.
    deps[1] = {0, VK_SUBPASS_EXTERNAL, tests, readers, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
               VK_ACCESS_SHADER_READ_BIT, 0};
    VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    ci.attachmentCount = 1;
    ci.pAttachments = &att;
    ci.subpassCount = 1;
    ci.pSubpasses = &sub;
    ci.dependencyCount = 2;
    ci.pDependencies = deps;
    return vkCheck(vkCreateRenderPass(device, &ci, nullptr, &out), "vkCreateRenderPass");
  }

  // Without a fragment shader: depth only, no colour attachments (record()'s pass).
  Status createPipeline(VkRenderPass pass, VkShaderModule fragment, VkPipelineLayout layout, bool reversed,
                        VkPipeline& out) {
    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fragment;
    stages[1].pName = "main";
    const VkVertexInputBindingDescription binding{0, detail::kVertexFloats * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription attributes[2] = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0},
                                                             {1, 0, VK_FORMAT_R32G32B32_SFLOAT, 3 * sizeof(float)}};
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = 1;
    vi.pVertexBindingDescriptions = &binding;
    vi.vertexAttributeDescriptionCount = 2;
    vi.pVertexAttributeDescriptions = attributes;
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = VK_CULL_MODE_NONE;  // thin panels are seen from both sides
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = VK_TRUE;
    ds.depthWriteEnable = VK_TRUE;
    ds.depthCompareOp = reversed ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState blend[2]{};
    for (auto& b : blend)
      b.colorWriteMask =
          VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = fragment ? 2 : 0;
    cb.pAttachments = blend;
    const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dy.dynamicStateCount = 2;
    dy.pDynamicStates = dynamic;
    VkGraphicsPipelineCreateInfo pi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    pi.stageCount = fragment ? 2 : 1;
    pi.pStages = stages;
    pi.pVertexInputState = &vi;
    pi.pInputAssemblyState = &ia;
    pi.pViewportState = &vp;
    pi.pRasterizationState = &rs;
    pi.pMultisampleState = &ms;
    pi.pDepthStencilState = &ds;
    pi.pColorBlendState = &cb;
    pi.pDynamicState = &dy;
    pi.layout = layout;
    pi.renderPass = pass;
    return vkCheck(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &pi, nullptr, &out), "vkCreateGraphicsPipelines");
  }

  Status ensurePipelines(DepthFormat format, bool reversed) {
    if (pipelinesMade && pipelineFormat == format && pipelineReversed == reversed) return Status::success();
    destroyTargets();  // their framebuffers belong to the render pass
    destroyPipelines();
    Status s = createRenderPass(vkDepthFormat(format), renderPass);
    if (s) s = createPipeline(renderPass, frag, layerLayout, reversed, layerPipeline);
    if (s) s = createPipeline(renderPass, peelFrag, peelLayout, reversed, peelPipeline);
    if (!s) {
      destroyPipelines();
      return s;
    }
    pipelineFormat = format;
    pipelineReversed = reversed;
    pipelinesMade = true;
    return Status::success();
  }

  Status ensureTargets(Extent e, DepthFormat format, bool second) {
    if (targetsMade && extent == e && targetFormat == format && targetSecond == second) return Status::success();
    destroyTargets();
    const VkFormat df = vkDepthFormat(format);
    const int count = second ? 2 : 1;
    VkDeviceSize offset = 0;
    const VkDeviceSize texels = VkDeviceSize(e.width) * e.height;
    Status s;
    for (int i = 0; i < count && s; ++i) {
      Layer& l = layers[i];
      VkImageUsageFlags depthUsage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      if (second && i == 0) depthUsage |= VK_IMAGE_USAGE_SAMPLED_BIT;
      const VkImageUsageFlags colorUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      s = alloc->createImage(df, e, depthUsage, VK_IMAGE_ASPECT_DEPTH_BIT, l.depth);
      if (s) s = alloc->createImage(kColorFormat, e, colorUsage, VK_IMAGE_ASPECT_COLOR_BIT, l.position);
      if (s) s = alloc->createImage(kColorFormat, e, colorUsage, VK_IMAGE_ASPECT_COLOR_BIT, l.normal);
      if (s) {
        const VkImageView views[3] = {l.position.view, l.normal.view, l.depth.view};
        VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fi.renderPass = renderPass;
        fi.attachmentCount = 3;
        fi.pAttachments = views;
        fi.width = e.width;
        fi.height = e.height;
        fi.layers = 1;
        s = vkCheck(vkCreateFramebuffer(device, &fi, nullptr, &l.framebuffer), "vkCreateFramebuffer");
      }
      depthOffset[i] = offset;
      offset = align16(offset + texels * depthBytes(format));
      positionOffset[i] = offset;
      offset = align16(offset + texels * 16);
      normalOffset[i] = offset;
      offset = align16(offset + texels * 16);
    }
    if (s) s = alloc->createBuffer(offset, VK_BUFFER_USAGE_TRANSFER_DST_BIT, readback);
    if (!s) {
      destroyTargets();
      return s;
    }
    if (second) {
      const VkDescriptorImageInfo info{sampler, layers[0].depth.view, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL};
      VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w.dstSet = peelSet;
      w.dstBinding = 1;
      w.descriptorCount = 1;
      w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      w.pImageInfo = &info;
      vkUpdateDescriptorSets(device, 1, &w, 0, nullptr);
    }
    extent = e;
    targetFormat = format;
    targetSecond = second;
    targetsMade = true;
    return Status::success();
  }

  Status uploadMesh(const scenes::Mesh& mesh, std::uint64_t digest) {
    if (haveMesh && meshDigest == digest) return Status::success();
    alloc->destroy(vertices);
    haveMesh = false;
    const std::vector<float> v = detail::expandMesh(mesh);
    if (Status s = alloc->createBuffer(v.size() * sizeof(float), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vertices); !s)
      return s;
    std::memcpy(vertices.mapped, v.data(), v.size() * sizeof(float));
    vertexCount = std::uint32_t(v.size() / detail::kVertexFloats);
    meshDigest = digest;
    haveMesh = true;
    return Status::success();
  }

  void record(VkCommandBuffer cmd, const detail::Frame& frame, bool second) {
    // The previous call's copies wrote the read-back buffer: order this call's copies after them.
    VkMemoryBarrier wawBuffer{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                              VK_ACCESS_TRANSFER_WRITE_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &wawBuffer, 0,
                         nullptr, 0, nullptr);
    VkClearValue clears[3]{};
    clears[2].depthStencil = {float(frame.clearDepth), 0};
    const VkViewport viewport{0, 0, float(frame.extent.width), float(frame.extent.height), 0, 1};
    const VkRect2D area{{0, 0}, {frame.extent.width, frame.extent.height}};
    const VkDeviceSize zero = 0;
    for (int i = 0; i < (second ? 2 : 1); ++i) {
      if (i == 1) {
        // The first layer's depth, copied out, becomes the peeling pass's texture.
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = 0;  // after the copy's reads: an execution dependency suffices
        b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        b.newLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = layers[0].depth.image;
        b.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &b);
      }
      VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
      bi.renderPass = renderPass;
      bi.framebuffer = layers[i].framebuffer;
      bi.renderArea = area;
      bi.clearValueCount = 3;
      bi.pClearValues = clears;
      vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
      // A positive viewport height: row 0 of every image is at ndc y = -1.
      vkCmdSetViewport(cmd, 0, 1, &viewport);
      vkCmdSetScissor(cmd, 0, 1, &area);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, i == 0 ? layerPipeline : peelPipeline);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, i == 0 ? layerLayout : peelLayout, 0, 1,
                              i == 0 ? &layerSet : &peelSet, 0, nullptr);
      vkCmdBindVertexBuffers(cmd, 0, 1, &vertices.buffer, &zero);
      vkCmdDraw(cmd, vertexCount, 1, 0, 0);
      vkCmdEndRenderPass(cmd);

      VkBufferImageCopy copy{};
      copy.imageExtent = {frame.extent.width, frame.extent.height, 1};
      copy.bufferOffset = depthOffset[i];
      copy.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
      vkCmdCopyImageToBuffer(cmd, layers[i].depth.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &copy);
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.bufferOffset = positionOffset[i];
      vkCmdCopyImageToBuffer(cmd, layers[i].position.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1,
                             &copy);
      copy.bufferOffset = normalOffset[i];
      vkCmdCopyImageToBuffer(cmd, layers[i].normal.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1,
                             &copy);
    }
    VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                         nullptr);
  }

  Status ensureFrameTarget(Extent e, DepthFormat format, bool reversed) {
    FrameTarget& t = frameTarget;
    if (!t.made || t.format != format || t.reversed != reversed) {
      destroyFrameTarget();
      Status s = createFramePass(vkDepthFormat(format), t.pass);
      if (s) s = createPipeline(t.pass, VK_NULL_HANDLE, layerLayout, reversed, t.pipeline);
      if (!s) {
        destroyFrameTarget();
        return s;
      }
      t.made = true;
      t.format = format;
      t.reversed = reversed;
    }
    if (t.depth.image && t.depth.extent == e) return Status::success();
    if (t.framebuffer) vkDestroyFramebuffer(device, t.framebuffer, nullptr);
    t.framebuffer = VK_NULL_HANDLE;
    alloc->destroy(t.depth);
    Status s = alloc->createImage(vkDepthFormat(format), e,
                                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                      VK_IMAGE_USAGE_TRANSFER_SRC_BIT,  // read-backs (tests, screenshots)
                                  VK_IMAGE_ASPECT_DEPTH_BIT, t.depth);
    if (s) {
      VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
      fi.renderPass = t.pass;
      fi.attachmentCount = 1;
      fi.pAttachments = &t.depth.view;
      fi.width = e.width;
      fi.height = e.height;
      fi.layers = 1;
      s = vkCheck(vkCreateFramebuffer(device, &fi, nullptr, &t.framebuffer), "vkCreateFramebuffer");
    }
    if (!s) alloc->destroy(t.depth);
    t.depth.layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    return s;
  }

  void recordFrame(VkCommandBuffer cmd, const detail::Frame& frame) {
    VkClearValue clear{};
    clear.depthStencil = {float(frame.clearDepth), 0};
    const VkRect2D area{{0, 0}, {frame.extent.width, frame.extent.height}};
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.renderPass = frameTarget.pass;
    bi.framebuffer = frameTarget.framebuffer;
    bi.renderArea = area;
    bi.clearValueCount = 1;
    bi.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
    // A positive viewport height: row 0 is at ndc y = -1.
    const VkViewport viewport{0, 0, float(frame.extent.width), float(frame.extent.height), 0, 1};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &area);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, frameTarget.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layerLayout, 0, 1, &layerSet, 0, nullptr);
    const VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices.buffer, &zero);
    vkCmdDraw(cmd, vertexCount, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
  }

  void read(int layer, DepthFormat format, Extent e, DepthImage& depth, FloatImage& position, FloatImage& normal) const {
    const std::size_t n = std::size_t(e.width) * e.height;
    const auto* base = static_cast<const unsigned char*>(readback.mapped);
    depth.extent = e;
    depth.format = format;
    depth.texels.assign(n, 0);
    if (format == DepthFormat::D16) {
      std::vector<std::uint16_t> v(n);
      std::memcpy(v.data(), base + depthOffset[layer], n * 2);
      for (std::size_t i = 0; i < n; ++i) depth.texels[i] = v[i];
    } else {
      std::memcpy(depth.texels.data(), base + depthOffset[layer], n * 4);
      if (format == DepthFormat::D24)
        for (auto& t : depth.texels) t &= 0x00FFFFFFu;  // X8: the top byte is undefined
    }
    position = FloatImage(e, 4);
    std::memcpy(position.data.data(), base + positionOffset[layer], n * 16);
    normal = FloatImage(e, 4);
    std::memcpy(normal.data.data(), base + normalOffset[layer], n * 16);
  }
};

Status VkPrepass::create(std::unique_ptr<VkPrepass>& out, const vk::headless::Options& options) {
  out.reset();
  std::unique_ptr<VkPrepass> p(new VkPrepass());
  if (Status s = vk::headless::Context::create(options, p->owned_); !s) return s;
  p->context_ = p->owned_.get();
  if (Status s = p->init(); !s) return s;
  out = std::move(p);
  return Status::success();
}

Status VkPrepass::create(vk::headless::Context& context, std::unique_ptr<VkPrepass>& out) {
  out.reset();
  std::unique_ptr<VkPrepass> p(new VkPrepass());
  p->context_ = &context;
  if (Status s = p->init(); !s) return s;
  out = std::move(p);
  return Status::success();
}

Status VkPrepass::init() {
  state_ = std::make_unique<State>();
  State& st = *state_;
  st.device = context_->device();
  st.physical = context_->physicalDevice();
  st.limits = context_->properties().limits;
  st.alloc = context_;
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(st.physical, kColorFormat, &fp);
  const VkFormatFeatureFlags colorNeed = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
  if ((fp.optimalTilingFeatures & colorNeed) != colorNeed)
    return Status::error(StatusCode::UnsupportedFormat,
                         "prepass: the device cannot render to and copy from VK_FORMAT_R32G32B32A32_SFLOAT");
  if (Status s = st.createShaders(); !s) return s;
  return st.createLayouts();
}

VkPrepass::~VkPrepass() {
  if (state_ && state_->device) {
    vkDeviceWaitIdle(state_->device);
    state_->destroyAll();
  }
  state_.reset();
  owned_.reset();
}

std::string VkPrepass::description() const { return context_ ? context_->description() : std::string("(none)"); }

Status VkPrepass::checkFormat(DepthFormat format, bool secondLayer) const {
  const VkFormat f = vkDepthFormat(format);
  if (f == VK_FORMAT_UNDEFINED)
    return Status::error(StatusCode::UnsupportedFormat,
                         std::string("prepass: ") + sao::toString(format) + " is not a depth-buffer format");
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(state_->physical, f, &fp);
  VkFormatFeatureFlags need = VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
  if (secondLayer) need |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
  if ((fp.optimalTilingFeatures & need) != need) {
    char features[16];
    std::snprintf(features, sizeof features, "0x%X", unsigned(fp.optimalTilingFeatures));
    return Status::error(StatusCode::UnsupportedFormat,
                         std::string("prepass: the device cannot ") +
                             (secondLayer ? "render, sample and copy " : "render and copy ") + vkFormatName(format) +
                             " (its optimal-tiling features are " + features + ")");
  }
  return Status::success();
}

Status VkPrepass::checkExtent(Extent e) const {
  const VkPhysicalDeviceLimits& l = state_->limits;
  const std::uint64_t maxW = std::min({l.maxImageDimension2D, l.maxFramebufferWidth, l.maxViewportDimensions[0]});
  const std::uint64_t maxH = std::min({l.maxImageDimension2D, l.maxFramebufferHeight, l.maxViewportDimensions[1]});
  if (e.width > maxW || e.height > maxH)
    return Status::error(StatusCode::InvalidExtent,
                         "prepass: the image is " + std::to_string(e.width) + "x" + std::to_string(e.height) +
                             " (viewport + 2 x guard band); this device renders at most " + std::to_string(maxW) + "x" +
                             std::to_string(maxH));
  return Status::success();
}

Status VkPrepass::render(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera,
                         const PrepassOptions& options, PrepassResult& out) {
  out = PrepassResult{};
  detail::Frame frame;
  if (Status s = detail::prepareFrame(mesh, view, camera, options, frame); !s) return s;
  if (!frame.zeroToOneClip) return clipError();
  std::uint64_t digest = 0;
  if (Status s = detail::checkMesh(mesh, digest); !s) return s;
  if (Status s = checkFormat(options.format, options.secondLayer); !s) return s;
  if (Status s = checkExtent(frame.extent); !s) return s;
  State& st = *state_;
  const Extent e = frame.extent;
  if (Status s = st.uploadMesh(mesh, digest); !s) return s;
  if (Status s = st.ensurePipelines(options.format, frame.reversedZ); !s) return s;
  if (Status s = st.ensureTargets(e, options.format, options.secondLayer); !s) return s;
  std::memcpy(st.ubo.mapped, &frame.uniforms, sizeof frame.uniforms);
  if (Status s = context_->submit([&](VkCommandBuffer cmd) { st.record(cmd, frame, options.secondLayer); });
      !s)
    return Status::error(s.code, "prepass: " + s.message);
  st.read(0, options.format, e, out.depth, out.position, out.normal);
  if (options.secondLayer) st.read(1, options.format, e, out.depth2, out.position2, out.normal2);
  if (frame.flipY) {
    for (DepthImage* d : {&out.depth, &out.depth2})
      if (!d->texels.empty()) detail::flipRows(d->texels, e);
    for (FloatImage* f : {&out.position, &out.normal, &out.position2, &out.normal2})
      if (!f->data.empty()) detail::flipRows(*f);
  }
  return Status::success();
}

Status VkPrepass::setMesh(const scenes::Mesh& mesh) {
  std::uint64_t digest = 0;
  if (Status s = detail::checkMesh(mesh, digest); !s) return s;
  return state_->uploadMesh(mesh, digest);
}

Status VkPrepass::record(VkCommandBuffer cmd, const glm::dmat4& view, const Camera& camera, DepthFormat format,
                         vk::headless::Image& out) {
  out = vk::headless::Image{};
  State& st = *state_;
  if (!st.haveMesh) return Status::error(StatusCode::InvalidInput, "prepass: record() before setMesh()");
  PrepassOptions options;
  options.format = format;
  detail::Frame frame;
  if (Status s = detail::prepareFrame(view, camera, options, frame); !s) return s;
  if (!frame.zeroToOneClip) return clipError();
  if (frame.flipY)
    return Status::error(StatusCode::InvalidCamera, "prepass: record() draws row 0 at ndc y = -1 (no Camera::flipY)");
  if (Status s = checkFormat(format, /*sampled=*/true); !s) return s;
  if (Status s = checkExtent(frame.extent); !s) return s;
  if (Status s = st.ensureFrameTarget(frame.extent, format, frame.reversedZ); !s) return s;
  std::memcpy(st.ubo.mapped, &frame.uniforms, sizeof frame.uniforms);
  st.recordFrame(cmd, frame);
  out = st.frameTarget.depth;
  return Status::success();
}

}  // namespace sao::prepass
