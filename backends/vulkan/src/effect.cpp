// Effect: creation (version, functions, device checks), configuration checks, teardown.
#include <algorithm>
#include <string>
#include <utility>

#include "effect_impl.h"
#include "sao/inputs.h"

namespace sao::vk {
namespace {

std::string versionText(int v) {
  return std::to_string((v >> 16) & 0xff) + "." + std::to_string((v >> 8) & 0xff) + "." + std::to_string(v & 0xff);
}

#define SAO_VK_NAMED(f) std::pair{f, #f}
// Formats named in messages by their Vulkan names (the others by number).
constexpr std::pair<VkFormat, const char*> kNamedFormats[] = {
    SAO_VK_NAMED(VK_FORMAT_D16_UNORM), SAO_VK_NAMED(VK_FORMAT_X8_D24_UNORM_PACK32),
    SAO_VK_NAMED(VK_FORMAT_D24_UNORM_S8_UINT), SAO_VK_NAMED(VK_FORMAT_D32_SFLOAT),
    SAO_VK_NAMED(VK_FORMAT_D32_SFLOAT_S8_UINT), SAO_VK_NAMED(VK_FORMAT_R32_SFLOAT),
    SAO_VK_NAMED(VK_FORMAT_S8_UINT), SAO_VK_NAMED(VK_FORMAT_D16_UNORM_S8_UINT),
    SAO_VK_NAMED(VK_FORMAT_R8_UNORM), SAO_VK_NAMED(VK_FORMAT_R8_SNORM), SAO_VK_NAMED(VK_FORMAT_R16_SNORM),
    SAO_VK_NAMED(VK_FORMAT_R16_SFLOAT), SAO_VK_NAMED(VK_FORMAT_R8G8_SNORM),
    SAO_VK_NAMED(VK_FORMAT_R16G16_SNORM), SAO_VK_NAMED(VK_FORMAT_R16G16_SFLOAT),
    SAO_VK_NAMED(VK_FORMAT_R32G32_SFLOAT), SAO_VK_NAMED(VK_FORMAT_R16G16B16A16_SFLOAT),
    SAO_VK_NAMED(VK_FORMAT_R32G32B32A32_SFLOAT), SAO_VK_NAMED(VK_FORMAT_R8G8B8A8_UNORM)};
#undef SAO_VK_NAMED

std::string formatText(VkFormat f) {
  for (const auto& [format, name] : kNamedFormats)
    if (format == f) return name;
  return "VkFormat " + std::to_string(static_cast<int>(f));
}
std::string formatText(gen::Format f) { return formatText(static_cast<VkFormat>(gen::formatInfo(f).vkFormat)); }

template <std::size_t N>
bool listed(const VkFormat (&list)[N], VkFormat f) {
  return std::find(list, list + N, f) != list + N;
}

constexpr VkFormat kDepthStencilFormats[] = {
    VK_FORMAT_D16_UNORM, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D32_SFLOAT, VK_FORMAT_S8_UINT,
    VK_FORMAT_D16_UNORM_S8_UINT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT_S8_UINT};
bool isDepthStencilFormat(VkFormat f) { return listed(kDepthStencilFormats, f); }
// What a depth input may be: hardware depth (the depth aspect of the combined formats) or linear z.
constexpr VkFormat kDepthReadFormats[] = {VK_FORMAT_D16_UNORM,         VK_FORMAT_X8_D24_UNORM_PACK32,
                                          VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT,
                                          VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_R32_SFLOAT};

// The colour channels a sampled read of `f` returns when it has fewer than three (1 or 2), else 3
// (three, four, or a format not listed here). Only the count below three matters: it decides
// whether .xy or .xyz of a normal would read a missing channel as 0 (no input reads .w without
// formats= listing its formats).
constexpr VkFormat kOneChannel[] = {
    VK_FORMAT_R8_UNORM, VK_FORMAT_R8_SNORM, VK_FORMAT_R8_USCALED, VK_FORMAT_R8_SSCALED, VK_FORMAT_R8_UINT,
    VK_FORMAT_R8_SINT, VK_FORMAT_R8_SRGB, VK_FORMAT_R16_UNORM, VK_FORMAT_R16_SNORM, VK_FORMAT_R16_USCALED,
    VK_FORMAT_R16_SSCALED, VK_FORMAT_R16_UINT, VK_FORMAT_R16_SINT, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R32_UINT,
    VK_FORMAT_R32_SINT, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R64_UINT, VK_FORMAT_R64_SINT, VK_FORMAT_R64_SFLOAT,
    VK_FORMAT_BC4_UNORM_BLOCK, VK_FORMAT_BC4_SNORM_BLOCK, VK_FORMAT_EAC_R11_UNORM_BLOCK,
    VK_FORMAT_EAC_R11_SNORM_BLOCK, VK_FORMAT_R10X6_UNORM_PACK16, VK_FORMAT_R12X4_UNORM_PACK16};
constexpr VkFormat kTwoChannels[] = {
    VK_FORMAT_R4G4_UNORM_PACK8, VK_FORMAT_R8G8_UNORM, VK_FORMAT_R8G8_SNORM, VK_FORMAT_R8G8_USCALED,
    VK_FORMAT_R8G8_SSCALED, VK_FORMAT_R8G8_UINT, VK_FORMAT_R8G8_SINT, VK_FORMAT_R8G8_SRGB,
    VK_FORMAT_R16G16_UNORM, VK_FORMAT_R16G16_SNORM, VK_FORMAT_R16G16_USCALED, VK_FORMAT_R16G16_SSCALED,
    VK_FORMAT_R16G16_UINT, VK_FORMAT_R16G16_SINT, VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R32G32_UINT,
    VK_FORMAT_R32G32_SINT, VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R64G64_UINT, VK_FORMAT_R64G64_SINT,
    VK_FORMAT_R64G64_SFLOAT, VK_FORMAT_BC5_UNORM_BLOCK, VK_FORMAT_BC5_SNORM_BLOCK,
    VK_FORMAT_EAC_R11G11_UNORM_BLOCK, VK_FORMAT_EAC_R11G11_SNORM_BLOCK, VK_FORMAT_R10X6G10X6_UNORM_2PACK16,
    VK_FORMAT_R12X4G12X4_UNORM_2PACK16};
std::uint32_t channelsUpToThree(VkFormat f) { return listed(kOneChannel, f) ? 1 : listed(kTwoChannels, f) ? 2 : 3; }

Status checkSampled(const EffectState& e, VkFormat format, std::string_view what) {
  VkFormatProperties fp{};
  e.d.vkGetPhysicalDeviceFormatProperties(e.ctx.physicalDevice, format, &fp);
  if (!(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT))
    return Status::error(StatusCode::UnsupportedFormat, "the " + std::string(what) + " format " + formatText(format) +
                                                            " cannot be sampled on this device (optimal tiling)");
  return Status::success();
}

// Every input's format against the effect's contract (sao/inputs.h) and the device: a depth input
// one of the depth formats (all of one frame the same), a colour input what its declaration
// accepts with the channels `camera` reads, each sampled with optimal tiling.
Status checkInputFormats(const EffectState& e, const InputFormats& formats, const Camera& camera) {
  if (Status st = checkColourInputs(formats, camera); !st) return st;
  for (const gen::ResourceId id : gen::kInputIds) {
    const VkFormat f = formats[id];
    if (f == VK_FORMAT_UNDEFINED) continue;  // not given (frameConfigOf requires the depth)
    if (isDepthInput(id)) {
      if (!listed(kDepthReadFormats, f))
        return Status::error(StatusCode::UnsupportedFormat,
                             inputName(id) + ".format" + " " + formatText(f) +
                                 " is not a depth format the effect reads (D16_UNORM, X8_D24_UNORM_PACK32, "
                                 "D24_UNORM_S8_UINT, D32_SFLOAT, D32_SFLOAT_S8_UINT, or R32_SFLOAT linear z)");
      if (f != formats.depth)
        return Status::error(StatusCode::InvalidInput, inputName(id) + ".format" + " " + formatText(f) + " but the depth is " +
                                                           formatText(formats.depth) + ": every depth layer has one format");
    } else if (isDepthStencilFormat(f)) {
      return Status::error(StatusCode::UnsupportedFormat, inputName(id) + ".format" + " " + formatText(f) + " is a depth/stencil format");
    }
    if (Status st = checkSampled(e, f, gen::kResources[static_cast<std::size_t>(id)].name); !st) return st;
  }
  return Status::success();
}

// A multisampled depth input is read directly (sampler2DMS, DEPTH_MULTISAMPLE): one sample count
// bit, which the device can sample for the format (and never with a second layer).
Status checkDepthSamples(const EffectState& e, const FrameConfig& f) {
  const auto n = static_cast<std::uint32_t>(f.depthSamples);
  if (n == 0 || n > 64 || (n & (n - 1)) != 0)
    return Status::error(StatusCode::InvalidInput, "Inputs::depth.samples is " + std::to_string(n) +
                                                       "; it must be one VkSampleCountFlagBits (1, 2, 4, .. 64)");
  if (n == 1) return Status::success();
  const bool colour = f.formats.depth == VK_FORMAT_R32_SFLOAT;
  const VkSampleCountFlags counts =
      colour ? e.props.limits.sampledImageColorSampleCounts : e.props.limits.sampledImageDepthSampleCounts;
  if (!(counts & f.depthSamples))
    return Status::error(StatusCode::UnsupportedFormat,
                         "Inputs::depth.samples is " + std::to_string(n) + " but this device samples " +
                             (colour ? "colour" : "depth") + " images with " + std::to_string(counts) +
                             " (sampledImage" + (colour ? "Color" : "Depth") + "SampleCounts bits) only");
  if (f.formats.depth2 != VK_FORMAT_UNDEFINED)
    return Status::error(StatusCode::InvalidInput,
                         "Inputs::depth.samples is " + std::to_string(n) +
                             " with Inputs::depth2: a multisampled depth input has no second layer (give both "
                             "layers single-sample)");
  return Status::success();
}

// An output format the effect writes, storable on the device: the effect's own (create()) or the
// caller's (each record()). `what` names it.
Status checkOutputFormat(const EffectState& e, VkFormat format, const std::string& what) {
  const gen::Format outputFormat = outputFormatOf(format);
  if (!isOutputFormat(outputFormat))
    return Status::error(StatusCode::UnsupportedFormat,
                         what + " is VkFormat " + std::to_string(static_cast<int>(format)) +
                             "; the effect writes VK_FORMAT_R16_SFLOAT, R8_UNORM, R8G8B8A8_UNORM or R16G16B16A16_SFLOAT");
  VkFormatProperties fp{};
  e.d.vkGetPhysicalDeviceFormatProperties(e.ctx.physicalDevice, format, &fp);
  if (!(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
    return Status::error(StatusCode::UnsupportedFormat, what + " " + sao::formatName(outputFormat) +
                                                            " cannot be an optimal-tiling storage image on this device");
  return Status::success();
}

// What create() fixes for the effect's life: the ring, the output's layout, stages and format.
Status checkConfig(const EffectState& e, const Config& c) {
  if (c.framesInFlight < 1 || c.framesInFlight > kMaxFramesInFlight)
    return Status::error(StatusCode::InvalidInput, "Config::framesInFlight is " + std::to_string(c.framesInFlight) +
                                                       "; allowed 1.." + std::to_string(kMaxFramesInFlight));
  if (c.outputLayout != VK_IMAGE_LAYOUT_GENERAL && c.outputLayout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
    return Status::error(StatusCode::InvalidInput, "Config::outputLayout must be VK_IMAGE_LAYOUT_GENERAL or "
                                                   "VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, got " +
                                                       std::to_string(c.outputLayout));
  if (c.outputDstStages == 0)
    return Status::error(StatusCode::InvalidInput, "Config::outputDstStages is empty");
  constexpr VkPipelineStageFlags graphicsStages =
      VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
      VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT | VK_PIPELINE_STAGE_TESSELLATION_EVALUATION_SHADER_BIT |
      VK_PIPELINE_STAGE_GEOMETRY_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
      VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT;
  if ((c.outputDstStages & graphicsStages) && !(e.family.queueFlags & VK_QUEUE_GRAPHICS_BIT))
    return Status::error(StatusCode::InvalidInput,
                         "Config::outputDstStages names graphics stages but queue family " +
                             std::to_string(e.ctx.queueFamilyIndex) +
                             " has no graphics (use VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT / TRANSFER_BIT)");
  return checkOutputFormat(e, c.outputFormat, "Config::outputFormat");
}

}  // namespace

Status checkColourInputs(const InputFormats& formats, const Camera& camera) {
  for (const gen::ResourceId id : gen::kInputIds) {
    const VkFormat f = formats[id];
    if (f == VK_FORMAT_UNDEFINED || isDepthInput(id)) continue;
    const std::optional<gen::Format> format = formatOfVk(f);
    if (colourInputRefused(id, format, channelsUpToThree(f), camera))  // messages only on failure
      return checkColourInput(id, format, channelsUpToThree(f), camera, inputName(id) + ".format", formatText(f), formatText,
                              "format");
  }
  return Status::success();
}

Status checkFrameConfig(const EffectState& e, const FrameConfig& frame, const Camera& camera, PlanInputs& out) {
  if (Status st = checkInputFormats(e, frame.formats, camera); !st) return st;
  if (Status st = checkDepthSamples(e, frame); !st) return st;
  if (frame.userOutput)
    if (Status st = checkOutputFormat(e, frame.outputFormat, "the output"); !st) return st;
  out = {};
  out.depthEncoding = depthEncodingOf(frame.formats.depth);
  for (const gen::ResourceId id : gen::kInputIds) out.supplied[id] = frame.formats[id] != VK_FORMAT_UNDEFINED;
  out.userOutput = frame.userOutput;
  out.outputFormat = outputFormatOf(frame.outputFormat);
  out.depthSamples = static_cast<std::uint32_t>(frame.depthSamples);
  return Status::success();
}

VkFormat depthVkFormat(DepthFormat format) {
  switch (format) {
    case DepthFormat::D16: return VK_FORMAT_D16_UNORM;
    case DepthFormat::D24: return VK_FORMAT_X8_D24_UNORM_PACK32;
    case DepthFormat::D32F: return VK_FORMAT_D32_SFLOAT;
    case DepthFormat::LinearZ: return VK_FORMAT_R32_SFLOAT;
  }
  return VK_FORMAT_UNDEFINED;
}

Status exceptionStatus(const char* where, const char* what) noexcept {
  try {
    return Status::error(StatusCode::DriverError, std::string(where) + ": " + what);
  } catch (...) {
    return Status::error(StatusCode::DriverError, "out of memory");  // short enough to need no allocation
  }
}

Effect::Effect(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Effect::~Effect() = default;  // the handles destroy every object; nothing here can throw

namespace {

// Everything of create() but the version check; `e` is dropped on error.
Status createEffect(const DeviceContext& context, const Config& config, EffectState& e) {
  e.ctx = context;
  e.owner = {context.device, context.allocator};
  if (Status st = e.d.load(context); !st) return st;
  e.d.vkGetPhysicalDeviceProperties(context.physicalDevice, &e.props);
  e.d.vkGetPhysicalDeviceFeatures(context.physicalDevice, &e.features);
  e.d.vkGetPhysicalDeviceMemoryProperties(context.physicalDevice, &e.memoryProps);
  std::uint32_t families = 0;
  e.d.vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice, &families, nullptr);
  std::vector<VkQueueFamilyProperties> fams(families);
  e.d.vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice, &families, fams.data());
  if (context.queueFamilyIndex >= families)
    return Status::error(StatusCode::InvalidInput, "DeviceContext::queueFamilyIndex " +
                                                       std::to_string(context.queueFamilyIndex) + " but the device has " +
                                                       std::to_string(families) + " queue families");
  e.family = fams[context.queueFamilyIndex];
  if (!(e.family.queueFlags & VK_QUEUE_COMPUTE_BIT))
    return Status::error(StatusCode::InvalidInput, "queue family " + std::to_string(context.queueFamilyIndex) +
                                                       " has no compute: the effect is compute passes");
  if (e.props.apiVersion < VK_API_VERSION_1_1)
    return Status::error(StatusCode::DriverError, std::string("the device ('") + e.props.deviceName +
                                                      "') is Vulkan " + std::to_string(VK_API_VERSION_MAJOR(e.props.apiVersion)) +
                                                      "." + std::to_string(VK_API_VERSION_MINOR(e.props.apiVersion)) +
                                                      "; the effect's SPIR-V 1.3 needs Vulkan 1.1");
  if (!e.features.shaderStorageImageExtendedFormats)
    return Status::error(StatusCode::DriverError,
                         "the device lacks shaderStorageImageExtendedFormats (rg32f / r16f storage images)");
  // Supported is not enabled: the device must have been created with each feature the effect uses.
  if (!context.enabledFeatures)
    return Status::error(StatusCode::InvalidInput,
                         "DeviceContext::enabledFeatures is null: pass the VkPhysicalDeviceFeatures enabled at "
                         "vkCreateDevice (the effect needs shaderStorageImageExtendedFormats)");
  if (!context.enabledFeatures->shaderStorageImageExtendedFormats)
    return Status::error(StatusCode::DriverError,
                         "the device was created without the feature shaderStorageImageExtendedFormats (rg32f / "
                         "r16f storage images): enable it in VkDeviceCreateInfo");
  e.ctx.enabledFeatures = nullptr;  // the caller's pointer is read here only

  if (Status st = checkConfig(e, config); !st) return st;
  e.config = config;
  e.allocator.init(&e.d, context.device, e.memoryProps, e.props.limits.bufferImageGranularity, context.allocator);
  if (Status st = createSampler(e); !st) return st;
  if (Status st = createParamBuffer(e, config.framesInFlight, e.ubo); !st) return st;
  if (Status st = createQueryPool(e, config.framesInFlight, e.queryPool); !st) return st;
  return Status::success();  // the first record() plans (core's FrameState through the executor)
}

}  // namespace

Status Effect::create(const DeviceContext& context, const Config& config, std::unique_ptr<Effect>& out,
                      int headerVersion) {
  out.reset();
  return guarded("sao::vk::Effect::create()", [&] {
    if (headerVersion != SAO_VERSION)
      return Status::error(StatusCode::VersionMismatch, "sao::vk::Effect::create(): the header is version " +
                                                            versionText(headerVersion) + " but the library is " +
                                                            versionText(SAO_VERSION) + "; rebuild against one version");
    auto impl = std::make_unique<Impl>();
    if (Status st = createEffect(context, config, *impl); !st) return st;
    out.reset(new Effect(std::move(impl)));
    return Status::success();
  });
}

// These allocate nothing and cannot fail.
const Config& Effect::config() const { return impl_->config; }
const Plan& Effect::plan() const { return impl_->frame.plan(); }
const ParamBlock& Effect::params() const { return impl_->frame.block(); }
MemoryStats Effect::memoryStats() const { return impl_->allocator.stats(); }
std::uint64_t Effect::outputGeneration() const { return impl_->outputGeneration; }
std::uint32_t Effect::pipelineCount() const { return static_cast<std::uint32_t>(impl_->pipelines.size()); }
std::uint64_t Effect::plans() const { return impl_->frame.plans(); }

OutputImage Effect::output() const {
  const OwnedImage* ao = impl_->res.find(gen::ResourceId::ao);
  if (!ao) return {};
  return {ao->image.get(), ao->levelViews[0].get(), ao->format, ao->planned.extent, impl_->config.outputLayout, 0};
}

OwnedImageInfo Effect::ownedImage(gen::ResourceId id) const {
  const OwnedImage* img = impl_->res.find(id);
  if (!img) return {};
  const bool isOutput = id == gen::ResourceId::ao;
  return {img->image.get(), img->format, img->planned.extent, img->planned.mipLevels,
          isOutput ? impl_->config.outputLayout : VK_IMAGE_LAYOUT_GENERAL};
}

}  // namespace sao::vk
