// The Vulkan path: a real Vulkan window on the project's Vulkan bootstrap (sao::vk::headless with
// a window surface). Each frame, in one command buffer: samples/prepass records the scene's depth
// into a D32_SFLOAT image, sao::vk::Effect::record adds the effect's compute passes, and a render
// pass on the acquired swapchain image runs the composite and ImGui (imgui_impl_vulkan); the
// image is presented with vkQueuePresentKHR. One frame in flight: the frame's fence is waited
// before the next one is recorded.
#define GLFW_INCLUDE_VULKAN  // glfwCreateWindowSurface
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <cstdio>

#include "backend.h"
#include "sao/prepass/vk_prepass.h"
#include "sao/vulkan/effect.h"
#include "sao/vulkan/headless.h"
#include "screenshot.h"
#include "vk_composite.h"
#include "vk_swapchain.h"

namespace sao::viewer {
namespace {

// The device side of an effect for a frame: the owned output read by the composite's fragment
// shader, one frame in flight, and the timing choice. The settings, the camera and the depth go to
// each record(), which plans again only when they change the plan.
vk::Config effectConfig(const FrameDesc& frame) {
  vk::Config c;
  c.outputLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  c.framesInFlight = 1;
  c.timestamps = frame.measureTime;
  return c;
}

// A new effect where there is none or its Config is not the frame's (timestamps turned on or off:
// the only Config member that changes). Called after the previous frame's fence: nothing recorded
// by the old effect is pending when it is destroyed.
Status keepEffect(vk::headless::Context& ctx, const FrameDesc& frame, std::unique_ptr<vk::Effect>& effect) {
  const vk::Config c = effectConfig(frame);
  if (effect && effect->config().timestamps == c.timestamps) return Status::success();
  effect.reset();
  return vk::Effect::create(ctx.deviceContext(), c, effect);
}

// The split-resolution view's second effect: the same depth and camera at the other divisor,
// created when the mode comes on and destroyed when it goes (other modes pay nothing).
struct CompareEffect {
  std::unique_ptr<vk::Effect> effect;
  bool pendingTimings = false;
  Status status;
  Timings timings;
  std::string timingNote;
};

// The instance, the window's surface and a device that presents to it and runs graphics and
// compute on one queue; --validation adds the layer with synchronization validation.
Status createContext(GLFWwindow* window, bool validation, std::unique_ptr<vk::headless::Context>& out) {
  vk::headless::Options o;
  o.validation = o.synchronizationValidation = validation;
  o.applicationName = "sao-viewer";
  std::uint32_t count = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&count);
  if (!extensions) return Status::error(StatusCode::DriverError, "GLFW cannot present with Vulkan on this system");
  o.instanceExtensions.assign(extensions, extensions + count);
  o.createSurface = [window](VkInstance instance, VkSurfaceKHR* surface) {
    return glfwCreateWindowSurface(instance, window, nullptr, surface);
  };
  return vk::headless::Context::create(o, out);
}

class VkBackend final : public Backend {
 public:
  VkBackend(Window& window, const BackendOptions& options) : window_(window), options_(options) {}
  ~VkBackend() override;
  Status init();

  std::string description() const override {
    return "Vulkan: " + ctx_->description() +
           "; presents through a VK_KHR_swapchain; depth: D32_SFLOAT reversed-Z, [0,1], infinite far (orthographic: a "
           "far plane just beyond the scene)";
  }
  ClipDepth clipDepth() const override { return ClipDepth::ZeroToOne; }
  bool reversedZ() const override { return true; }
  std::size_t validationErrors() const override;
  Status setMesh(const scenes::Mesh& mesh) override {
    vkDeviceWaitIdle(ctx_->device());
    return prepass_->setMesh(mesh);
  }
  Status setReference(const FloatImage* reference) override {
    vkDeviceWaitIdle(ctx_->device());
    return composite_.setReference(reference);
  }
  void newImGuiFrame() override {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
  }
  Status renderFrame(const FrameDesc& frame, FrameStats& stats) override;
  Status readAo(FloatImage& out) override;

 private:
  Status initImGui();
  void updateEffect(const FrameDesc& frame, FrameStats& stats);
  void updateCompare(const FrameDesc& frame);
  Status refreshEffectViews();
  void readTimings(const FrameDesc& frame);
  Status createEffectViews();
  void destroyEffectViews();
  void recordScreenshot(VkCommandBuffer cmd, VkImage image);

  Window& window_;
  BackendOptions options_;
  std::unique_ptr<vk::headless::Context> ctx_;
  VkSwapchain swapchain_;
  std::unique_ptr<prepass::VkPrepass> prepass_;
  VkComposite composite_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  VkDescriptorPool imguiPool_ = VK_NULL_HANDLE;
  bool imgui_ = false, recreate_ = false, pendingTimings_ = false;
  std::unique_ptr<vk::Effect> effect_;
  bool rendered_ = false;  // effect_'s last record() succeeded: its output holds the last frame's AO
  VkImageView aoRawView_ = VK_NULL_HANDLE, cszView_ = VK_NULL_HANDLE;
  std::uint32_t cszLevels_ = 0;
  std::uint64_t viewsPlan_ = 0;  // effect_->plans() when the views were made (0: none)
  vk::headless::Buffer shot_;
  Timings lastTimings_;
  std::string timingNote_;
  CompareEffect compare_;
  mutable std::size_t validationMessages_ = 0;  // warnings and errors, the first 20 printed
};

std::size_t VkBackend::validationErrors() const {
  if (!ctx_) return 0;
  for (const vk::headless::Message& m : ctx_->takeMessages()) {
    if (m.severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) continue;
    if (++validationMessages_ <= 20)
      std::fprintf(stderr, "sao-viewer: validation %s: %s\n",
                   m.severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning", m.text.c_str());
  }
  return validationMessages_;
}

VkBackend::~VkBackend() {
  if (!ctx_) return;
  vkDeviceWaitIdle(ctx_->device());
  if (imgui_) {
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
  }
  destroyEffectViews();
  compare_ = {};
  effect_.reset();
  composite_.destroy();
  prepass_.reset();
  swapchain_.destroy();
  ctx_->destroy(shot_);
  VkDevice d = ctx_->device();
  if (imguiPool_) vkDestroyDescriptorPool(d, imguiPool_, nullptr);
  if (fence_) vkDestroyFence(d, fence_, nullptr);
  if (acquired_) vkDestroySemaphore(d, acquired_, nullptr);
}

Status VkBackend::init() {
  if (Status s = createContext(window_.handle(), options_.validation, ctx_); !s) return s;
  const glm::ivec2 fb = window_.framebufferSize();
  if (Status s = swapchain_.create(*ctx_, std::uint32_t(fb.x), std::uint32_t(fb.y), options_.vsync); !s) return s;
  if (Status s = prepass::VkPrepass::create(*ctx_, prepass_); !s) return s;
  if (Status s = composite_.init(*ctx_, swapchain_.renderPass); !s) return s;
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = ctx_->commandPool();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  SAO_VIEWER_VK(vkAllocateCommandBuffers(ctx_->device(), &ai, &cmd_));
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  SAO_VIEWER_VK(vkCreateFence(ctx_->device(), &fi, nullptr, &fence_));
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  SAO_VIEWER_VK(vkCreateSemaphore(ctx_->device(), &si, nullptr, &acquired_));
  return initImGui();
}

Status VkBackend::initImGui() {
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pi.maxSets = 16;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = &size;
  SAO_VIEWER_VK(vkCreateDescriptorPool(ctx_->device(), &pi, nullptr, &imguiPool_));
  if (!ImGui_ImplGlfw_InitForVulkan(window_.handle(), true))
    return Status::error(StatusCode::DriverError, "cannot initialise ImGui's GLFW backend");
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = ctx_->instance();
  info.PhysicalDevice = ctx_->physicalDevice();
  info.Device = ctx_->device();
  info.QueueFamily = ctx_->queueFamily();
  info.Queue = ctx_->queue();
  info.DescriptorPool = imguiPool_;
  info.MinImageCount = swapchain_.minImageCount;
  info.ImageCount = std::uint32_t(swapchain_.images.size());
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  if (!ImGui_ImplVulkan_Init(&info, swapchain_.renderPass)) {
    ImGui_ImplGlfw_Shutdown();
    return Status::error(StatusCode::DriverError, "cannot initialise ImGui's Vulkan backend");
  }
  imgui_ = true;
  Status s = ctx_->submit([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  return s;
}

void VkBackend::destroyEffectViews() {
  for (VkImageView* v : {&aoRawView_, &cszView_})
    if (*v) {
      vkDestroyImageView(ctx_->device(), *v, nullptr);
      *v = VK_NULL_HANDLE;
    }
  cszLevels_ = 0;
  viewsPlan_ = 0;
}

// The composite reads ao_raw and every csz level through views of the effect's own images.
Status VkBackend::createEffectViews() {
  for (auto [id, view] : {std::pair{gen::ResourceId::ao_raw, &aoRawView_}, std::pair{gen::ResourceId::csz, &cszView_}}) {
    const vk::OwnedImageInfo info = effect_->ownedImage(id);
    if (!info.image) continue;
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = info.image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = info.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, info.mipLevels, 0, 1};
    SAO_VIEWER_VK(vkCreateImageView(ctx_->device(), &vi, nullptr, view));
    if (id == gen::ResourceId::csz) cszLevels_ = info.mipLevels;
  }
  return Status::success();
}

// A new effect when the timing choice changed (or the last create failed); the settings and the
// camera need nothing here: each record() takes them.
void VkBackend::updateEffect(const FrameDesc& frame, FrameStats& stats) {
  if (effect_ && effect_->config().timestamps == frame.measureTime) return;
  destroyEffectViews();  // views of the old effect's images, which the composite no longer reads
  rendered_ = false;
  stats.effect = keepEffect(*ctx_, frame, effect_);
}

// After a record() that planned again (a resize, a new projection, other settings), the views the
// composite reads of ao_raw and csz are made again: the new plan may have new images. The old
// plan's images live until the next record() (one frame in flight), after the previous frame's
// composite has completed.
Status VkBackend::refreshEffectViews() {
  if (effect_->plans() == viewsPlan_) return Status::success();
  destroyEffectViews();
  if (Status s = createEffectViews(); !s) return s;
  viewsPlan_ = effect_->plans();
  return Status::success();
}

// After the previous frame's fence: nothing recorded by the second effect is pending.
void VkBackend::updateCompare(const FrameDesc& frame) {
  if (frame.mode != ViewMode::SplitResolution) {
    compare_ = {};
    return;
  }
  if (compare_.effect && compare_.effect->config().timestamps == frame.measureTime) return;
  compare_.pendingTimings = false;
  compare_.status = keepEffect(*ctx_, frame, compare_.effect);
}

// The previous frame has completed: its timestamps are readable.
void VkBackend::readTimings(const FrameDesc& frame) {
  auto read = [](const vk::Effect& effect, Timings& timings, std::string& note) {
    Timings t;
    if (Status s = effect.timings(t); s) timings = t, note.clear();
    else timings = {}, note = s.message;
  };
  if (pendingTimings_) read(*effect_, lastTimings_, timingNote_);
  if (compare_.pendingTimings) read(*compare_.effect, compare_.timings, compare_.timingNote);
  pendingTimings_ = compare_.pendingTimings = false;
  if (!frame.measureTime) {
    lastTimings_ = compare_.timings = {};
    timingNote_.clear();
    compare_.timingNote.clear();
  }
}

void VkBackend::recordScreenshot(VkCommandBuffer cmd, VkImage image) {
  auto b = vk::headless::imageBarrier(image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                             VK_ACCESS_TRANSFER_READ_BIT);
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &b);
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {swapchain_.extent.width, swapchain_.extent.height, 1};
  vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shot_.buffer, 1, &copy);
  b = vk::headless::imageBarrier(image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                        VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, 0, 0);
  VkBufferMemoryBarrier hb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
  hb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  hb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  hb.srcQueueFamilyIndex = hb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  hb.buffer = shot_.buffer;
  hb.size = VK_WHOLE_SIZE;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &hb, 1, &b);
}

Status VkBackend::renderFrame(const FrameDesc& frame, FrameStats& stats) {
  validationErrors();  // prints what the last frame drew, as it comes
  VkDevice d = ctx_->device();
  SAO_VIEWER_VK(vkWaitForFences(d, 1, &fence_, VK_TRUE, UINT64_MAX));
  readTimings(frame);
  const glm::ivec2 fb = window_.framebufferSize();
  if (recreate_ || swapchain_.extent.width != std::uint32_t(fb.x) || swapchain_.extent.height != std::uint32_t(fb.y)) {
    vkDeviceWaitIdle(d);
    if (Status s = swapchain_.create(*ctx_, std::uint32_t(fb.x), std::uint32_t(fb.y), options_.vsync); !s) return s;
    ImGui_ImplVulkan_SetMinImageCount(swapchain_.minImageCount);
    recreate_ = false;
  }
  updateEffect(frame, stats);
  updateCompare(frame);
  const bool screenshot = !frame.screenshotPath.empty() && swapchain_.transferSrc;
  const VkDeviceSize shotBytes = VkDeviceSize(swapchain_.extent.width) * swapchain_.extent.height * 4;
  if (screenshot && shot_.size != shotBytes) {
    ctx_->destroy(shot_);
    if (Status s = ctx_->createBuffer(shotBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, shot_); !s) return s;
  }

  std::uint32_t imageIndex = 0;
  VkResult r = vkAcquireNextImageKHR(d, swapchain_.handle, UINT64_MAX, acquired_, VK_NULL_HANDLE, &imageIndex);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) {
    recreate_ = true;
    return Status::success();  // skip this frame
  }
  SAO_VIEWER_VK(r);

  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  SAO_VIEWER_VK(vkResetCommandBuffer(cmd_, 0));
  SAO_VIEWER_VK(vkBeginCommandBuffer(cmd_, &bi));
  // The previous frame's composite read the effect's intermediates: order before their rewrite.
  vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr,
                       0, nullptr, 0, nullptr);
  Camera depthCamera = frame.camera;
  depthCamera.metersToViewUnits = 1;  // the mesh and the view are in the scene's units already
  vk::headless::Image depth;
  if (Status s = prepass_->record(cmd_, frame.view, depthCamera, DepthFormat::D32F, depth); !s) return s;
  // The effect's input: the prepass's depth, of the camera's extent (viewport + guard band).
  vk::Inputs in;
  in.depth = {depth.view, depth.layout, depth.extent, depth.format};
  in.frameIndex = frame.frameIndex;
  bool recorded = false;
  if (effect_) {  // this frame's camera (its pose too) and the panel's settings
    stats.effect = effect_->record(cmd_, frame.camera, frame.settings, in);
    recorded = rendered_ = stats.effect.ok();
    if (recorded)
      if (Status s = refreshEffectViews(); !s) return s;
  }
  bool compared = false;  // the second effect reads the same depth (read-read: no barrier)
  if (compare_.effect) {
    compare_.status = compare_.effect->record(cmd_, frame.camera, compareSettings(frame.settings), in);
    compared = compare_.status.ok();
  }
  // ao_raw and csz are read by the composite too (the effect's final barrier covers its output).
  VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  mb.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  mb.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 1, &mb, 0,
                       nullptr, 0, nullptr);
  VkCompositeInputs inputs;
  inputs.depth = depth.view;
  if (recorded) {
    inputs.ao = effect_->output().view;
    inputs.aoRaw = aoRawView_;
    inputs.csz = cszView_;
  }
  if (frame.mode == ViewMode::SplitResolution) {  // left the divisor-1 AO, right the reduced one
    const VkImageView other = compared ? compare_.effect->output().view : VK_NULL_HANDLE;
    const bool mainIsFull = frame.settings.resolution_divisor == 1;
    inputs.aoReduced = mainIsFull ? other : inputs.ao;
    inputs.ao = mainIsFull ? inputs.ao : other;
  }
  composite_.setInputs(inputs);  // before the set is bound in this command buffer

  VkClearValue clear{};
  VkRenderPassBeginInfo rb{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rb.renderPass = swapchain_.renderPass;
  rb.framebuffer = swapchain_.framebuffers[imageIndex];
  rb.renderArea = {{0, 0}, swapchain_.extent};
  rb.clearValueCount = 1;
  rb.pClearValues = &clear;
  vkCmdBeginRenderPass(cmd_, &rb, VK_SUBPASS_CONTENTS_INLINE);
  composite_.record(cmd_, makeCompositeParams(frame, true, recorded && aoRawView_, recorded ? cszLevels_ : 0),
                    swapchain_.extent);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd_);
  vkCmdEndRenderPass(cmd_);
  if (screenshot) recordScreenshot(cmd_, swapchain_.images[imageIndex]);
  SAO_VIEWER_VK(vkEndCommandBuffer(cmd_));

  const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &acquired_;
  si.pWaitDstStageMask = &waitStage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &swapchain_.renderFinished[imageIndex];
  SAO_VIEWER_VK(vkResetFences(d, 1, &fence_));
  SAO_VIEWER_VK(vkQueueSubmit(ctx_->queue(), 1, &si, fence_));
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &swapchain_.renderFinished[imageIndex];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_.handle;
  pi.pImageIndices = &imageIndex;
  r = vkQueuePresentKHR(ctx_->queue(), &pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) recreate_ = true;
  else SAO_VIEWER_VK(r);

  pendingTimings_ = recorded && effect_->config().timestamps;
  compare_.pendingTimings = compared && compare_.effect->config().timestamps;
  stats.compare = {};
  if (frame.mode == ViewMode::SplitResolution)
    stats.compare = {true, compare_.status, compare_.timings, compare_.timingNote};
  if (effect_ && effect_->plans() > 0) stats.plan = effect_->plan();
  stats.timings = lastTimings_;
  stats.timingNote = timingNote_;
  if (!frame.screenshotPath.empty()) {
    if (!swapchain_.transferSrc)
      return Status::error(StatusCode::UnsupportedFormat, "the swapchain images cannot be copied (no TRANSFER_SRC usage)");
    SAO_VIEWER_VK(vkWaitForFences(d, 1, &fence_, VK_TRUE, UINT64_MAX));
    return writeScreenshot(frame.screenshotPath, int(swapchain_.extent.width), int(swapchain_.extent.height),
                           static_cast<const std::uint8_t*>(shot_.mapped), {.bottomUp = false, .bgra = swapchain_.bgra});
  }
  return Status::success();
}

Status VkBackend::readAo(FloatImage& out) {
  if (!effect_ || !rendered_) return Status::error(StatusCode::InvalidInput, "no AO rendered yet");
  SAO_VIEWER_VK(vkWaitForFences(ctx_->device(), 1, &fence_, VK_TRUE, UINT64_MAX));
  const vk::OutputImage ao = effect_->output();
  return ctx_->readback(ao.image, ao.format, ao.extent, 0, ao.layout,
                        VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                        VK_ACCESS_SHADER_WRITE_BIT, out);
}

}  // namespace

Status createVulkanBackend(Window& window, const BackendOptions& options, std::unique_ptr<Backend>& out) {
  auto backend = std::make_unique<VkBackend>(window, options);
  if (Status s = backend->init(); !s) return s;
  out = std::move(backend);
  return Status::success();
}

}  // namespace sao::viewer
