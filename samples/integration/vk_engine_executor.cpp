// An engine with its own Vulkan renderer runs the effect from sao::core alone: it implements
// sao::Executor (images, pipelines from the installed .spv files, barriers, dispatches) and lets
// sao::FrameState decide the plan, the schedule, the parameter block and the history. Each depth
// file runs a few frames under the Khronos validation layer with synchronization validation, and
// its output is compared with the CPU reference. Only the installed sao::core, sao::io and
// sao::cpu and the system's Vulkan loader are used (no sao::vulkan), so it builds against a package.
//
//   sao-example-vulkan-engine --shaders DIR [--frames N] [--set NAME=VALUE]... DEPTH.exr [...]
#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/cpu/reference.h"
#include "sao/executor.h"
#include "sao/image.h"
#include "sao/io.h"
#include "sao/plan.h"
#include "sao/schedule.h"
#include "sao/settings.h"
#include "sao_effect.h"

namespace {

namespace gen = sao::gen;
using sao::Status;
using sao::StatusCode;

Status vkFail(const std::string& what, VkResult r) {
  return Status::error(StatusCode::DriverError, what + " failed: VkResult " + std::to_string(int(r)));
}
#define VK_TRY(call)                                                      \
  do {                                                                    \
    if (VkResult r_ = (call); r_ != VK_SUCCESS) return vkFail(#call, r_); \
  } while (false)

// Runs `f` at scope exit: the engine's clean-up on every path.
struct Defer {
  std::function<void()> f;
  ~Defer() { f(); }
};

const char* nameOf(gen::ResourceId id) { return gen::kResources[std::size_t(id)].name.data(); }
bool isOutput(gen::ResourceId id) { return gen::kResources[std::size_t(id)].kind == gen::ResourceKind::Output; }
// Writes are storage images, reads sampled (texelFetch) through the one immutable sampler.
VkDescriptorType descriptorType(bool write) {
  return write ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
}

// ---- The engine's device: validation, one compute queue, one command buffer for every submit.

int gValidationMessages = 0;

// Subscribed to warnings and errors only (not the layer's createinstance-status-message, an
// info): each one is a finding.
VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                         VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  ++gValidationMessages;
  const bool error = severity == VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  std::fprintf(stderr, "[validation %s] %s\n", error ? "error" : "warning", data->pMessage);
  return VK_FALSE;
}

struct Gpu {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties props{};
  VkPhysicalDeviceMemoryProperties memory{};
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;  // begun again for every submit
  VkFence fence = VK_NULL_HANDLE;

  Status create(bool validation);
  ~Gpu() {
    if (device) {
      vkDeviceWaitIdle(device);
      vkDestroyFence(device, fence, nullptr);
      vkDestroyCommandPool(device, pool, nullptr);
      vkDestroyDevice(device, nullptr);  // the layer reports every object left here
    }
    if (messenger)
      reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"))(instance, messenger, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
  }
  Status allocate(VkMemoryRequirements needs, VkMemoryPropertyFlags want, VkDeviceMemory& out) const {
    std::uint32_t type = 0;
    while (type < memory.memoryTypeCount && !((needs.memoryTypeBits >> type & 1) &&
                                              (memory.memoryTypes[type].propertyFlags & want) == want))
      ++type;
    if (type == memory.memoryTypeCount)
      return Status::error(StatusCode::DriverError, "no memory type with flags " + std::to_string(want));
    const VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, needs.size, type};
    VK_TRY(vkAllocateMemory(device, &info, nullptr, &out));
    return Status::success();
  }
  VkCommandBuffer begin() const {
    const VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                        VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    vkBeginCommandBuffer(cmd, &info);  // resets it (RESET_COMMAND_BUFFER pool)
    return cmd;
  }
  Status submitAndWait() const {
    VK_TRY(vkEndCommandBuffer(cmd));
    const VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO, nullptr, 0, nullptr, nullptr, 1, &cmd};
    VK_TRY(vkQueueSubmit(queue, 1, &submit, fence));
    VK_TRY(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
    VK_TRY(vkResetFences(device, 1, &fence));
    return Status::success();
  }
};

Status Gpu::create(bool validation) {
  std::uint32_t loader = VK_API_VERSION_1_0;
  vkEnumerateInstanceVersion(&loader);
  if (loader < VK_API_VERSION_1_1) return Status::error(StatusCode::DriverError, "the Vulkan loader offers only 1.0");
  const VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO, nullptr, "sao-example-vulkan-engine", 1, nullptr, 0,
                              VK_API_VERSION_1_1};
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME};
  const VkValidationFeatureEnableEXT syncval = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  // No shader-validation cache file in the home directory, shared by every process that validates.
  const VkValidationFeatureDisableEXT noCache = VK_VALIDATION_FEATURE_DISABLE_SHADER_VALIDATION_CACHE_EXT;
  const VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT, nullptr, 1, &syncval, 1, &noCache};
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT, &features};
  messengerInfo.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messengerInfo.pfnUserCallback = &onMessage;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, nullptr, 0, &app};
  if (validation) {
    std::uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    if (std::none_of(layers.begin(), layers.end(), [&](auto& l) { return std::strcmp(l.layerName, layer) == 0; }))
      return Status::error(StatusCode::DriverError, "VK_LAYER_KHRONOS_validation is not installed (Debian: "
                                                    "vulkan-validationlayers); --no-validation runs without it");
    info = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, &messengerInfo, 0, &app, 1, &layer, 2, extensions};
  }
  VK_TRY(vkCreateInstance(&info, nullptr, &instance));  // the chained messenger also sees its messages
  if (validation) {
    messengerInfo.pNext = nullptr;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    VK_TRY(create(instance, &messengerInfo, nullptr, &messenger));
  }

  // The first device of Vulkan 1.1+ with a compute queue and r16f / rg16f storage images.
  std::uint32_t n = 0;
  VK_TRY(vkEnumeratePhysicalDevices(instance, &n, nullptr));
  std::vector<VkPhysicalDevice> devices(n);
  VK_TRY(vkEnumeratePhysicalDevices(instance, &n, devices.data()));
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceFeatures f;
    vkGetPhysicalDeviceFeatures(d, &f);
    vkGetPhysicalDeviceProperties(d, &props);
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &count, families.data());
    for (family = 0; family < count && !(families[family].queueFlags & VK_QUEUE_COMPUTE_BIT);) ++family;
    if (props.apiVersion >= VK_API_VERSION_1_1 && f.shaderStorageImageExtendedFormats && family < count) {
      physical = d;
      break;
    }
  }
  if (!physical)
    return Status::error(StatusCode::DriverError, std::to_string(n) + " Vulkan device(s), none with Vulkan 1.1, a "
                                                  "compute queue and shaderStorageImageExtendedFormats");
  vkGetPhysicalDeviceMemoryProperties(physical, &memory);
  const float priority = 1.0f;
  const VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, nullptr, 0, family, 1, &priority};
  VkPhysicalDeviceFeatures enabled{};
  enabled.shaderStorageImageExtendedFormats = VK_TRUE;
  const VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, nullptr, 0, 1, &queueInfo,
                                      0, nullptr, 0, nullptr, &enabled};
  VK_TRY(vkCreateDevice(physical, &deviceInfo, nullptr, &device));
  vkGetDeviceQueue(device, family, 0, &queue);
  const VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                         VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, family};
  VK_TRY(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
  const VkCommandBufferAllocateInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                            VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  VK_TRY(vkAllocateCommandBuffers(device, &cmdInfo, &cmd));
  const VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_TRY(vkCreateFence(device, &fenceInfo, nullptr, &fence));
  return Status::success();
}

// ---- Images and buffers, the engine's and the effect's alike.

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView whole = VK_NULL_HANDLE;  // every level: a read of the whole chain
  std::vector<VkImageView> levels;     // one per level: a write, or a read of one level
  void destroy(VkDevice device) {
    for (VkImageView v : levels) vkDestroyImageView(device, v, nullptr);
    vkDestroyImageView(device, whole, nullptr);
    vkDestroyImage(device, image, nullptr);
    vkFreeMemory(device, memory, nullptr);
    *this = {};
  }
};

Status makeImage(const Gpu& gpu, VkFormat format, VkImageAspectFlags aspect, sao::Extent extent, std::uint32_t levels,
                 VkImageUsageFlags usage, Image& out) {
  const VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, nullptr, 0, VK_IMAGE_TYPE_2D, format,
                               {extent.width, extent.height, 1}, levels, 1, VK_SAMPLE_COUNT_1_BIT,
                               VK_IMAGE_TILING_OPTIMAL, usage};
  VK_TRY(vkCreateImage(gpu.device, &info, nullptr, &out.image));
  VkMemoryRequirements needs;
  vkGetImageMemoryRequirements(gpu.device, out.image, &needs);
  if (Status st = gpu.allocate(needs, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, out.memory); !st) return st;
  VK_TRY(vkBindImageMemory(gpu.device, out.image, out.memory, 0));
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, out.image, VK_IMAGE_VIEW_TYPE_2D,
                             format, {}, {aspect, 0, levels, 0, 1}};
  VK_TRY(vkCreateImageView(gpu.device, &view, nullptr, &out.whole));
  out.levels.assign(levels, VK_NULL_HANDLE);
  for (std::uint32_t m = 0; m < levels; ++m) {
    view.subresourceRange = {aspect, m, 1, 0, 1};
    VK_TRY(vkCreateImageView(gpu.device, &view, nullptr, &out.levels[m]));
  }
  return Status::success();
}

// Host-visible, coherent and mapped: the upload, the parameter block, the readback.
struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  void destroy(VkDevice device) {
    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, memory, nullptr);
    *this = {};
  }
};

Status makeBuffer(const Gpu& gpu, VkDeviceSize size, VkBufferUsageFlags usage, Buffer& out) {
  const VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, size, usage};
  VK_TRY(vkCreateBuffer(gpu.device, &info, nullptr, &out.buffer));
  VkMemoryRequirements needs;
  vkGetBufferMemoryRequirements(gpu.device, out.buffer, &needs);
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if (Status st = gpu.allocate(needs, host, out.memory); !st) return st;
  VK_TRY(vkBindBufferMemory(gpu.device, out.buffer, out.memory, 0));
  VK_TRY(vkMapMemory(gpu.device, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped));
  return Status::success();
}

VkImageMemoryBarrier imageBarrier(VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                                  VkAccessFlags src, VkAccessFlags dst, std::uint32_t baseLevel = 0,
                                  std::uint32_t levels = VK_REMAINING_MIP_LEVELS) {
  return {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, src, dst, from, to, VK_QUEUE_FAMILY_IGNORED,
          VK_QUEUE_FAMILY_IGNORED, image, {aspect, baseLevel, levels, 0, 1}};
}

void cmdBarriers(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst,
                 const std::vector<VkImageMemoryBarrier>& barriers) {
  if (!barriers.empty())
    vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, std::uint32_t(barriers.size()), barriers.data());
}

// The VkFormat of an effect image: the generated table says which it is (depth is only an input).
VkFormat vkFormat(gen::Format format) {
  const gen::FormatInfo& f = gen::formatInfo(format);
  return f.colour ? static_cast<VkFormat>(f.vkFormat) : VK_FORMAT_UNDEFINED;
}

bool hasFeatures(const Gpu& gpu, VkFormat format, VkFormatFeatureFlags need) {
  VkFormatProperties p{};
  vkGetPhysicalDeviceFormatProperties(gpu.physical, format, &p);
  return (p.optimalTilingFeatures & need) == need;
}

// ---- The executor: what FrameState asks for, in raw Vulkan.

// An image behind a resource, as the effect sees it: the engine's depth (sampled in `layout`) and
// output (GENERAL), which the engine transitions, or a copy of an effect image (always GENERAL).
struct Target {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};

class VkExecutor final : public sao::Executor {
 public:
  VkExecutor(const Gpu& gpu, std::string shaderDir) : gpu_(gpu), shaderDir_(std::move(shaderDir)) {}

  Status init() {
    // The one sampler of every read: the shaders only texelFetch, at explicit levels.
    VkSamplerCreateInfo s{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    s.magFilter = s.minFilter = VK_FILTER_NEAREST;
    s.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    s.addressModeU = s.addressModeV = s.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    s.maxLod = VK_LOD_CLAMP_NONE;
    VK_TRY(vkCreateSampler(gpu_.device, &s, nullptr, &sampler_));
    return makeBuffer(gpu_, sizeof(sao::ParamBlock), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, ubo_);
  }

  ~VkExecutor() override {
    vkDeviceWaitIdle(gpu_.device);
    for (Owned& o : owned_)  // none after FrameState::release()
      for (Image& i : o.copies) i.destroy(gpu_.device);
    for (const Pipeline& p : pipelines_) {  // FrameState leaves pipelines to the executor
      vkDestroyPipeline(gpu_.device, p.pipeline, nullptr);
      vkDestroyPipelineLayout(gpu_.device, p.layout, nullptr);
      vkDestroyDescriptorSetLayout(gpu_.device, p.setLayout, nullptr);
    }
    vkDestroyDescriptorPool(gpu_.device, pool_, nullptr);
    vkDestroySampler(gpu_.device, sampler_, nullptr);
    ubo_.destroy(gpu_.device);
  }

  // The engine's images of this configuration: its depth and the output.
  void setEngineImages(const Target& depth, const Target& output) { depth_ = depth, output_ = output; }

  // The device's limits against a plan, before FrameState creates anything for it (core checks
  // each pass's shared memory, push constants and descriptors, and the largest image).
  Status checkPlan(const sao::Plan& plan) override {
    const VkPhysicalDeviceLimits& l = gpu_.props.limits;
    sao::DeviceLimits limits;
    limits.imageSide = {l.maxImageDimension2D, "maxImageDimension2D"};
    limits.sharedBytes = {l.maxComputeSharedMemorySize, "maxComputeSharedMemorySize"};
    limits.pushConstantBytes = {l.maxPushConstantsSize, "maxPushConstantsSize"};
    limits.storageImagesPerPass = {l.maxPerStageDescriptorStorageImages, "maxPerStageDescriptorStorageImages"};
    limits.sampledImagesPerPass = {l.maxPerStageDescriptorSampledImages, "maxPerStageDescriptorSampledImages"};
    return sao::checkDeviceLimits(plan, limits);
  }

  // The schedule's work groups against the device (FrameState hands over the schedule it made; a
  // refusal here destroys the plan's new images and keeps the current configuration).
  Status preparePlan(const sao::Plan&, const sao::Schedule& schedule) override {
    const VkPhysicalDeviceLimits& l = gpu_.props.limits;
    for (const sao::ScheduledDispatch& d : schedule.dispatches)
      if (d.groupsX > l.maxComputeWorkGroupCount[0] || d.groupsY > l.maxComputeWorkGroupCount[1])
        return Status::error(StatusCode::InvalidExtent, "pass '" + std::string(gen::pass(d.pass).name) +
                                                            "' needs more work groups than the device dispatches");
    return Status::success();
  }

  Status createImage(const sao::PlannedImage& image) override {
    const VkFormat format = vkFormat(image.format);
    if (!hasFeatures(gpu_, format, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT))
      return Status::error(StatusCode::UnsupportedFormat, "the device cannot store and sample VkFormat " +
                                                              std::to_string(format) + " of " + nameOf(image.resource));
    Owned& made = owned_.emplace_back(Owned{image, std::vector<Image>(image.copies)});  // a history has two
    for (Image& copy : made.copies)
      if (Status st = makeImage(gpu_, format, VK_IMAGE_ASPECT_COLOR_BIT, image.extent, image.mipLevels,
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, copy);
          !st) {
        destroyImage(image);
        return Status::error(st.code, std::string(nameOf(image.resource)) + ": " + st.message);
      }
    return Status::success();
  }

  // Named by the PlannedImage it was made for: while a new plan replaces an image, the old and the
  // new one of a resource both exist. Every frame waited for its fence; an engine with frames in
  // flight would wait for theirs here.
  void destroyImage(const sao::PlannedImage& image) noexcept override {
    const auto o = std::find_if(owned_.begin(), owned_.end(), [&](const Owned& x) { return same(x.planned, image); });
    if (o == owned_.end()) return;
    for (Image& copy : o->copies) copy.destroy(gpu_.device);
    owned_.erase(o);
  }

  Status createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) override;
  Status beginFrame(const sao::FrameWork& frame) override;
  void barrier(std::span<const sao::Hazard> hazards) override;
  void dispatch(const sao::ScheduledDispatch& d, std::span<const sao::ScheduledBinding> bindings) override;

  Status endFrame() override {
    const Status submitted = gpu_.submitAndWait();
    return error_.ok() ? submitted : error_;
  }

 private:
  struct Pipeline {
    const gen::PassVariantInfo* variant;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
  };

  // The image a binding or hazard names this frame: the engine's for an input or the output, else
  // the effect's own copy (imageCopy: a history's previous or current one).
  Target target(gen::ResourceId id, bool previousFrame) const {
    if (const Image* copy = ownedCopy(id, previousFrame)) return {copy->image, copy->whole};
    if (id == gen::ResourceId::depth) return depth_;
    return isOutput(id) ? output_ : Target{};
  }
  // This frame's copy of an effect image (current_: the plan's images, found in beginFrame), or null.
  const Image* ownedCopy(gen::ResourceId id, bool previousFrame) const {
    const Owned* o = current_[std::size_t(id)];
    return o ? &o->copies[sao::imageCopy(frame_.historyParity, id, previousFrame)] : nullptr;
  }
  static bool same(const sao::PlannedImage& a, const sao::PlannedImage& b) {
    return a.resource == b.resource && sao::sameImage(a, b) && a.copies == b.copies;
  }
  Status ensurePool(const sao::Schedule& schedule);

  const Gpu& gpu_;
  std::string shaderDir_;
  Target depth_, output_;
  struct Owned {
    sao::PlannedImage planned;
    std::vector<Image> copies;
  };
  std::vector<Owned> owned_;  // every effect image made, one Image per copy
  std::array<const Owned*, gen::kResources.size()> current_{};  // this frame's, by resource
  std::vector<Pipeline> pipelines_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  Buffer ubo_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::array<std::uint32_t, 3> poolSize_{};  // sets, sampled and storage descriptors it holds
  sao::FrameWork frame_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  Status error_;  // of barrier() or dispatch(), which return none: endFrame() returns it
};

Status VkExecutor::createPipeline(const gen::PassInfo& pass, const gen::PassVariantInfo& variant) {
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

  Pipeline& p = pipelines_.emplace_back(Pipeline{&variant});  // the destructor frees what gets made
  std::vector<VkDescriptorSetLayoutBinding> bindings{
      {gen::kParamBlockBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  for (const gen::BindingInfo& b : variant.bindings)  // a read has one element: only writes are arrays
    bindings.push_back({b.binding, descriptorType(b.write), b.slots, VK_SHADER_STAGE_COMPUTE_BIT,
                        b.write ? nullptr : &sampler_});
  const VkDescriptorSetLayoutCreateInfo dl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, nullptr, 0,
                                           std::uint32_t(bindings.size()), bindings.data()};
  VK_TRY(vkCreateDescriptorSetLayout(gpu_.device, &dl, nullptr, &p.setLayout));
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, variant.pushConstantBytes};
  const VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO, nullptr, 0, 1, &p.setLayout,
                                      variant.pushConstantBytes ? 1u : 0u, &push};
  VK_TRY(vkCreatePipelineLayout(gpu_.device, &pl, nullptr, &p.layout));
  const VkShaderModuleCreateInfo sm{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, nullptr, 0, std::size_t(size),
                                    code.data()};
  VkShaderModule module;
  VK_TRY(vkCreateShaderModule(gpu_.device, &sm, nullptr, &module));
  const VkComputePipelineCreateInfo ci{
      VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO, nullptr, 0,
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main"},
      p.layout};
  const VkResult r = vkCreateComputePipelines(gpu_.device, VK_NULL_HANDLE, 1, &ci, nullptr, &p.pipeline);
  vkDestroyShaderModule(gpu_.device, module, nullptr);
  return r == VK_SUCCESS ? Status::success() : vkFail("vkCreateComputePipelines for " + where, r);
}

// One descriptor set per dispatch, from a pool reset every frame and grown for a larger schedule.
Status VkExecutor::ensurePool(const sao::Schedule& schedule) {
  std::array<std::uint32_t, 3> need{std::uint32_t(schedule.dispatches.size()), 0, 0};
  for (const sao::ScheduledDispatch& d : schedule.dispatches)
    for (const gen::BindingInfo& b : d.variant->bindings) need[b.write ? 2 : 1] += b.slots;
  if (pool_ && need[0] <= poolSize_[0] && need[1] <= poolSize_[1] && need[2] <= poolSize_[2]) {
    VK_TRY(vkResetDescriptorPool(gpu_.device, pool_, 0));  // the frame before has completed
    return Status::success();
  }
  vkDestroyDescriptorPool(gpu_.device, pool_, nullptr);
  pool_ = VK_NULL_HANDLE;
  for (std::uint32_t& n : need) n = std::max(n, 1u);
  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, need[0]},
                                        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, need[1]},
                                        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, need[2]}};
  const VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO, nullptr, 0, need[0], 3, sizes};
  VK_TRY(vkCreateDescriptorPool(gpu_.device, &info, nullptr, &pool_));
  poolSize_ = need;
  return Status::success();
}

Status VkExecutor::beginFrame(const sao::FrameWork& frame) {
  frame_ = frame;
  error_ = Status::success();
  std::memcpy(ubo_.mapped, frame.block, sizeof(sao::ParamBlock));  // coherent: the submit makes it visible
  current_ = {};
  for (const sao::PlannedImage& planned : frame.plan->images) {
    const auto o = std::find_if(owned_.begin(), owned_.end(), [&](const Owned& x) { return same(x.planned, planned); });
    if (o == owned_.end())
      return Status::error(StatusCode::InvalidInput, std::string("no image made for ") + nameOf(planned.resource));
    current_[std::size_t(planned.resource)] = &*o;
  }
  if (Status st = ensurePool(*frame.schedule); !st) return st;
  cmd_ = gpu_.begin();
  // The frame rewrites every effect image, so their contents are discarded (UNDEFINED -> GENERAL)
  // after the previous frame's accesses; but the previous frame's history copy, which this frame
  // reads, is kept when it holds a frame.
  std::vector<VkImageMemoryBarrier> barriers;
  for (const sao::PlannedImage& planned : frame.plan->images) {
    const std::vector<Image>& copies = current_[std::size_t(planned.resource)]->copies;
    for (std::uint32_t c = 0; c < planned.copies; ++c) {
      const bool keep = frame.historyValid && gen::kResources[std::size_t(planned.resource)].history &&
                        c == sao::imageCopy(frame.historyParity, planned.resource, true);
      barriers.push_back(imageBarrier(copies[c].image, VK_IMAGE_ASPECT_COLOR_BIT,
                                      keep ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED,
                                      VK_IMAGE_LAYOUT_GENERAL, VK_ACCESS_SHADER_WRITE_BIT,
                                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT));
    }
  }
  cmdBarriers(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, barriers);
  return Status::success();
}

void VkExecutor::barrier(std::span<const sao::Hazard> hazards) {
  constexpr VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  constexpr VkPipelineStageFlags transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
  VkPipelineStageFlags srcStages = 0, dstStages = 0;
  std::vector<VkImageMemoryBarrier> barriers;
  for (const sao::Hazard& h : hazards) {
    const Target t = target(h.resource, h.previousFrame);
    if (!t.image) {
      error_ = Status::error(StatusCode::InvalidInput,
                             std::string("a hazard names ") + nameOf(h.resource) + ", which the engine lacks");
      continue;
    }
    // {src stage, src access, dst stage, dst access}: the effect reads by sampling and writes by
    // storing in compute shaders; this engine writes its depth and reads the output by transfers.
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
    if (isOutput(h.resource)) srcStages |= transfer;
    dstStages |= rule.dstStage;
    barriers.push_back(imageBarrier(t.image, t.aspect, t.layout, t.layout, rule.src, rule.dst, h.baseLevel,
                                    h.levelCount));
  }
  cmdBarriers(cmd_, srcStages, dstStages, barriers);
}

void VkExecutor::dispatch(const sao::ScheduledDispatch& d, std::span<const sao::ScheduledBinding> bindings) {
  const auto p = std::find_if(pipelines_.begin(), pipelines_.end(), [&](auto& q) { return q.variant == d.variant; });
  VkDescriptorSet set = VK_NULL_HANDLE;
  if (p != pipelines_.end()) {
    const VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO, nullptr, pool_, 1,
                                         &p->setLayout};
    if (VkResult r = vkAllocateDescriptorSets(gpu_.device, &ai, &set); r != VK_SUCCESS) set = VK_NULL_HANDLE;
  }
  if (!set) {
    error_ = Status::error(StatusCode::DriverError,
                           std::string("no pipeline or descriptor set for pass ") + gen::pass(d.pass).name.data());
    return;
  }
  // The block, then each binding: the schedule's bindings are the variant's, in order. Element
  // `slot` of a levels= write's array is level slotLevel(slot); a read sees one level or the chain.
  const VkDescriptorBufferInfo block{ubo_.buffer, 0, sizeof(sao::ParamBlock)};
  std::vector<VkDescriptorImageInfo> images;
  for (std::size_t i = 0; i < bindings.size(); ++i) {
    const sao::ScheduledBinding& b = bindings[i];
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
  vkUpdateDescriptorSets(gpu_.device, std::uint32_t(writes.size()), writes.data(), 0, nullptr);
  vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
  vkCmdBindDescriptorSets(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &set, 0, nullptr);
  if (d.variant->pushConstantBytes) {
    const gen::PushConstants constants = gen::pushConstantsOf(*frame_.block);
    vkCmdPushConstants(cmd_, p->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, d.variant->pushConstantBytes, &constants);
  }
  vkCmdDispatch(cmd_, d.groupsX, d.groupsY, 1);
}

// ---- The engine's side: its depth and output images, the frames, the readback, the check.

// One-shot work of the engine on the same queue: the executor's frames are ordered after it.
Status submitOnce(const Gpu& gpu, const std::function<void(VkCommandBuffer)>& record) {
  record(gpu.begin());
  return gpu.submitAndWait();
}

// The output copied to the host and widened from binary16. It lives in GENERAL, where the effect
// stores to it, and the frame's CallerReads barrier made its writes visible to transfers; the copy
// reads it in TRANSFER_SRC_OPTIMAL and gives it back in GENERAL before the next frame's writes.
Status readOutput(const Gpu& gpu, VkImage output, sao::Extent extent, sao::FloatImage& out) {
  Buffer host;
  Defer freeHost{[&] { host.destroy(gpu.device); }};
  out = sao::FloatImage(extent, 1);
  if (Status st = makeBuffer(gpu, out.data.size() * 2, VK_BUFFER_USAGE_TRANSFER_DST_BIT, host); !st) return st;
  const Status st = submitOnce(gpu, [&](VkCommandBuffer cmd) {
    cmdBarriers(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                {imageBarrier(output, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                              VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, 0, VK_ACCESS_TRANSFER_READ_BIT)});
    const VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {}, {extent.width, extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, output, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host.buffer, 1, &region);
    cmdBarriers(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                {imageBarrier(output, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT)});
    const VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                                       VK_ACCESS_HOST_READ_BIT, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED,
                                       host.buffer, 0, VK_WHOLE_SIZE};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &toHost, 0,
                         nullptr);
  });
  const auto* half = static_cast<const std::uint16_t*>(host.mapped);
  for (std::size_t i = 0; st && i < out.data.size(); ++i) out.data[i] = sao::halfToFloat(half[i]);
  return st;
}

// One depth file through the engine: its images, `frames` frames of FrameState, the readback.
Status runFile(const Gpu& gpu, VkExecutor& executor, sao::FrameState& frame, const sao::Settings& settings,
               std::uint32_t frames, const sao::DepthImage& depth, const sao::Camera& camera, sao::FloatImage& ao,
               std::size_t& passes) {
  const bool linear = depth.format == sao::DepthFormat::LinearZ;
  sao::PlanInputs inputs;
  inputs.depthEncoding = linear ? sao::DepthEncoding::LinearZ : sao::DepthEncoding::Hardware;
  inputs.userOutput = true;  // the engine owns the output
  inputs.outputFormat = gen::Format::R16F;
  if (Status st = frame.configure(settings, camera, inputs, executor); !st) return st;
  Defer release{[&] { frame.release(executor); }};
  const sao::Plan& plan = frame.plan();
  passes = plan.passes.size();

  // The engine's images: its depth (D32F through the depth aspect, or LinearZ as R32F) and the
  // output, an r16f storage image (shaderStorageImageExtendedFormats) of the plan's AO extent.
  Image depthImage, output;
  Buffer staging;
  Defer freeImages{[&] { depthImage.destroy(gpu.device), output.destroy(gpu.device), staging.destroy(gpu.device); }};
  const VkImageAspectFlags aspect = linear ? VK_IMAGE_ASPECT_COLOR_BIT : VK_IMAGE_ASPECT_DEPTH_BIT;
  const VkFormat depthFormat = linear ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_D32_SFLOAT;
  if (!hasFeatures(gpu, depthFormat, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT))
    return Status::error(StatusCode::UnsupportedFormat, "the device cannot sample VkFormat " +
                                                            std::to_string(depthFormat));
  const VkDeviceSize bytes = depth.texels.size() * sizeof(std::uint32_t);  // D32F and LinearZ: the floats' bits
  if (Status st = makeImage(gpu, depthFormat, aspect, depth.extent, 1,
                            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, depthImage);
      !st)
    return st;
  if (Status st = makeImage(gpu, VK_FORMAT_R16_SFLOAT, VK_IMAGE_ASPECT_COLOR_BIT, plan.aoExtent, 1,
                            VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, output);
      !st)
    return st;
  if (Status st = makeBuffer(gpu, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, staging); !st) return st;
  std::memcpy(staging.mapped, depth.texels.data(), bytes);
  // The depth uploaded and left in SHADER_READ_ONLY_OPTIMAL, the layout the effect samples it in
  // (each frame's CallerWrote barrier orders the reads after the copy); the output in GENERAL from
  // here on, where the effect stores to it.
  if (Status st = submitOnce(gpu, [&](VkCommandBuffer cmd) {
        cmdBarriers(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                    VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                    {imageBarrier(depthImage.image, aspect, VK_IMAGE_LAYOUT_UNDEFINED,
                                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT),
                     imageBarrier(output.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                  VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT)});
        const VkBufferImageCopy region{0, 0, 0, {aspect, 0, 0, 1}, {}, {depth.extent.width, depth.extent.height, 1}};
        vkCmdCopyBufferToImage(cmd, staging.buffer, depthImage.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        cmdBarriers(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    {imageBarrier(depthImage.image, aspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT, 0)});
      });
      !st)
    return st;
  executor.setEngineImages({depthImage.image, depthImage.whole, aspect, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                           {output.image, output.whole});

  // What the engine hands over, so that core checks it against the plan every frame.
  sao::SuppliedImages supplied{};
  supplied[std::size_t(gen::ResourceId::depth)] = {true, depth.extent, {}};
  supplied[std::size_t(gen::ResourceId::ao)] = {true, plan.aoExtent, {}};
  sao::FrameInputs in;
  in.images = &supplied;  // frameIndex 0 every frame: the spiral of the CPU reference's run
  for (std::uint32_t f = 0; f < frames; ++f)
    if (Status st = frame.run(in, executor); !st)
      return Status::error(st.code, "frame " + std::to_string(f) + ": " + st.message);
  return readOutput(gpu, output.image, plan.aoExtent, ao);
}

// The GPU's output against the CPU reference in float (as a GPU computes); with the temporal
// setting the CPU runs as many frames, carrying the history from run to run as the GPU does.
bool compare(const std::string& path, const sao::Settings& settings, std::uint32_t frames, const sao::FloatImage& vk,
             std::size_t passes, const sao::DepthImage& depth, const sao::Camera& camera) {
  sao::cpu::Inputs in;
  in.depth = &depth;
  in.outputFormat = gen::Format::R16F;
  sao::cpu::Options options;
  options.precision = sao::cpu::Precision::Float;
  sao::cpu::Result cpu, previous;
  for (std::uint32_t f = 0; f < (settings.temporal ? frames : 1); ++f) {
    in.history = f ? &previous.images[std::size_t(gen::ResourceId::history)][0] : nullptr;
    in.previousCamera = f ? &camera : nullptr;
    if (Status st = sao::cpu::run(settings, camera, in, options, cpu); !st)
      return std::fprintf(stderr, "%s: the CPU reference failed: %s\n", path.c_str(), st.message.c_str()), false;
    std::swap(cpu, previous);
  }
  const sao::FloatImage& ref = previous.ao;
  if (ref.extent != vk.extent || ref.channels != 1)
    return std::fprintf(stderr, "%s: the CPU reference's output differs in size\n", path.c_str()), false;
  std::vector<float> diff(vk.data.size());
  std::size_t nonFinite = 0, above = 0;
  for (std::size_t i = 0; i < diff.size(); ++i) {
    const bool finite = std::isfinite(vk.data[i]) && std::isfinite(ref.data[i]);
    diff[i] = finite ? std::fabs(vk.data[i] - ref.data[i]) : INFINITY;
    nonFinite += !finite;
    above += diff[i] > 2.0f / 255.0f;
  }
  std::sort(diff.begin(), diff.end());
  const float max = diff.back(), p999 = diff[std::size_t(std::ceil(0.999 * double(diff.size()))) - 1];
  std::printf("%s: %ux%u, %zu passes, max |vk - cpu| = %.3g (%.3f/255), p99.9 = %.3f/255, %zu texels > 2/255\n",
              path.c_str(), vk.extent.width, vk.extent.height, passes, max, max * 255.0f, p999 * 255.0f, above);
  if (nonFinite) std::fprintf(stderr, "%s: %zu texels are not finite\n", path.c_str(), nonFinite);
  if (p999 > 2.0f / 255.0f) std::fprintf(stderr, "%s: p99.9 exceeds 2/255\n", path.c_str());
  return nonFinite == 0 && p999 <= 2.0f / 255.0f;
}

// A depth file this engine takes: a sao.* camera, single-sampled D32F or LinearZ, valid texels.
Status readDepth(const std::string& path, sao::DepthImage& depth, sao::Camera& camera) {
  bool hasCamera = false;
  if (Status st = sao::readDepthExr(path, depth, camera, hasCamera); !st) return st;  // it names the file
  if (!hasCamera)
    return Status::error(StatusCode::InvalidInput, path + " has no sao.* camera (sao-render --save-depth writes one)");
  if (depth.samples > 1)
    return Status::error(StatusCode::UnsupportedFormat, path + " is multisampled (" + std::to_string(depth.samples) +
                                                        " samples); this engine reads single-sampled depth");
  if (depth.format != sao::DepthFormat::D32F && depth.format != sao::DepthFormat::LinearZ)
    return Status::error(StatusCode::UnsupportedFormat,
                         path + " holds " + sao::toString(depth.format) + " depth; this engine takes D32F or LinearZ");
  // Temporal accumulation needs the view matrix: a file without one is a camera that never moves.
  if (!camera.view) camera.view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (Status st = sao::checkDepthValues(depth); !st) return Status::error(st.code, path + ": " + st.message);
  return Status::success();
}

int usage(const char* message) {
  std::fprintf(stderr,
               "sao-example-vulkan-engine: %s\n"
               "usage: sao-example-vulkan-engine --shaders DIR [--frames N] [--set NAME=VALUE]... [--no-validation]\n"
               "                                 DEPTH.exr [DEPTH.exr ...]\n"
               "  --shaders DIR     the installed shader files, <fileStem>.spv\n"
               "  --frames N        frames per depth file, 1..1000 (default 2)\n"
               "  --set NAME=VALUE  a setting (default: the settings' defaults)\n"
               "  --no-validation   without VK_LAYER_KHRONOS_validation (required by default)\n",
               message);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string shaders;
  std::uint32_t frames = 2;
  sao::Settings settings;
  bool validation = true;
  std::vector<std::string> files;
  std::vector<sao::SettingId> given;  // a setting given that has no effect is refused
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--shaders" || a == "--frames" || a == "--set") && i + 1 == argc)
      return usage((a + " needs a value").c_str());
    if (a == "--shaders") {
      shaders = argv[++i];
    } else if (a == "--frames") {
      char* end = nullptr;
      const unsigned long n = std::strtoul(argv[++i], &end, 10);
      if (*end || argv[i][0] == '-' || n < 1 || n > 1000) return usage("--frames takes 1..1000");
      frames = std::uint32_t(n);
    } else if (a == "--set") {
      const std::string assignment = argv[++i];
      if (Status st = sao::setFromAssignment(settings, assignment); !st) return usage(st.message.c_str());
      if (const auto id = sao::findSetting(assignment.substr(0, assignment.find('=')))) given.push_back(*id);
    } else if (a == "--no-validation") {
      validation = false;
    } else if (a == "--help") {
      return usage("the effect run by an engine's own sao::Executor on Vulkan"), 0;
    } else if (a.rfind("--", 0) == 0) {
      return usage(("unknown option " + a).c_str());
    } else {
      files.push_back(a);
    }
  }
  if (shaders.empty()) return usage("--shaders DIR is required");
  if (files.empty()) return usage("no depth file given");
  for (sao::SettingId id : given)
    if (const gen::InertRule* rule = sao::inertRule(settings, id)) return usage(sao::describeInert(*rule).c_str());

  // Every file read and checked before the device starts.
  std::vector<sao::DepthImage> depths(files.size());
  std::vector<sao::Camera> cameras(files.size());
  for (std::size_t i = 0; i < files.size(); ++i)
    if (Status st = readDepth(files[i], depths[i], cameras[i]); !st)
      return std::fprintf(stderr, "sao-example-vulkan-engine: %s\n", st.message.c_str()), 1;

  int failed = 0;
  {
    Gpu gpu;
    if (Status st = gpu.create(validation); !st)
      return std::fprintf(stderr, "sao-example-vulkan-engine: %s\n", st.message.c_str()), 1;
    VkExecutor executor(gpu, shaders);
    if (Status st = executor.init(); !st) return std::fprintf(stderr, "executor: %s\n", st.message.c_str()), 1;
    sao::FrameState frame("vk-engine-example");  // one effect instance, configured for each file
    for (std::size_t i = 0; i < files.size(); ++i) {
      sao::FloatImage ao;
      std::size_t passes = 0;
      if (Status st = runFile(gpu, executor, frame, settings, frames, depths[i], cameras[i], ao, passes); !st)
        std::fprintf(stderr, "%s: %s\n", files[i].c_str(), st.message.c_str()), ++failed;
      else if (!compare(files[i], settings, frames, ao, passes, depths[i], cameras[i]))
        ++failed;
    }
  }  // the executor, then the device and the instance: the layer reports leaks here
  if (validation) std::printf("validation: %d message(s)\n", gValidationMessages);
  if (failed) std::fprintf(stderr, "%d of %zu file(s) failed\n", failed, files.size());
  return failed || gValidationMessages ? 1 : 0;
}
