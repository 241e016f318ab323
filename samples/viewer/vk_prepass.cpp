#include "vk_prepass.h"

#include <cstring>

#include "prepass.vert.spv.h"

namespace sao::viewer {

Status VkPrepass::init(VkContext& context) {
  context_ = &context;
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(context.physical, kDepthFormat, &fp);
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
  if ((fp.optimalTilingFeatures & need) != need)
    return Status::error(StatusCode::UnsupportedFormat, "the device cannot render and sample VK_FORMAT_D32_SFLOAT");
  if (Status s = createRenderPass(); !s) return s;
  return createPipeline();
}

void VkPrepass::destroy() {
  if (!context_) return;
  VkDevice d = context_->device;
  if (framebuffer_) vkDestroyFramebuffer(d, framebuffer_, nullptr);
  if (pipeline_) vkDestroyPipeline(d, pipeline_, nullptr);
  if (layout_) vkDestroyPipelineLayout(d, layout_, nullptr);
  if (renderPass_) vkDestroyRenderPass(d, renderPass_, nullptr);
  context_->destroy(depth_);
  context_->destroy(vertices_);
  context_->destroy(indices_);
  framebuffer_ = VK_NULL_HANDLE;
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  renderPass_ = VK_NULL_HANDLE;
}

Status VkPrepass::createRenderPass() {
  VkAttachmentDescription depth{};
  depth.format = kDepthFormat;
  depth.samples = VK_SAMPLE_COUNT_1_BIT;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  depth.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.pDepthStencilAttachment = &ref;
  VkSubpassDependency deps[2]{};
  // The previous frame's effect and composite read the depth: wait for them before clearing.
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[0].dstAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  // The effect (compute) and the composite (fragment) read it afterwards.
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[1].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  ci.attachmentCount = 1;
  ci.pAttachments = &depth;
  ci.subpassCount = 1;
  ci.pSubpasses = &subpass;
  ci.dependencyCount = 2;
  ci.pDependencies = deps;
  SAO_VIEWER_VK(vkCreateRenderPass(context_->device, &ci, nullptr, &renderPass_));
  return Status::success();
}

Status VkPrepass::createPipeline() {
  VkDevice d = context_->device;
  VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(float) * 16};
  VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  li.pushConstantRangeCount = 1;
  li.pPushConstantRanges = &push;
  SAO_VIEWER_VK(vkCreatePipelineLayout(d, &li, nullptr, &layout_));
  VkShaderModule vs = vkx::shaderModule(d, kPrepassVertSpv, sizeof kPrepassVertSpv);
  if (!vs) return Status::error(StatusCode::DriverError, "cannot create the prepass shader module");
  VkPipelineShaderStageCreateInfo stage{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stage.stage = VK_SHADER_STAGE_VERTEX_BIT;
  stage.module = vs;
  stage.pName = "main";
  VkVertexInputBindingDescription binding{0, sizeof(glm::vec3), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attribute{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0};
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = 1;
  vi.pVertexBindingDescriptions = &binding;
  vi.vertexAttributeDescriptionCount = 1;
  vi.pVertexAttributeDescriptions = &attribute;
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
  ds.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed-Z
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = 2;
  dy.pDynamicStates = dynamic;
  VkGraphicsPipelineCreateInfo pi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  pi.stageCount = 1;
  pi.pStages = &stage;
  pi.pVertexInputState = &vi;
  pi.pInputAssemblyState = &ia;
  pi.pViewportState = &vp;
  pi.pRasterizationState = &rs;
  pi.pMultisampleState = &ms;
  pi.pDepthStencilState = &ds;
  pi.pColorBlendState = &cb;
  pi.pDynamicState = &dy;
  pi.layout = layout_;
  pi.renderPass = renderPass_;
  const VkResult r = vkCreateGraphicsPipelines(d, VK_NULL_HANDLE, 1, &pi, nullptr, &pipeline_);
  vkDestroyShaderModule(d, vs, nullptr);
  return vkx::check(r, "vkCreateGraphicsPipelines (prepass)");
}

Status VkPrepass::setMesh(const scenes::Mesh& mesh) {
  context_->destroy(vertices_);
  context_->destroy(indices_);
  const VkDeviceSize vbytes = mesh.positions.size() * sizeof(glm::vec3);
  const VkDeviceSize ibytes = mesh.indices.size() * sizeof(std::uint32_t);
  if (Status s = context_->createBuffer(vbytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vertices_); !s) return s;
  if (Status s = context_->createBuffer(ibytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, indices_); !s) return s;
  std::memcpy(vertices_.mapped, mesh.positions.data(), vbytes);
  std::memcpy(indices_.mapped, mesh.indices.data(), ibytes);
  indexCount_ = std::uint32_t(mesh.indices.size());
  return Status::success();
}

Status VkPrepass::resize(VkExtent2D extent) {
  if (depth_.image && depth_.extent.width == extent.width && depth_.extent.height == extent.height)
    return Status::success();
  if (framebuffer_) vkDestroyFramebuffer(context_->device, framebuffer_, nullptr);
  framebuffer_ = VK_NULL_HANDLE;
  context_->destroy(depth_);
  if (Status s = context_->createImage(kDepthFormat, extent,
                                       VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                       VK_IMAGE_ASPECT_DEPTH_BIT, depth_);
      !s)
    return s;
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fi.renderPass = renderPass_;
  fi.attachmentCount = 1;
  fi.pAttachments = &depth_.view;
  fi.width = extent.width;
  fi.height = extent.height;
  fi.layers = 1;
  SAO_VIEWER_VK(vkCreateFramebuffer(context_->device, &fi, nullptr, &framebuffer_));
  return Status::success();
}

void VkPrepass::record(VkCommandBuffer cmd, const glm::dmat4& mvp) {
  VkClearValue clear{};
  clear.depthStencil = {0.0f, 0};  // reversed-Z: the far plane
  VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  bi.renderPass = renderPass_;
  bi.framebuffer = framebuffer_;
  bi.renderArea = {{0, 0}, depth_.extent};
  bi.clearValueCount = 1;
  bi.pClearValues = &clear;
  vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
  // A positive viewport: row 0 of the depth image is ndc y = -1 (Camera::flipY stays false).
  VkViewport viewport{0, 0, float(depth_.extent.width), float(depth_.extent.height), 0, 1};
  VkRect2D scissor{{0, 0}, depth_.extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  if (indexCount_ > 0) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    const glm::mat4 m(mvp);
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof m, &m);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertices_.buffer, &offset);
    vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, indexCount_, 1, 0, 0, 0);
  }
  vkCmdEndRenderPass(cmd);
}

}  // namespace sao::viewer
