// Compute pipelines from the embedded SPIR-V (one per pass variant the plan needs, kept across
// update()), their set layouts, and the descriptor sets: one per dispatch, per ring slot.
#include <string>

#include "effect_impl.h"

namespace sao::vk {

Status createSampler(EffectState& e) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_NEAREST;
  info.minFilter = VK_FILTER_NEAREST;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.minLod = 0.0f;
  info.maxLod = VK_LOD_CLAMP_NONE;
  info.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
  if (VkResult r = make(e.owner, e.d.vkCreateSampler, e.d.vkDestroySampler, info, e.sampler); r != VK_SUCCESS)
    return vkError("vkCreateSampler", r);
  return Status::success();
}

const PipelineEntry* findPipeline(const EffectState& e, const gen::PassVariantInfo* variant) {
  for (const auto& p : e.pipelines)
    if (p.variant == variant) return &p;
  return nullptr;
}

namespace {

Status buildPipeline(EffectState& e, const gen::PassInfo& pass, const gen::PassVariantInfo* variant) {
  PipelineEntry entry;
  entry.variant = variant;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  bindings.reserve(variant->bindings.size() + 1);
  const VkSampler sampler = e.sampler.get();
  bindings.push_back({gen::kParamBlockBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  for (const auto& b : variant->bindings)
    bindings.push_back({b.binding, b.write ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                        VK_SHADER_STAGE_COMPUTE_BIT, b.write ? nullptr : &sampler});

  auto fail = [&](const char* what, VkResult r) {
    const std::string where =
        std::string(what) + " for pass '" + std::string(pass.name) + "' (" + std::string(variant->fileStem) + ")";
    return vkError(where.c_str(), r);
  };

  VkDescriptorSetLayoutCreateInfo dl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  dl.bindingCount = static_cast<std::uint32_t>(bindings.size());
  dl.pBindings = bindings.data();
  if (VkResult r =
          make(e.owner, e.d.vkCreateDescriptorSetLayout, e.d.vkDestroyDescriptorSetLayout, dl, entry.setLayout);
      r != VK_SUCCESS)
    return fail("vkCreateDescriptorSetLayout", r);

  const VkDescriptorSetLayout setLayout = entry.setLayout.get();
  VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pl.setLayoutCount = 1;
  pl.pSetLayouts = &setLayout;
  if (VkResult r = make(e.owner, e.d.vkCreatePipelineLayout, e.d.vkDestroyPipelineLayout, pl, entry.layout);
      r != VK_SUCCESS)
    return fail("vkCreatePipelineLayout", r);

  const auto code = gen::spirvModule(variant->spirvBlob);
  VkShaderModuleCreateInfo sm{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  sm.codeSize = code.size_bytes();
  sm.pCode = code.data();
  Handle<VkShaderModule> module;  // only needed until the pipeline exists
  if (VkResult r = make(e.owner, e.d.vkCreateShaderModule, e.d.vkDestroyShaderModule, sm, module); r != VK_SUCCESS)
    return fail("vkCreateShaderModule", r);

  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT,
              module.get(), "main", nullptr};
  ci.layout = entry.layout.get();
  VkPipeline pipeline = VK_NULL_HANDLE;
  const VkResult r =
      e.d.vkCreateComputePipelines(e.ctx.device, e.ctx.pipelineCache, 1, &ci, e.ctx.allocator, &pipeline);
  if (r != VK_SUCCESS) return fail("vkCreateComputePipelines", r);
  entry.pipeline = Handle<VkPipeline>(e.owner, e.d.vkDestroyPipeline, pipeline);
  e.pipelines.push_back(std::move(entry));
  return Status::success();
}

}  // namespace

Status ensurePipelines(EffectState& e, const Plan& plan) {
  for (const auto& p : plan.passes) {
    if (findPipeline(e, p.variant)) continue;
    if (Status st = buildPipeline(e, gen::pass(p.pass), p.variant); !st) return st;
  }
  return Status::success();
}

Status createDescriptors(EffectState& e, const Plan& plan, std::uint32_t slots, Descriptors& out) {
  Descriptors ds;
  std::uint32_t sets = 0, samplers = 0, storage = 0;
  for (const auto& p : plan.passes) {
    sets += p.dispatchCount;
    for (const auto& b : p.variant->bindings) (b.write ? storage : samplers) += p.dispatchCount;
  }
  ds.setsPerSlot = sets;
  std::vector<VkDescriptorPoolSize> sizes;
  sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, sets * slots});
  if (samplers) sizes.push_back({VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, samplers * slots});
  if (storage) sizes.push_back({VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, storage * slots});
  VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  info.maxSets = sets * slots;
  info.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  info.pPoolSizes = sizes.data();
  if (VkResult r = make(e.owner, e.d.vkCreateDescriptorPool, e.d.vkDestroyDescriptorPool, info, ds.pool);
      r != VK_SUCCESS)
    return vkError("vkCreateDescriptorPool", r);

  std::vector<VkDescriptorSetLayout> layouts;
  layouts.reserve(std::size_t(sets) * slots);
  for (std::uint32_t s = 0; s < slots; ++s)
    for (const auto& p : plan.passes)
      for (std::uint32_t k = 0; k < p.dispatchCount; ++k)
        layouts.push_back(findPipeline(e, p.variant)->setLayout.get());
  ds.sets.assign(layouts.size(), VK_NULL_HANDLE);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = ds.pool.get();
  ai.descriptorSetCount = static_cast<std::uint32_t>(layouts.size());
  ai.pSetLayouts = layouts.data();
  if (VkResult r = e.d.vkAllocateDescriptorSets(e.ctx.device, &ai, ds.sets.data()); r != VK_SUCCESS)
    return vkError("vkAllocateDescriptorSets", r);
  out = std::move(ds);
  return Status::success();
}

void writeDescriptors(EffectState& e, std::uint32_t slot, const Inputs& inputs, const OutputTarget& output) {
  std::vector<VkDescriptorImageInfo> images;
  std::vector<VkDescriptorBufferInfo> buffers;
  std::vector<VkWriteDescriptorSet> writes;
  // Reserve so the pointers stored in `writes` stay valid.
  std::size_t bindingCount = 0;
  for (const auto& p : e.plan.passes) bindingCount += p.dispatchCount * p.variant->bindings.size();
  images.reserve(bindingCount);
  buffers.reserve(e.desc.setsPerSlot);
  writes.reserve(bindingCount + e.desc.setsPerSlot);

  std::uint32_t k = slot * e.desc.setsPerSlot;
  for (const auto& p : e.plan.passes) {
    const bool perMip = gen::pass(p.pass).perMip;
    for (std::uint32_t dispatch = 0; dispatch < p.dispatchCount; ++dispatch, ++k) {
      const VkDescriptorSet set = e.desc.sets[k];
      buffers.push_back({e.ubo.buffer.get(), slot * e.ubo.stride, sizeof(ParamBlock)});
      writes.push_back({VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, gen::kParamBlockBinding, 0, 1,
                        VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, nullptr, &buffers.back(), nullptr});
      for (const auto& b : p.variant->bindings) {
        const gen::ResourceId id = e.plan.resolve(p, b.resource);
        VkDescriptorImageInfo info{VK_NULL_HANDLE, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL};
        if (id == gen::ResourceId::depth) info = {VK_NULL_HANDLE, inputs.depth.view, inputs.depth.layout};
        else if (id == gen::ResourceId::depth2) info = {VK_NULL_HANDLE, inputs.depth2.view, inputs.depth2.layout};
        else if (id == gen::ResourceId::normals) info = {VK_NULL_HANDLE, inputs.normals.view, inputs.normals.layout};
        else if (const OwnedImage* img = e.res.find(id)) {
          // per=mip: read level m-1 = dispatch, write level m = dispatch + 1. Otherwise reads see
          // the whole chain and writes go to level 0.
          if (perMip) info.imageView = img->levelViews[b.write ? dispatch + 1 : dispatch].get();
          else info.imageView = b.write ? img->levelViews[0].get() : img->fullView.get();
        } else {
          info.imageView = output.view;  // the user's output
        }
        images.push_back(info);
        writes.push_back({VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, b.binding, 0, 1,
                          b.write ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                          &images.back(), nullptr, nullptr});
      }
    }
  }
  e.d.vkUpdateDescriptorSets(e.ctx.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

}  // namespace sao::vk
