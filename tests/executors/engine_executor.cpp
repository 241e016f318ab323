// The harness's third executor: the engine-side example's effect (samples/integration/vk_engine:
// sao::core's FrameState driving the engine's own sao::Executor on raw Vulkan, the pipelines made
// from the SPIR-V files the build writes for installation) on the Vulkan test context, under the
// same validation and synchronization validation as Api::Vulkan: a message fails the test. The
// harness uploads the inputs (the engine's "device-side inputs": its images, sampled in their
// layout after a transfer); the caller's output is the engine's own image (written whole), the
// effect-owned one an image of the plan. What the example does not implement (harness.h Feature)
// is refused here, naming it.
#include <cstdlib>

#include "harness_apis.h"
#include "vk_engine/engine_effect.h"
#include "vk_formats.h"
#include "vk_support.h"

namespace sao::exectest {
namespace {

using vk::headless::Image;

constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// The feature of harness.h a frame needs that the example lacks, if any.
std::optional<Feature> unsupported(const Frame& f) {
  if (!f.depthLayers.empty()) return Feature::Stereo;
  if (f.depth && f.depth->samples > 1) return Feature::MultisampledDepth;
  if (f.output.initial || f.output.channels != kAllChannels || f.output.blend != OutputBlend::Replace)
    return Feature::OutputContents;
  return std::nullopt;
}
Status checkSupported(const Frame& f) {
  if (const auto feature = unsupported(f))
    return Status::error(StatusCode::InvalidInput, std::string("harness: the engine-side example does not implement ") +
                                                       describe(*feature));
  return Status::success();
}

class EngineExecutor final : public Executor {
 public:
  ~EngineExecutor() override {
    effect_.reset();
    releaseInputs();
  }
  Api api() const override { return Api::Engine; }

  Status upload(const Frame& f) override {
    releaseInputs();
    if (Status st = checkSupported(f); !st) return st;
    if (f.depth == nullptr) return Status::error(StatusCode::InvalidInput, "harness: the frame has no depth");
    auto& ctx = vktest::context();
    depthLayout_ = f.depthReadOnlyLayout ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL : kRead;
    if (Status st = ctx.uploadDepth(*f.depth, vkDepth(f.format), depthLayout_, depth_); !st) return st;
    if (f.depth2)
      if (Status st = ctx.uploadDepth(*f.depth2, vkDepth(f.format), depthLayout_, depth2_); !st) return st;
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
    return Status::success();
  }

  Status run(const Frame& f) override {
    if (Status st = checkSupported(f); !st) return st;
    if (!depth_.image) return Status::error(StatusCode::InvalidInput, "harness: run() before a successful upload()");
    if (!effect_) {
      const auto& ctx = vktest::context();
      const vkengine::DeviceHandles device{ctx.physicalDevice(), ctx.device(), ctx.queueFamily(), ctx.queue()};
      // SAO_ENGINE_SHADER_DIR in the environment: another set of .spv files of the same effect (the
      // HLSL round trip's, exec.reference.hlsl50 / hlsl60); by default the build's own.
      const char* dir = std::getenv("SAO_ENGINE_SHADER_DIR");
      if (Status st = vkengine::EngineEffect::create(device, dir && *dir ? dir : SAO_ENGINE_SHADER_DIR, effect_); !st)
        return st;
    }
    vkengine::EngineFrame in;
    in.inputs[std::size_t(gen::ResourceId::depth)] = input(depth_, depthLayout_);
    in.inputs[std::size_t(gen::ResourceId::depth2)] = input(depth2_, depthLayout_);
    in.inputs[std::size_t(gen::ResourceId::normals)] = input(normals_, kRead);
    in.inputs[std::size_t(gen::ResourceId::motion)] = input(motion_, kRead);
    in.region = f.region;
    in.outputFormat = f.output.format;
    in.engineOutput = f.output.callerOwned;  // the engine's image (PlanInputs::userOutput), else the effect's
    in.frameIndex = f.frameIndex;
    in.resetHistory = f.resetHistory;
    in.previousCamera = f.previousCamera;
    return effect_->run(f.settings, f.camera, in);
  }

  FloatImage output() override {
    FloatImage out;
    const Status st = effect_ ? effect_->readOutput(out) : Status::error(StatusCode::InvalidInput, "no effect");
    EXPECT_TRUE(st.ok()) << st.message;
    return out;
  }

  FloatImage image(gen::ResourceId resource, std::uint32_t level) override {
    FloatImage out;
    if (!effect_ || !effect_->plan().image(resource)) return out;  // not planned: empty
    const Status st = effect_->readImage(resource, level, out);
    EXPECT_TRUE(st.ok()) << st.message;
    return out;
  }

  const Plan& plan() const override { return effect_ ? effect_->plan() : kNoPlan; }
  const ParamBlock& params() const override { return effect_ ? effect_->params() : kNoBlock; }
  std::uint64_t plans() const override { return effect_ ? effect_->plans() : 0; }
  std::uint64_t imageAllocations() const override { return effect_ ? effect_->imageAllocations() : 0; }
  std::uint64_t pipelines() const override { return effect_ ? effect_->pipelines() : 0; }
  std::uint64_t outputGeneration() const override { return effect_ ? effect_->outputGeneration() : 0; }
  void releaseEffect() override { effect_.reset(); }

 private:
  static vkengine::InputImage input(const Image& i, VkImageLayout layout) {
    return {i.image, i.view, i.format, layout, i.extent};  // null image: not supplied
  }
  void releaseInputs() {
    for (Image* i : {&depth_, &depth2_, &normals_, &motion_}) vktest::context().destroy(*i);
  }
  static inline const Plan kNoPlan{};
  static inline const ParamBlock kNoBlock{};
  std::unique_ptr<vkengine::EngineEffect> effect_;
  Image depth_, depth2_, normals_, motion_;
  VkImageLayout depthLayout_ = kRead;
};

}  // namespace

std::unique_ptr<Executor> makeEngineExecutor() {
  vktest::context();
  return std::make_unique<EngineExecutor>();
}

}  // namespace sao::exectest
