// Compute pipelines from the embedded SPIR-V (one per pass variant FrameState asks for, kept across
// plans), their set layouts, and the descriptor sets: one per dispatch, per ring slot.
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
  // An immutable sampler per element of a sampled binding (one element each: only writes are arrays).
  for (const auto& b : variant->bindings)
    bindings.push_back({b.binding, b.write ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                        b.slots, VK_SHADER_STAGE_COMPUTE_BIT, b.write ? nullptr : &sampler});

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
  // The generated push constants, for the variants whose SPIR-V declares them.
  const VkPushConstantRange pushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, variant->pushConstantBytes};
  pl.pushConstantRangeCount = variant->pushConstantBytes > 0 ? 1 : 0;
  pl.pPushConstantRanges = &pushRange;
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

Status ensurePipeline(EffectState& e, const gen::PassInfo& pass, const gen::PassVariantInfo& variant) {
  if (findPipeline(e, &variant)) return Status::success();  // a cache: FrameState may ask again
  return buildPipeline(e, pass, &variant);
}

Status createDescriptors(EffectState& e, const Schedule& schedule, std::uint32_t slots, Descriptors& out) {
  Descriptors ds;
  const auto sets = static_cast<std::uint32_t>(schedule.dispatches.size());
  std::uint32_t samplers = 0, storage = 0, elements = 0;
  for (const ScheduledDispatch& d : schedule.dispatches)
    for (const gen::BindingInfo& b : d.variant->bindings) (b.write ? storage : samplers) += b.slots, elements += b.slots;
  ds.setsPerSlot = sets;
  ds.slots = slots;
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
    for (const ScheduledDispatch& d : schedule.dispatches) layouts.push_back(findPipeline(e, d.variant)->setLayout.get());
  ds.sets.assign(layouts.size(), VK_NULL_HANDLE);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = ds.pool.get();
  ai.descriptorSetCount = static_cast<std::uint32_t>(layouts.size());
  ai.pSetLayouts = layouts.data();
  if (VkResult r = e.d.vkAllocateDescriptorSets(e.ctx.device, &ai, ds.sets.data()); r != VK_SUCCESS)
    return vkError("vkAllocateDescriptorSets", r);
  ds.writes.resize(sets + schedule.bindings.size());
  ds.images.resize(elements);
  ds.buffers.resize(sets);
  out = std::move(ds);
  return Status::success();
}

namespace {

// The view and layout that serve a resolved binding.
// `slot`: the element of a levels= write's array, level baseLevel + slot (the last level past the chain).
VkDescriptorImageInfo imageInfo(const EffectState& e, std::uint32_t historyParity, const ScheduledBinding& b,
                                const Inputs& inputs, const OutputTarget& output, std::uint32_t slot) {
  if (gen::kResources[static_cast<std::size_t>(b.resource)].kind == gen::ResourceKind::Input)
    return {VK_NULL_HANDLE, inputs[b.resource].view, inputs[b.resource].layout};
  VkDescriptorImageInfo info{VK_NULL_HANDLE, output.view, VK_IMAGE_LAYOUT_GENERAL};  // the user's output
  if (const OwnedImage* img = e.res.find(b.resource, imageCopy(historyParity, b.resource, b.previousFrame)))
    info.imageView = b.wholeChain ? img->fullView.get() : img->levelViews[b.slotLevel(slot)].get();
  return info;
}

}  // namespace

void writeDescriptors(EffectState& e, std::uint32_t slot, std::uint32_t historyParity, const Inputs& inputs,
                      const OutputTarget& output) {
  Descriptors& ds = e.desc;
  const Schedule& schedule = e.schedule();
  std::size_t w = 0, image = 0;
  for (std::uint32_t k = 0; k < schedule.dispatches.size(); ++k) {
    const ScheduledDispatch& d = schedule.dispatches[k];
    const VkDescriptorSet set = ds.sets[slot * ds.setsPerSlot + k];
    ds.buffers[k] = {e.ubo.buffer.get(), slot * e.ubo.stride, sizeof(ParamBlock)};
    ds.writes[w++] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, gen::kParamBlockBinding, 0, 1,
                      VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, nullptr, &ds.buffers[k], nullptr};
    const std::span<const ScheduledBinding> bindings = schedule.bindingsOf(d);  // one to one with the variant's
    for (std::size_t i = 0; i < bindings.size(); ++i) {
      const ScheduledBinding& b = bindings[i];
      const std::uint32_t slots = d.variant->bindings[i].slots;
      for (std::uint32_t j = 0; j < slots; ++j) ds.images[image + j] = imageInfo(e, historyParity, b, inputs, output, j);
      ds.writes[w++] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, b.binding, 0, slots,
                        b.write ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                        &ds.images[image], nullptr, nullptr};
      image += slots;
    }
  }
  e.d.vkUpdateDescriptorSets(e.ctx.device, static_cast<std::uint32_t>(w), ds.writes.data(), 0, nullptr);
}

}  // namespace sao::vk
