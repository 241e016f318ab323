#include "vk_composite.h"

#include <cstring>

#include "composite.frag.spv.h"
#include "fullscreen.vert.spv.h"

namespace sao::viewer {
namespace {
constexpr std::uint32_t kTextures = 6;  // bindings 1..6: depth, ao, ao_raw, csz, reference, reduced-resolution AO
}

Status VkComposite::init(vk::headless::Context& context, VkRenderPass renderPass) {
  context_ = &context;
  if (Status s = context.createBuffer(sizeof(CompositeParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, params_); !s)
    return s;
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = VK_LOD_CLAMP_NONE;
  SAO_VIEWER_VK(vkCreateSampler(context.device(), &si, nullptr, &sampler_));
  // 1.0 where an input is missing (no AO, no reference, a plan without the intermediate).
  const FloatImage white({1, 1}, 1, 1.0f);
  if (Status s = context.uploadColor(white, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, white_); !s)
    return s;
  if (Status s = createDescriptors(); !s) return s;
  return createPipeline(renderPass);
}

void VkComposite::destroy() {
  if (!context_) return;
  VkDevice d = context_->device();
  if (pipeline_) vkDestroyPipeline(d, pipeline_, nullptr);
  if (layout_) vkDestroyPipelineLayout(d, layout_, nullptr);
  if (pool_) vkDestroyDescriptorPool(d, pool_, nullptr);
  if (setLayout_) vkDestroyDescriptorSetLayout(d, setLayout_, nullptr);
  if (sampler_) vkDestroySampler(d, sampler_, nullptr);
  context_->destroy(params_);
  context_->destroy(white_);
  context_->destroy(reference_);
  context_ = nullptr;
}

Status VkComposite::createDescriptors() {
  VkDescriptorSetLayoutBinding bindings[1 + kTextures]{};
  bindings[0] = {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  for (std::uint32_t i = 1; i <= kTextures; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = 1 + kTextures;
  li.pBindings = bindings;
  SAO_VIEWER_VK(vkCreateDescriptorSetLayout(context_->device(), &li, nullptr, &setLayout_));
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kTextures}};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = 2;
  pi.pPoolSizes = sizes;
  SAO_VIEWER_VK(vkCreateDescriptorPool(context_->device(), &pi, nullptr, &pool_));
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &setLayout_;
  SAO_VIEWER_VK(vkAllocateDescriptorSets(context_->device(), &ai, &set_));
  VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pl.setLayoutCount = 1;
  pl.pSetLayouts = &setLayout_;
  SAO_VIEWER_VK(vkCreatePipelineLayout(context_->device(), &pl, nullptr, &layout_));
  return Status::success();
}

Status VkComposite::createPipeline(VkRenderPass renderPass) {
  VkDevice d = context_->device();
  VkShaderModule vs = vkx::shaderModule(d, kFullscreenVertSpv, sizeof kFullscreenVertSpv);
  VkShaderModule fs = vkx::shaderModule(d, kCompositeFragSpv, sizeof kCompositeFragSpv);
  VkPipelineShaderStageCreateInfo stages[2]{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vs, "main", nullptr};
  stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fs, "main", nullptr};
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                         VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = 1;
  cb.pAttachments = &blend;
  const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dy.dynamicStateCount = 2;
  dy.pDynamicStates = dynamic;
  VkGraphicsPipelineCreateInfo pi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  pi.stageCount = 2;
  pi.pStages = stages;
  pi.pVertexInputState = &vi;
  pi.pInputAssemblyState = &ia;
  pi.pViewportState = &vp;
  pi.pRasterizationState = &rs;
  pi.pMultisampleState = &ms;
  pi.pColorBlendState = &cb;
  pi.pDynamicState = &dy;
  pi.layout = layout_;
  pi.renderPass = renderPass;
  const VkResult r = vs && fs ? vkCreateGraphicsPipelines(d, VK_NULL_HANDLE, 1, &pi, nullptr, &pipeline_)
                              : VK_ERROR_INITIALIZATION_FAILED;
  if (vs) vkDestroyShaderModule(d, vs, nullptr);
  if (fs) vkDestroyShaderModule(d, fs, nullptr);
  return vkx::check(r, "vkCreateGraphicsPipelines (composite)");
}

Status VkComposite::setReference(const FloatImage* reference) {
  context_->destroy(reference_);
  written_ = false;
  if (!reference) return Status::success();
  return context_->uploadColor(*reference, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, reference_);
}

// Always rewritten (seven writes): a destroyed view and its replacement may share a handle.
void VkComposite::setInputs(const VkCompositeInputs& inputs) {
  inputs_ = inputs;
  writeDescriptors();
}

void VkComposite::writeDescriptors() {
  VkDescriptorBufferInfo buffer{params_.buffer, 0, sizeof(CompositeParams)};
  const VkImageView white = white_.view;
  const VkDescriptorImageInfo images[kTextures] = {
      {sampler_, inputs_.depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL},
      inputs_.ao ? VkDescriptorImageInfo{sampler_, inputs_.ao, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}
                 : VkDescriptorImageInfo{sampler_, white, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      inputs_.aoRaw ? VkDescriptorImageInfo{sampler_, inputs_.aoRaw, VK_IMAGE_LAYOUT_GENERAL}
                    : VkDescriptorImageInfo{sampler_, white, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      inputs_.csz ? VkDescriptorImageInfo{sampler_, inputs_.csz, VK_IMAGE_LAYOUT_GENERAL}
                  : VkDescriptorImageInfo{sampler_, white, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {sampler_, reference_.view ? reference_.view : white, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
      {sampler_, inputs_.aoReduced ? inputs_.aoReduced : white, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
  };
  VkWriteDescriptorSet writes[1 + kTextures]{};
  writes[0] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  writes[0].dstSet = set_;
  writes[0].dstBinding = 0;
  writes[0].descriptorCount = 1;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  writes[0].pBufferInfo = &buffer;
  for (std::uint32_t i = 0; i < kTextures; ++i) {
    writes[1 + i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[1 + i].dstSet = set_;
    writes[1 + i].dstBinding = 1 + i;
    writes[1 + i].descriptorCount = 1;
    writes[1 + i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    writes[1 + i].pImageInfo = &images[i];
  }
  vkUpdateDescriptorSets(context_->device(), 1 + kTextures, writes, 0, nullptr);
  written_ = true;
}

void VkComposite::record(VkCommandBuffer cmd, const CompositeParams& params, VkExtent2D extent) {
  if (!written_) writeDescriptors();
  std::memcpy(params_.mapped, &params, sizeof params);  // the previous frame has completed
  VkViewport viewport{0, 0, float(extent.width), float(extent.height), 0, 1};
  VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdDraw(cmd, 3, 1, 0, 0);
}

}  // namespace sao::viewer
