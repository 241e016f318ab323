// The harness's Vulkan half: sao::vk::Effect on the validated headless context of tests/vulkan,
// driven by its per-frame record(cmd, camera, settings, inputs[, output]) (GL's shape: it plans
// again within the call when it must), submitted and waited for.
#include "harness_apis.h"
#include "vk_formats.h"
#include "sao/frame.h"
#include "vk_array_image.h"
#include "vk_msaa_depth_writer.h"
#include "vk_support.h"

namespace sao::exectest {
namespace {

using vk::headless::Image;

VkFormat vkFormat(gen::Format f) { return VkFormat(gen::formatInfo(f).vkFormat); }

constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
VkImageLayout depthLayout(const Frame& f) {
  return f.depthReadOnlyLayout ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL : kRead;
}

class VkExecutor final : public Executor {
 public:
  ~VkExecutor() override {
    effect_.reset();
    releaseInputs();
  }
  Api api() const override { return Api::Vulkan; }

  Status upload(const Frame& f) override {
    releaseInputs();
    auto& ctx = vktest::context();
    if (!f.depthLayers.empty()) {  // stereo: arrays with a 2D view per layer, OutputImage::layer
      if (Status st = checkLayers(f); !st) return st;
      outputLayouts_.assign(f.depthLayers.size(), VK_IMAGE_LAYOUT_UNDEFINED);
      if (Status st = vktest::uploadDepthLayers(f.depthLayers, depthLayout(f), depthArray_); !st) return st;
      return vktest::createArrayImage(vkFormat(f.output.format), {f.camera.width, f.camera.height},
                                      std::uint32_t(f.depthLayers.size()), vktest::kOutputArrayUsage,
                                      VK_IMAGE_ASPECT_COLOR_BIT, outputArray_);
    }
    if (f.depth == nullptr) return Status::error(StatusCode::InvalidInput, "harness: the frame has no depth");
    const VkImageLayout layout = depthLayout(f);
    if (Status st = f.depth->samples > 1 ? vktest::writeMultisampledDepth(ctx, *f.depth, layout, depth_)
                                         : ctx.uploadDepth(*f.depth, vkDepth(f.format), layout, depth_);
        !st)
      return st;
    if (f.depth2)
      if (Status st = ctx.uploadDepth(*f.depth2, vkDepth(f.format), layout, depth2_); !st) return st;
    if (f.normals)
      if (Status st = ctx.uploadColor(withChannels(*f.normals, channelsOf(f.normalsTexels)), vkTexels(f.normalsTexels),
                                      kRead, normals_);
          !st)
        return st;
    if (f.motion)
      if (Status st = ctx.uploadColor(withChannels(*f.motion, channelsOf(f.motionTexels)), vkTexels(f.motionTexels),
                                      kRead, motion_);
          !st)
        return st;
    if (f.output.callerOwned) {
      const VkFormat format = vkFormat(f.output.format);
      const Status st = f.output.initial
                            ? ctx.uploadColor(*f.output.initial, format, VK_IMAGE_LAYOUT_GENERAL, output_,
                                              VK_IMAGE_USAGE_STORAGE_BIT)
                            : ctx.createStorageImage(format, {f.camera.width, f.camera.height}, output_);
      if (!st) return st;
    }
    return Status::success();
  }

  Status run(const Frame& f) override {
    // The per-frame call, GL's shape: what only Config can say (the effect-owned output's format)
    // makes a new effect when it changes; everything else goes to record().
    const DepthImage& depth = runDepth(f);
    const bool layered = !outputLayouts_.empty();
    const bool otherOwnedFormat = !f.output.callerOwned && vkFormat(f.output.format) != ownedFormat_;
    if (effect_ && otherOwnedFormat) effect_.reset();
    if (!effect_) {
      if (!f.output.callerOwned) ownedFormat_ = vkFormat(f.output.format);
      vk::Config c;
      c.outputFormat = ownedFormat_;
      if (Status st = vk::Effect::create(vktest::context().deviceContext(), c, effect_); !st) return st;
      createdBlocks_ = effect_->memoryStats().totalAllocations;  // the parameter buffer's, no image yet
      callerOutput_ = false;
    }
    vk::Inputs in;
    in.depth = {layered ? depthArray_.views.at(f.layer) : depth_.view, depthLayout(f), depth.extent, vkDepth(f.format),
                VkSampleCountFlagBits(depth.samples)};
    if (f.depth2) in.depth2 = {depth2_.view, depthLayout(f), f.depth2->extent, vkDepth(f.format)};
    if (f.normals) in.normals = {normals_.view, kRead, f.normals->extent, vkTexels(f.normalsTexels)};
    if (f.motion) in.motion = {motion_.view, kRead, f.motion->extent, vkTexels(f.motionTexels)};
    in.region = f.region;
    in.frameIndex = f.frameIndex;
    in.resetHistory = f.resetHistory;
    in.previousCamera = f.previousCamera;
    in.outputChannels = f.output.channels;
    in.outputBlend = f.output.blend;
    const vk::OutputImage user =
        layered ? vk::OutputImage{outputArray_.image, outputArray_.views.at(f.layer), outputArray_.format,
                                  outputArray_.extent, outputLayouts_[f.layer], f.layer}
                : vk::OutputImage{output_.image, output_.view, output_.format, output_.extent, output_.layout};
    Status recorded;
    const Status submitted = vktest::context().submit([&](VkCommandBuffer cmd) {
      recorded = effect_->record(cmd, f.camera, f.settings, in, f.output.callerOwned ? &user : nullptr);
    });
    if (!submitted) return submitted;
    if (recorded && f.output.callerOwned)
      (layered ? outputLayouts_[f.layer] : output_.layout) = effect_->config().outputLayout;
    if (recorded) lastLayer_ = f.layer, callerOutput_ = f.output.callerOwned;
    return recorded;
  }

  FloatImage output() override {
    if (!outputLayouts_.empty()) {  // the last run's layer
      FloatImage out;
      const vk::Config& c = effect_->config();
      const Status st = vktest::readLayer(outputArray_, lastLayer_, outputLayouts_[lastLayer_], c.outputDstStages,
                                          c.outputDstAccess, out);
      EXPECT_TRUE(st.ok()) << st.message;
      return out;
    }
    const vk::OutputImage o = callerOutput_
                                  ? vk::OutputImage{output_.image, output_.view, output_.format, output_.extent, output_.layout}
                                  : effect_->output();
    FloatImage out;
    const Status st = vktest::context().readback(o.image, o.format, o.extent, 0, o.layout, effect_->config().outputDstStages,
                                                 effect_->config().outputDstAccess, out);
    EXPECT_TRUE(st.ok()) << st.message;
    return out;
  }

  FloatImage image(gen::ResourceId resource, std::uint32_t level) override {
    const vk::OwnedImageInfo i = effect_->ownedImage(resource);
    FloatImage out;
    if (i.image == VK_NULL_HANDLE) return out;
    const Status st = vktest::context().readback(i.image, i.format, i.extent, level, i.layout,
                                                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, out);
    EXPECT_TRUE(st.ok()) << st.message;
    return out;
  }

  const Plan& plan() const override { return effect_->plan(); }
  const ParamBlock& params() const override { return effect_->params(); }
  std::uint64_t plans() const override { return effect_ ? effect_->plans() : 0; }
  std::uint64_t imageAllocations() const override {
    return effect_ ? effect_->memoryStats().totalAllocations - createdBlocks_ : 0;
  }
  std::uint64_t pipelines() const override { return effect_ ? effect_->pipelineCount() : 0; }
  std::uint64_t outputGeneration() const override { return effect_ ? effect_->outputGeneration() : 0; }
  void releaseEffect() override { effect_.reset(); }

 private:
  void releaseInputs() {
    for (Image* i : {&depth_, &depth2_, &normals_, &motion_, &output_}) vktest::context().destroy(*i);
    vktest::destroy(depthArray_);
    vktest::destroy(outputArray_);
    outputLayouts_.clear();
  }
  std::unique_ptr<vk::Effect> effect_;
  VkFormat ownedFormat_ = VK_FORMAT_R16_SFLOAT;  // Config::outputFormat of effect_
  std::uint64_t createdBlocks_ = 0;
  Image depth_, depth2_, normals_, motion_, output_;
  vktest::ArrayImage depthArray_, outputArray_;  // stereo (Frame::depthLayers)
  std::vector<VkImageLayout> outputLayouts_;     // per layer of outputArray_; empty: not stereo
  std::uint32_t lastLayer_ = 0;
  bool callerOutput_ = false;  // the last recorded run wrote the caller's output_, not the effect's
};

}  // namespace

std::unique_ptr<Executor> makeVkExecutor() {
  vktest::context();
  return std::make_unique<VkExecutor>();
}

void vkMessagesBefore() {
  vktest::context();
  vktest::expectNoMessages("before the test (context creation or an earlier test)");
}

void vkMessagesAfter() { vktest::expectNoMessages("during the test"); }

}  // namespace sao::exectest
