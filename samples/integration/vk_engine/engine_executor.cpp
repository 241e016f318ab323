#include "engine_executor.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include "sao/temporal.h"

namespace sao::vkengine {
namespace {

const char* nameOf(gen::ResourceId id) { return gen::kResources[std::size_t(id)].name.data(); }
// Writes are storage images, reads sampled (texelFetch) through the one immutable sampler.
VkDescriptorType descriptorType(bool write) {
  return write ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
}
// The VkFormat of an effect image: the generated table says which it is (depth is only an input).
VkFormat vkFormat(gen::Format format) {
  const gen::FormatInfo& f = gen::formatInfo(format);
  return f.colour ? static_cast<VkFormat>(f.vkFormat) : VK_FORMAT_UNDEFINED;
}
bool same(const PlannedImage& a, const PlannedImage& b) {
  return a.resource == b.resource && sameImage(a, b) && a.copies == b.copies;
}

}  // namespace

Status EngineExecutor::init() {
  // The one sampler of every read: the shaders only texelFetch, at explicit levels.
  VkSamplerCreateInfo s{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  s.magFilter = s.minFilter = VK_FILTER_NEAREST;
  s.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  s.addressModeU = s.addressModeV = s.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  s.maxLod = VK_LOD_CLAMP_NONE;
  SAO_ENGINE_VK_TRY(vkCreateSampler(device_.device(), &s, nullptr, &sampler_));
  return makeBuffer(device_, sizeof(ParamBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, ubo_);
}

EngineExecutor::~EngineExecutor() {
  const VkDevice d = device_.device();
  for (Owned& o : owned_)  // none after FrameState::release()
    for (Image& i : o.copies) i.destroy(d);
  for (const Pipeline& p : pipelines_) {  // FrameState leaves pipelines to the executor
    vkDestroyPipeline(d, p.pipeline, nullptr);
    vkDestroyPipelineLayout(d, p.layout, nullptr);
    vkDestroyDescriptorSetLayout(d, p.setLayout, nullptr);
  }
  vkDestroyDescriptorPool(d, pool_, nullptr);
  vkDestroySampler(d, sampler_, nullptr);
  ubo_.destroy(d);
}

// The device's limits against a plan, before FrameState creates anything for it (core checks
// each pass's shared memory, push constants and descriptors, and the largest image).
Status EngineExecutor::checkPlan(const Plan& plan) {
  const VkPhysicalDeviceLimits& l = device_.properties().limits;
  DeviceLimits limits;
  limits.imageSide = {l.maxImageDimension2D, "maxImageDimension2D"};
  limits.sharedBytes = {l.maxComputeSharedMemorySize, "maxComputeSharedMemorySize"};
  limits.pushConstantBytes = {l.maxPushConstantsSize, "maxPushConstantsSize"};
  limits.storageImagesPerPass = {l.maxPerStageDescriptorStorageImages, "maxPerStageDescriptorStorageImages"};
  limits.sampledImagesPerPass = {l.maxPerStageDescriptorSampledImages, "maxPerStageDescriptorSampledImages"};
  return checkDeviceLimits(plan, limits);
}

// The schedule's work groups against the device (FrameState hands over the schedule it made; a
// refusal here destroys the plan's new images and keeps the current configuration).
Status EngineExecutor::preparePlan(const Plan&, const Schedule& schedule) {
  const VkPhysicalDeviceLimits& l = device_.properties().limits;
  for (const ScheduledDispatch& d : schedule.dispatches)
    if (d.groupsX > l.maxComputeWorkGroupCount[0] || d.groupsY > l.maxComputeWorkGroupCount[1])
      return Status::error(StatusCode::InvalidExtent, "pass '" + std::string(gen::pass(d.pass).name) +
                                                          "' needs more work groups than the device dispatches");
  return Status::success();
}

Status EngineExecutor::createImage(const PlannedImage& image) {
  const VkFormat format = vkFormat(image.format);
  if (!device_.hasFeatures(format, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT))
    return Status::error(StatusCode::UnsupportedFormat, "the device cannot store and sample VkFormat " +
                                                            std::to_string(format) + " of " + nameOf(image.resource));
  Owned& made = owned_.emplace_back(Owned{image, std::vector<Image>(image.copies)});  // a history has two
  // TRANSFER_SRC: the engine reads intermediates back (engine_transfer.h).
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  for (Image& copy : made.copies) {
    const Status st = makeImage(device_, format, VK_IMAGE_ASPECT_COLOR_BIT, image.extent, image.mipLevels, usage, copy);
    if (!st) {
      destroyImage(image);
      return Status::error(st.code, std::string(nameOf(image.resource)) + ": " + st.message);
    }
    ++imagesMade_;
  }
  outputsMade_ += gen::kResources[std::size_t(image.resource)].kind == gen::ResourceKind::Output;
  return Status::success();
}

// Named by the PlannedImage it was made for: while a new plan replaces an image, the old and the
// new one of a resource both exist. Every frame waited for its fence; an engine with frames in
// flight would wait for theirs here.
void EngineExecutor::destroyImage(const PlannedImage& image) noexcept {
  const auto o = std::find_if(owned_.begin(), owned_.end(), [&](const Owned& x) { return same(x.planned, image); });
  if (o == owned_.end()) return;
  for (Image& copy : o->copies) copy.destroy(device_.device());
  owned_.erase(o);
}

const Image* EngineExecutor::image(const PlannedImage& planned, std::uint32_t copy) const {
  const auto o = std::find_if(owned_.begin(), owned_.end(), [&](const Owned& x) { return same(x.planned, planned); });
  return o != owned_.end() && copy < o->copies.size() ? &o->copies[copy] : nullptr;
}

Status EngineExecutor::createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) {
  // (Its shared memory against the device's limit: checkPlan.)
  const std::string where = "pass '" + std::string(pass.name) + "' (" + std::string(variant.fileStem) + ")";
  // The shader from its installed file, not from the library's embedded copy.
  const std::string path = shaderDir_ + "/" + std::string(variant.fileStem) + ".spv";
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = file ? std::streamoff(file.tellg()) : -1;
  std::vector<std::uint32_t> code(size > 0 ? std::size_t(size) / 4 : 0);
  if (size < 20 || size % 4 || !file.seekg(0).read(reinterpret_cast<char*>(code.data()), size) ||
      code[0] != 0x07230203u)
    return Status::error(StatusCode::IoError, "cannot read the SPIR-V module " + path + " of " + where);

  const VkDevice d = device_.device();
  Pipeline& p = pipelines_.emplace_back(Pipeline{&variant});  // the destructor frees what gets made
  std::vector<VkDescriptorSetLayoutBinding> bindings{
      {gen::kParamBlockBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  for (const gen::BindingInfo& b : variant.bindings)  // a read has one element: only writes are arrays
    bindings.push_back({b.binding, descriptorType(b.write), b.slots, VK_SHADER_STAGE_COMPUTE_BIT,
                        b.write ? nullptr : &sampler_});
  const VkDescriptorSetLayoutCreateInfo dl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr, 0,
                                           std::uint32_t(bindings.size()), bindings.data()};
  SAO_ENGINE_VK_TRY(vkCreateDescriptorSetLayout(d, &dl, nullptr, &p.setLayout));
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, variant.pushConstantBytes};
  const VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 1, &p.setLayout,
                                      variant.pushConstantBytes ? 1u : 0u, &push};
  SAO_ENGINE_VK_TRY(vkCreatePipelineLayout(d, &pl, nullptr, &p.layout));
  const VkShaderModuleCreateInfo sm{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, std::size_t(size),
                                    code.data()};
  VkShaderModule module;
  SAO_ENGINE_VK_TRY(vkCreateShaderModule(d, &sm, nullptr, &module));
  const VkComputePipelineCreateInfo ci{
      VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO, nullptr, 0,
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main"},
      p.layout};
  const VkResult r = vkCreateComputePipelines(d, VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline);
  vkDestroyShaderModule(d, module, nullptr);
  return r == VK_SUCCESS ? Status::success() : vkFail("vkCreateComputePipelines for " + where, r);
}

// One descriptor set per dispatch, from a pool reset every frame and grown for a larger schedule.
Status EngineExecutor::ensurePool(const Schedule& schedule) {
  const VkDevice d = device_.device();
  std::array<std::uint32_t, 3> need{std::uint32_t(schedule.dispatches.size()), 0, 0};
  for (const ScheduledDispatch& s : schedule.dispatches)
    for (const gen::BindingInfo& b : s.variant->bindings) need[b.write ? 2 : 1] += b.slots;
  if (pool_ && need[0] <= poolSize_[0] && need[1] <= poolSize_[1] && need[2] <= poolSize_[2]) {
    SAO_ENGINE_VK_TRY(vkResetDescriptorPool(d, pool_, 0));  // the frame before has completed
    return Status::success();
  }
  vkDestroyDescriptorPool(d, pool_, nullptr);
  pool_ = VK_NULL_HANDLE;
  for (std::uint32_t& n : need) n = std::max(n, 1u);
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, need[0]},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, need[1]},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, need[2]}};
  const VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, need[0], 3, sizes};
  SAO_ENGINE_VK_TRY(vkCreateDescriptorPool(d, &info, nullptr, &pool_));
  poolSize_ = need;
  return Status::success();
}

// The image a binding or hazard names this frame: the engine's for an input or the output, else
// the effect's own copy (imageCopy: a history's previous or current one).
Target EngineExecutor::target(gen::ResourceId id, bool previousFrame) const {
  if (const Image* copy = ownedCopy(id, previousFrame)) return {copy->image, copy->whole};
  return engine_[std::size_t(id)];
}

// This frame's copy of an effect image (current_: the plan's images, found in beginFrame), or null.
const Image* EngineExecutor::ownedCopy(gen::ResourceId id, bool previousFrame) const {
  const Owned* o = current_[std::size_t(id)];
  return o ? &o->copies[imageCopy(frame_.historyParity, id, previousFrame)] : nullptr;
}

Status EngineExecutor::beginFrame(const FrameWork& frame) {
  frame_ = frame;
  error_ = Status::success();
  std::memcpy(ubo_.mapped, frame.block, sizeof(ParamBlock));  // coherent: the submit makes it visible
  current_ = {};
  for (const PlannedImage& planned : frame.plan->images) {
    const auto o = std::find_if(owned_.begin(), owned_.end(), [&](const Owned& x) { return same(x.planned, planned); });
    if (o == owned_.end())
      return Status::error(StatusCode::InvalidInput, std::string("no image made for ") + nameOf(planned.resource));
    current_[std::size_t(planned.resource)] = &*o;
  }
  if (Status st = ensurePool(*frame.schedule); !st) return st;
  cmd_ = device_.begin();
  // The frame rewrites every effect image, so their contents are discarded (UNDEFINED -> GENERAL)
  // after the previous frame's accesses; but the previous frame's history copy, which this frame
  // reads, is kept when it holds a frame.
  std::vector<VkImageMemoryBarrier> barriers;
  for (const PlannedImage& planned : frame.plan->images) {
    const std::vector<Image>& copies = current_[std::size_t(planned.resource)]->copies;
    for (std::uint32_t c = 0; c < planned.copies; ++c) {
      const bool keep = frame.historyValid && gen::kResources[std::size_t(planned.resource)].history &&
                        c == imageCopy(frame.historyParity, planned.resource, true);
      barriers.push_back(imageBarrier(copies[c].image, VK_IMAGE_ASPECT_COLOR_BIT,
                                      keep ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED,
                                      VK_IMAGE_LAYOUT_GENERAL, VK_ACCESS_SHADER_WRITE_BIT,
                                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT));
    }
  }
  cmdBarriers(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, barriers);
  return Status::success();
}

void EngineExecutor::barrier(std::span<const Hazard> hazards) {
  constexpr VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  constexpr VkPipelineStageFlags transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkPipelineStageFlags srcStages = 0, dstStages = 0;
  std::vector<VkImageMemoryBarrier> barriers;
  for (const Hazard& h : hazards) {
    const Target t = target(h.resource, h.previousFrame);
    if (!t.image) {
      error_ = Status::error(StatusCode::InvalidInput,
                             std::string("a hazard names ") + nameOf(h.resource) + ", which the engine lacks");
      continue;
    }
    // {src stage, src access, dst stage, dst access}: the effect reads by sampling and writes by
    // storing in compute shaders; this engine writes its inputs and reads the output by transfers.
    struct Rule {
      VkPipelineStageFlags srcStage, src, dstStage, dst;
    };
    static constexpr Rule kRules[] = {
        {compute, VK_ACCESS_SHADER_WRITE_BIT, compute, VK_ACCESS_SHADER_READ_BIT},      // ReadAfterWrite
        {compute, VK_ACCESS_SHADER_READ_BIT, compute, VK_ACCESS_SHADER_WRITE_BIT},      // WriteAfterRead
        {compute, VK_ACCESS_SHADER_WRITE_BIT, compute, VK_ACCESS_SHADER_WRITE_BIT},     // WriteAfterWrite
        {transfer, VK_ACCESS_TRANSFER_WRITE_BIT, compute, VK_ACCESS_SHADER_READ_BIT},   // CallerWrote
        {compute, VK_ACCESS_SHADER_WRITE_BIT, transfer, VK_ACCESS_TRANSFER_READ_BIT}};  // CallerReads
    const Rule& rule = kRules[std::size_t(h.kind)];
    srcStages |= rule.srcStage;
    // The output's hazard at frame entry follows the engine's readback of the frame before (a
    // transfer), not only the effect's own accesses: the executor cannot tell which, so both.
    if (gen::kResources[std::size_t(h.resource)].kind == gen::ResourceKind::Output) srcStages |= transfer;
    dstStages |= rule.dstStage;
    barriers.push_back(imageBarrier(t.image, t.aspects, t.layout, t.layout, rule.src, rule.dst, h.baseLevel,
                                    h.levelCount));
  }
  cmdBarriers(cmd_, srcStages, dstStages, barriers);
}

void EngineExecutor::dispatch(const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  const auto p = std::find_if(pipelines_.begin(), pipelines_.end(), [&](auto& q) { return q.variant == d.variant; });
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (p != pipelines_.end()) {
    const VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, pool_, 1,
                                         &p->setLayout};
    if (VkResult r = vkAllocateDescriptorSets(device_.device(), &ai, &set); r != VK_SUCCESS) set = VK_NULL_HANDLE;
  }
  if (!set) {
    error_ = Status::error(StatusCode::DriverError,
                           std::string("no pipeline or descriptor set for pass ") + gen::pass(d.pass).name.data());
    return;
  }
  // The block, then each binding: the schedule's bindings are the variant's, in order. Element
  // `slot` of a levels= write's array is level slotLevel(slot); a read sees one level or the chain.
  const VkDescriptorBufferInfo block{ubo_.buffer, 0, sizeof(ParamBlock)};
  std::vector<VkDescriptorImageInfo> images;
  for (std::size_t i = 0; i < bindings.size(); ++i) {
    const ScheduledBinding& b = bindings[i];
    const Target t = target(b.resource, b.previousFrame);
    if (!t.image) {
      error_ = Status::error(StatusCode::InvalidInput, std::string("pass ") + gen::pass(d.pass).name.data() +
                                                           " binds " + nameOf(b.resource) + ", which the engine lacks");
      return;
    }
    const Image* own = ownedCopy(b.resource, b.previousFrame);
    for (std::uint32_t slot = 0; slot < d.variant->bindings[i].slots; ++slot)
      images.push_back({VK_NULL_HANDLE, !own || b.wholeChain ? t.view : own->levels[b.slotLevel(slot)], t.layout});
  }
  std::vector<VkWriteDescriptorSet> writes{{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set,
                                            gen::kParamBlockBinding, 0, 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, nullptr,
                                            &block}};
  const VkDescriptorImageInfo* next = images.data();
  for (std::size_t i = 0; i < bindings.size(); ++i) {
    const std::uint32_t slots = d.variant->bindings[i].slots;
    writes.push_back({VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set, bindings[i].binding, 0, slots,
                      descriptorType(bindings[i].write), next});
    next += slots;
  }
  vkUpdateDescriptorSets(device_.device(), std::uint32_t(writes.size()), writes.data(), 0, nullptr);
  vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
  vkCmdBindDescriptorSets(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &set, 0, nullptr);
  if (d.variant->pushConstantBytes) {
    const gen::PushConstants constants = gen::pushConstantsOf(*frame_.block);
    vkCmdPushConstants(cmd_, p->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, d.variant->pushConstantBytes, &constants);
  }
  vkCmdDispatch(cmd_, d.groupsX, d.groupsY, 1);
}

Status EngineExecutor::endFrame() {
  const Status submitted = device_.submitAndWait();
  return error_.ok() ? submitted : error_;
}

}  // namespace sao::vkengine
