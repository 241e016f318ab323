// sao::vk — the Vulkan backend: the effect recorded into your command buffer.
//
// Everything goes through the vkGetInstanceProcAddr / vkGetDeviceProcAddr you pass in: the
// library exports no vk* symbol and does not link the Vulkan loader. The compute pipelines come
// from the SPIR-V embedded at build time (SPIR-V 1.3, Vulkan 1.1), one per pass variant the plan
// needs; images and memory come from plan() through a small allocator of the library's own.
//
//   sao::vk::DeviceContext ctx{instance, physicalDevice, device, vkGetInstanceProcAddr,
//                              vkGetDeviceProcAddr, queueFamily};
//   ctx.enabledFeatures = &enabledFeatures;  // what you passed to vkCreateDevice
//   std::unique_ptr<sao::vk::Effect> effect;
//   sao::Status st = sao::vk::Effect::create(ctx, {}, effect);  // Config: ring size, output layout, ...
//   ...
//   sao::vk::Inputs in;
//   in.depth = {depthView, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, {w, h}, VK_FORMAT_D32_SFLOAT};
//   st = effect->record(cmd, camera, settings, in);  // each frame, as sao::gl::Effect::render()
//   sao::vk::OutputImage ao = effect->output();  // Config::outputFormat (R16_SFLOAT), in config.outputLayout
//
// record(cmd, camera, settings, inputs[, output]) is the GL backend's shape: any of them may change
// from one frame to the next, and a change that needs a new plan is made within the call (no
// wait). Config holds only what the device side fixes for the effect's life (create()).
//
// Stereo (VR: two eyes in array layers of one depth image): one effect, recorded once per eye into
// the same command buffer. Make a VK_IMAGE_VIEW_TYPE_2D view per layer of your depth (and normals)
// array and of your output array (your output: the effect's own has one layer), give each record
// its eye's views, OutputImage::layer = the eye and the eye's camera (one that plans as the other
// eye's does records without a new plan: a mirrored off-axis eye projection does). The pipelines and
// the intermediate images are shared by the eyes (one set of memory, not two); the second record's
// barriers order it after the first. Each record takes a ring slot: see framesInFlight below.
//
// Requirements on your device: Vulkan 1.1 or later, the feature shaderStorageImageExtendedFormats
// enabled (the (A, key) intermediates are rg16f or rg32f storage images, the output r16f by default; tell create() through
// DeviceContext::enabledFeatures), and a queue family with compute. create() checks each and names
// the one missing. Command buffers recorded by record() must be submitted to a queue of the family named
// in DeviceContext::queueFamilyIndex (one queue: the effect's own images are reused every frame
// and ordered by pipeline barriers in submission order).
//
// Synchronisation contract (checked by the tests under synchronization validation):
//  * Inputs (depth, depth2, normals): you make your writes available and visible to
//    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT / VK_ACCESS_SHADER_READ_BIT and put the image in the
//    layout you name in InputImage::layout before the recorded commands run. The effect never
//    transitions or writes your inputs; before writing them again, wait for the compute stage.
//  * Output: record() discards the output's previous contents (a transition from UNDEFINED after
//    Config::outputDstStages of earlier commands) unless Inputs::outputChannels keeps some of its
//    channels: then it transitions your image from OutputImage::layout (the layout it is in when
//    the commands run) and you make your writes to it available and visible to
//    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT / SHADER_READ_BIT, as for inputs. It writes the output in VK_IMAGE_LAYOUT_GENERAL and leaves
//    it in Config::outputLayout (GENERAL or SHADER_READ_ONLY_OPTIMAL), made visible to
//    Config::outputDstStages / outputDstAccess. Earlier accesses of your own output image in other
//    stages must be ordered before outputDstStages by you.
//  * Effect-owned intermediates stay in VK_IMAGE_LAYOUT_GENERAL after record().
//  * Frames in flight: record() uses the next of Config::framesInFlight ring slots, each with its
//    own descriptor sets and its own copy of the parameter block (gen::SaoParams memcpy'd as is
//    into host-coherent memory, made visible by vkQueueSubmit). framesInFlight counts record()
//    calls, not frames: at most framesInFlight record() (and measure()) calls of one Effect may be
//    pending (recorded, their command buffer not completed) at a time, whether they share a command
//    buffer or not, since every record() rewrites its slot's descriptor sets (a destroyed view's
//    handle value can come back for a new view, so handles cannot tell a set is still valid). A
//    stereo frame records twice: 2 frames in flight x 2 eyes needs framesInFlight = 4. The effect's
//    images are shared by all slots; the barriers order them in submission order on the one queue.
//  * Per-record camera: record()'s camera (a jittered projection, another field of view, a new view
//    rotation) is written into the record's own slot of the parameter block, so the frames in
//    flight each keep their camera: no wait. A camera that changes the plan (size, guard band, csz
//    levels) plans again within the call, what pending records use kept until they complete.
//  * The destructor must not run while a command buffer recorded by the effect is pending (wait
//    for its fence, or vkDeviceWaitIdle).
#pragma once
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <memory>

#include "sao/camera.h"
#include "sao/constants.h"
#include "sao/image.h"
#include "sao/output.h"
#include "sao/plan.h"
#include "sao/presets.h"  // presetSettings(): what every integration starts from
#include "sao/settings.h"
#include "sao/status.h"
#include "sao/timing.h"
#include "sao/version.h"

#if defined(_WIN32)
#define SAO_VK_API
#else
#define SAO_VK_API __attribute__((visibility("default")))
#endif

namespace sao::vk {

// Your Vulkan objects. The effect keeps the handles, never destroys them.
struct DeviceContext {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;  // required
  PFN_vkGetDeviceProcAddr getDeviceProcAddr = nullptr;      // optional: taken from getInstanceProcAddr
  std::uint32_t queueFamilyIndex = 0;                       // where the recorded commands are submitted
  VkPipelineCache pipelineCache = VK_NULL_HANDLE;           // optional, used for every pipeline
  const VkAllocationCallbacks* allocator = nullptr;         // optional, used for every object
  // Set when the instance enabled VK_EXT_debug_utils: each pass is recorded inside a
  // vkCmdBeginDebugUtilsLabelEXT / End pair named "sao <pass>" (for captures and validation).
  bool debugUtilsEnabled = false;
  // Required: the features you enabled at vkCreateDevice (VkDeviceCreateInfo::pEnabledFeatures, or
  // VkPhysicalDeviceFeatures2::features in its pNext chain), read by create() only. Vulkan cannot
  // be asked what a VkDevice enabled, so create() refuses (InvalidInput) without it and refuses a
  // device without a feature the effect needs (DriverError naming it).
  const VkPhysicalDeviceFeatures* enabledFeatures = nullptr;
};

// What the device side fixes for the effect's life: where the output goes, the ring, timestamps.
// Everything else comes with each record() (settings, camera, inputs and their formats, output).
struct Config {
  // The effect-owned output's format (when record() gets no output of yours): VK_FORMAT_R16_SFLOAT
  // (the default), R8_UNORM, R8G8B8A8_UNORM or R16G16B16A16_SFLOAT, with optimal-tiling storage
  // support on the device (sao/output.h says how each rounds A). Another is refused with
  // UnsupportedFormat naming it and this list.
  VkFormat outputFormat = VK_FORMAT_R16_SFLOAT;
  // Layout of the output after record(): VK_IMAGE_LAYOUT_GENERAL or SHADER_READ_ONLY_OPTIMAL.
  VkImageLayout outputLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  // Where you read the output afterwards (the final barrier's destination scope). On a queue family
  // without graphics, leave out the graphics stages (create() says so otherwise).
  VkPipelineStageFlags outputDstStages = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  VkAccessFlags outputDstAccess = VK_ACCESS_SHADER_READ_BIT;
  // Ring size, 1..16: record() calls that may be pending at once (the contract above; stereo: x 2).
  std::uint32_t framesInFlight = 2;
  bool timestamps = false;  // record() writes per-pass timestamps where the queue family has them
};

// One of your sampled inputs: a view of one mip level, in `layout` (SHADER_READ_ONLY_OPTIMAL,
// DEPTH_STENCIL_READ_ONLY_OPTIMAL, DEPTH_READ_ONLY_OPTIMAL, DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL,
// READ_ONLY_OPTIMAL or GENERAL), created with VK_IMAGE_USAGE_SAMPLED_BIT. `extent` is the view's
// size (a view cannot tell it): it must be plan().inputExtent (viewport + 2 * guard band) or, with
// Inputs::region, hold it from there on, and not exceed maxImageDimension2D.
struct InputImage {
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  Extent extent;  // the whole level the view shows
  // Required with a view: the view's format (a view cannot tell it either), one the input accepts
  // (below), sampled with optimal tiling on the device.
  VkFormat format = VK_FORMAT_UNDEFINED;
  // The image's samples. Only the depth may be multisampled: it is read directly, no resolve pass;
  // linear_z keeps one sample per texel as Camera::depthSamplePolicy says (sample 0, or the one
  // nearest to the camera). Refused: a count that is not one VkSampleCountFlagBits, one the device
  // cannot sample for the format (sampledImageDepthSampleCounts, or sampledImageColorSampleCounts
  // for R32_SFLOAT), and more than one with depth2. A view cannot tell its count either: one that
  // differs from this is reported by the validation layer, not by the library.
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
};

// The inputs are the effect's kind=input resources (effect/sao.glsl), one InputImage each, by name
// (inputs.depth, inputs.normals, ...) or by id (inputs[gen::ResourceId::normals]); the views given
// select the plan's variants. What each accepts (sao/inputs.h, one contract on every backend):
//  * depth (required) and depth2 (a second layer, the deep G-buffer, the same format):
//    VK_FORMAT_D16_UNORM, X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT, D32_SFLOAT, D32_SFLOAT_S8_UINT
//    (hardware depth per the camera's conventions; views of the combined formats select
//    VK_IMAGE_ASPECT_DEPTH_BIT only) or VK_FORMAT_R32_SFLOAT (linear camera-space z). Depth values
//    (sao/image.h): hardware depth that is NaN, +-Inf, below 0 or above 1 (possible in D32_SFLOAT
//    with VK_EXT_depth_range_unrestricted or a buffer copy) is read as sky, like the clear value,
//    bit for bit as on the other backends; -0.0 is 0. The depth is not scanned.
//  * an input whose declaration lists formats= (motion, with the temporal setting:
//    VK_FORMAT_R16G16_SFLOAT recommended, R32G32_SFLOAT, R16G16B16A16_SFLOAT or
//    R32G32B32A32_SFLOAT; .xy the offset in pixels from each texel to where its surface was in the
//    previous frame, previous = current + motion, in the depth's row order): one of those.
//  * any other (normals, as Camera::normalsEncoding says: camera-space .xyz by default, components
//    in [-1,1]; world space and octahedral .xy too): any sampled colour format with the channels
//    read, three or more for the xyz encodings (e.g. R16G16B16A16_SFLOAT), two or more for the
//    octahedral ones (e.g. R16G16_SFLOAT); fewer is refused (UnsupportedFormat naming the format and
//    the encoding): a missing channel would read 0.
struct Inputs : gen::InputSet<InputImage> {
  // Optional: where the region of plan().inputExtent texels starts in depth, depth2 and normals
  // (they share it): the texel (x along a row, y in rows from row 0) holding the guard band's first
  // corner. With it the images may be larger (dynamic resolution: the viewport inside a bigger
  // depth buffer); the region is read in place, no copy. Unset, every input must be exactly
  // plan().inputExtent. Changing it does not plan again. A region that does not lie
  // inside every image given is refused (InvalidInput naming the offset, the extent and the
  // image's size), never clamped.
  std::optional<Offset> region{};
  // The frame's number, for an engine that accumulates frames (TAA or its own temporal filter):
  // frame k turns and shifts every pixel's spiral (sao::frameSpiral, sao/spiral.h), so N
  // consecutive frames sample the disk evenly; frame 0 (the default) is the paper's spiral. Count
  // it up by one per frame. Per record, in the ring slot's block.
  std::uint32_t frameIndex = 0;
  // Temporal accumulation (the temporal setting; sao/temporal.h says when the history is reused):
  // the effect keeps two history images and the camera of its last record, and blends each pixel's obscurance with that frame's, reprojected through
  // Camera::view (required then). Records are frames in submission order: submit every record, in
  // the order you made them (a record that is never submitted leaves the next frame a history that
  // was never written; start again with resetHistory). resetHistory: start again from this frame
  // alone (a camera cut). previousCamera: the camera the history was made with, when not the last
  // record's (null: that one). Without the temporal setting both are ignored. A new plan starts
  // the history again. The history follows one view: give each eye of a stereo pair its own
  // effect. Per record: no allocation, no wait.
  bool resetHistory = false;
  const Camera* previousCamera = nullptr;
  // Which channels of the output receive A (sao/output.h), as sao::gl::Inputs::outputChannels:
  // kAllChannels (every channel the format has) or a non-empty set of kChannelR/G/B/A it has. With
  // an RGBA format and a mask that leaves channels out, the effect keeps them: record() reads your
  // image's texels and stores them back with only these channels replaced, so the contents must be
  // defined and visible (see the synchronisation contract: OutputImage::layout). Only with your
  // output. Per record: no new plan.
  std::uint32_t outputChannels = kAllChannels;
  // How those channels take A (sao/output.h): Replace (the default), or Multiply: each texel's
  // channel is multiplied by A, the apply step in the effect's final pass (e.g. your lit
  // R16G16B16A16_SFLOAT colour target with outputChannels = kChannelR | kChannelG | kChannelB). Only
  // with your output; like a mask that keeps channels, record() reads the texels, so the contents
  // must be defined and visible (OutputImage::layout). Per record: no new plan.
  OutputBlend outputBlend = OutputBlend::Replace;
};

// The output: yours (its format one of Config::outputFormat's list) or the effect's (in
// Config::outputFormat), the viewport's extent (plan().aoExtent), one level, usage
// STORAGE (plus whatever you read it with). As returned by Effect::output(), `layout` is where
// record() leaves it. Passed to record() with an Inputs::outputChannels that keeps channels (or the multiply blend),
// `layout` is the layout your image is in when the recorded commands run (not UNDEFINED or
// PREINITIALIZED: its texels are kept); otherwise it is not read.
struct OutputImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;  // a single-level colour view (VK_IMAGE_VIEW_TYPE_2D)
  VkFormat format = VK_FORMAT_R16_SFLOAT;  // selects the final pass's pipelines
  Extent extent;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  // The array layer `view` shows, for an output array image (stereo / multiview: one layer per
  // eye); record()'s barriers on your image cover this layer only, its other layers are left alone.
  // A view cannot tell its layer, so it must match the view's baseArrayLayer: the library cannot
  // check it (refused only beyond maxImageArrayLayers); a wrong one is reported by the validation
  // layer. 0 for a single-layer image and for Effect::output().
  std::uint32_t layer = 0;
};

// An effect-owned image (for debugging and tests): VK_IMAGE_LAYOUT_GENERAL after record(), usage
// includes TRANSFER_SRC. `image` is VK_NULL_HANDLE when the plan has no such image.
struct OwnedImageInfo {
  VkImage image = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  Extent extent;  // level 0
  std::uint32_t mipLevels = 0;
  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};

// Device memory held through the library's allocator.
struct MemoryStats {
  std::uint64_t liveAllocations = 0;  // VkDeviceMemory objects alive
  std::uint64_t liveBytes = 0;
  std::uint64_t totalAllocations = 0;  // ever made
};

// Every effect of the process together.
SAO_VK_API MemoryStats processMemoryStats();

enum class MeasureMethod {
  Auto,        // timestamps where the queue family has them, else the fence fallback
  FenceClock,  // one submission per pass, a fence wait and a steady clock around each
};

// No exception leaves an Effect: every failure, running out of host memory (std::bad_alloc)
// included, comes back as a Status (DriverError naming the call), and the accessors and the
// destructor cannot fail.
class SAO_VK_API Effect {
 public:
  // Checks the version (VersionMismatch when the header you compiled against differs from the
  // library), loads the functions, validates config against the device (features, the output's
  // format and stages) and makes the parameter buffer and sampler; the first record() plans. On
  // error `out` is reset and the Status says what is wrong; nothing is left allocated.
  static Status create(const DeviceContext& context, const Config& config, std::unique_ptr<Effect>& out,
                       int headerVersion = SAO_VERSION);
  ~Effect();
  Effect(const Effect&) = delete;
  Effect& operator=(const Effect&) = delete;

  // The per-frame call, sao::gl::Effect::render()'s shape: this frame's camera, settings and inputs
  // (with `userOutput` the caller's output; null: the effect's own, in Config::outputFormat) into
  // `cmd`, which must be in the recording state, outside a render pass, on a queue of
  // DeviceContext::queueFamilyIndex's family. The inputs given (their views) and their formats and
  // samples select the plan. The same settings and inputs with a camera that keeps the plan
  // (sao::cameraKeepsPlan) record at once, allocating nothing; anything else plans again here:
  // only the images whose format, extent or levels the new plan changes are made again
  // (sao::FrameState, sao/executor.h: one rule with the GL backend), pipelines only for variants
  // not built yet, and what the old plan alone used (images, descriptor sets) is destroyed only
  // once the Config::framesInFlight records after it have been made (the ring contract says they
  // are complete), so pending records are undisturbed and nothing waits. Planning again starts the
  // temporal history again, as on GL. On error nothing is recorded and the previous configuration
  // stays.
  Status record(VkCommandBuffer cmd, const Camera& camera, const Settings& settings, const Inputs& inputs,
                const OutputImage* userOutput = nullptr);

  // Per-pass times of the last record() with Config::timestamps, once its submission completed
  // (DriverError with "not ready" before), one entry per planned pass.
  Status timings(Timings& out) const;

  // Runs the frame record() would record once on `queue` (of the context's family), on its own
  // command buffers, and waits: per-pass times by timestamps (GpuTimestamps) or, where the family
  // has none or when asked, one fenced submission per pass timed by a steady clock
  // (FinishAndClock). Plans as record() does and uses the next ring slot like it.
  Status measure(VkQueue queue, const Camera& camera, const Settings& settings, const Inputs& inputs,
                 const OutputImage* userOutput, Timings& out, MeasureMethod method = MeasureMethod::Auto);

  // Whether record() can write timestamps on the context's queue family.
  bool timestampsSupported() const;

  const Config& config() const;
  const Plan& plan() const;
  // The parameter block of the last record() (as sao::gl::Effect::params()).
  const ParamBlock& params() const;
  // The effect-owned output (VK_NULL_HANDLE with userOutput); `layout` is where record() leaves it
  // (undefined contents before the first submitted record()).
  OutputImage output() const;
  // Counts the changes of the effect-owned output image: it goes up whenever a new plan makes a
  // new one (a resize, any change of the plan's images) or drops it (a record with your output).
  // Descriptors you wrote with output().view must be rewritten when it differs from the value you
  // saw last (handles can be reused, so comparing them cannot tell). 0 until the first plan with
  // the effect's own output; your own output never changes it.
  std::uint64_t outputGeneration() const;
  OwnedImageInfo ownedImage(gen::ResourceId id) const;
  MemoryStats memoryStats() const;  // this effect's device memory
  std::uint32_t pipelineCount() const;  // pipelines built so far (one per pass variant used)
  // Configurations planned so far: each record() or measure() that had to plan (GL: Stats::plans).
  std::uint64_t plans() const;

 private:
  struct Impl;  // the library's own
  explicit Effect(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// The VkFormat of the depth texels a DepthFormat describes (D16 -> D16_UNORM, D24 ->
// X8_D24_UNORM_PACK32, D32F -> D32_SFLOAT, LinearZ -> R32_SFLOAT).
SAO_VK_API VkFormat depthVkFormat(DepthFormat format);

}  // namespace sao::vk
