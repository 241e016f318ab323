#include "engine_effect.h"

#include <string>
#include <utility>

#include "engine_transfer.h"
#include "sao/temporal.h"

namespace sao::vkengine {
namespace {

bool isInput(std::size_t id) { return gen::kResources[id].kind == gen::ResourceKind::Input; }
const char* nameOf(std::size_t id) { return gen::kResources[id].name.data(); }

// The plan inputs a frame's images say: which inputs are supplied, how the depth encodes z (the
// depth formats: hardware depth; R32_SFLOAT: linear z), the output's format, single samples.
Status planInputsOf(const EngineFrame& frame, PlanInputs& out) {
  out = PlanInputs{};
  const InputImage& depth = frame.inputs[std::size_t(gen::ResourceId::depth)];
  if (!depth.image) return Status::error(StatusCode::InvalidInput, "vk-engine-example: the frame has no depth");
  const bool linear = depth.format == VK_FORMAT_R32_SFLOAT;
  if (!linear && !(barrierAspects(depth.format) & VK_IMAGE_ASPECT_DEPTH_BIT))
    return Status::error(StatusCode::UnsupportedFormat, "vk-engine-example: the depth is VkFormat " +
                                                            std::to_string(depth.format) +
                                                            ", neither a depth format nor R32_SFLOAT linear z");
  out.depthEncoding = linear ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  for (std::size_t id = 0; id < frame.inputs.size(); ++id) {
    if (!frame.inputs[id].image) continue;
    if (!isInput(id))
      return Status::error(StatusCode::InvalidInput,
                           std::string("vk-engine-example: ") + nameOf(id) + " is not an input of the effect");
    out.supplied[gen::ResourceId(id)] = true;
  }
  out.userOutput = frame.engineOutput;
  out.outputFormat = frame.outputFormat;
  return Status::success();
}

}  // namespace

InputImage inputOf(const Image& image, VkImageLayout layout) {
  return {image.image, image.whole, image.format, layout, image.extent};
}

Status EngineEffect::create(const DeviceHandles& device, std::string shaderDir, std::unique_ptr<EngineEffect>& out) {
  std::unique_ptr<EngineEffect> e(new EngineEffect);
  if (Status st = Device::create(device, e->device_); !st) return st;
  e->executor_ = std::make_unique<EngineExecutor>(*e->device_, std::move(shaderDir));
  if (Status st = e->executor_->init(); !st) return st;
  out = std::move(e);
  return Status::success();
}

EngineEffect::~EngineEffect() {
  if (executor_) state_.release(*executor_);  // every effect image; the executor frees its pipelines
  if (device_) output_.destroy(device_->device());
}

// A new engine output (output_ is empty), which the effect stores to: r16f storage needs
// shaderStorageImageExtendedFormats, which the device has; it lives in GENERAL from here on.
Status EngineEffect::makeOutput(Extent extent, gen::Format format) {
  const auto vkFormat = static_cast<VkFormat>(gen::formatInfo(format).vkFormat);
  if (!device_->hasFeatures(vkFormat, VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT))
    return Status::error(StatusCode::UnsupportedFormat, std::string("vk-engine-example: the device cannot store ") +
                                                            gen::formatInfo(format).name.data() + " (the output)");
  Status st = makeImage(*device_, vkFormat, VK_IMAGE_ASPECT_COLOR_BIT, extent, 1,
                        VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, output_);
  if (st)
    st = device_->submitOnce([&](VkCommandBuffer cmd) {
      cmdBarriers(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  {imageBarrier(output_.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT)});
    });
  if (!st) {
    output_.destroy(device_->device());
    return st;
  }
  outputFormat_ = format;
  ++engineOutputs_;
  return Status::success();
}

Status EngineEffect::configure(const Settings& settings, const Camera& camera, const EngineFrame& frame) {
  PlanInputs planInputs;
  if (Status st = planInputsOf(frame, planInputs); !st) return st;
  if (Status st = state_.configure(settings, camera, planInputs, *executor_); !st) return st;
  ran_ = false;
  output_.destroy(device_->device());  // every frame before waited for its fence
  // Without the engine's output the effect's is one of the plan's images, made by now.
  return frame.engineOutput ? makeOutput(state_.plan().aoExtent, frame.outputFormat) : Status::success();
}

Status EngineEffect::run(const Settings& settings, const Camera& camera, const EngineFrame& frame) {
  PlanInputs planInputs;
  if (Status st = planInputsOf(frame, planInputs); !st) return st;
  // FrameState::render() configures when the frame needs it, after checking the frame against the
  // new plan, so that a refused frame leaves the configuration as it was. The engine's output must
  // have the AO extent of the plan the frame runs on before that: planned here too (the cost of a
  // plan is small next to a new configuration's images and pipelines).
  Extent aoExtent = state_.plan().aoExtent;
  if (!state_.keeps(settings, camera, planInputs)) {
    Plan next;
    if (Status st = sao::plan(settings, camera, planInputs, next); !st) return st;
    aoExtent = next.aoExtent;
  }
  // Another output (extent, format, owner): the current one is kept until the frame has run, so
  // that a refused frame leaves the output as it was too. Every frame before waited for its fence.
  Image previous;
  const gen::Format previousFormat = outputFormat_;
  const bool previousRan = ran_;
  const bool sameOutput = frame.engineOutput
                              ? output_.image && output_.extent == aoExtent && outputFormat_ == frame.outputFormat
                              : !output_.image;
  if (!sameOutput) {
    previous = std::exchange(output_, Image{});
    ran_ = false;
    if (frame.engineOutput)
      if (Status st = makeOutput(aoExtent, frame.outputFormat); !st) {
        output_ = previous, outputFormat_ = previousFormat, ran_ = previousRan;
        return st;
      }
  }

  // What the engine hands over, so that core checks it against the plan every frame.
  SuppliedImages supplied{};
  EngineImages images{};
  for (std::size_t id = 0; id < frame.inputs.size(); ++id) {
    const InputImage& in = frame.inputs[id];
    if (!in.image) continue;
    supplied[id] = {true, in.extent, frame.region};
    images[id] = {in.image, in.view, barrierAspects(in.format), in.layout};
  }
  if (frame.engineOutput) {
    const std::size_t ao = std::size_t(gen::ResourceId::ao);
    supplied[ao] = {true, aoExtent, {}};
    images[ao] = {output_.image, output_.whole, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL};
  }
  executor_->setEngineImages(images);

  FrameInputs in;
  in.previousCamera = frame.previousCamera;
  in.resetHistory = frame.resetHistory;
  in.values.inputOffset = frame.region.value_or(Offset{});
  in.values.frameIndex = frame.frameIndex;
  in.images = &supplied;
  const std::uint64_t plans = state_.plans();
  const Status st = state_.render(settings, camera, planInputs, in, *executor_);
  const VkDevice d = device_->device();
  if (!st.ok() && state_.plans() == plans && !sameOutput) {  // refused: the configuration and its output stay
    output_.destroy(d);
    output_ = previous, outputFormat_ = previousFormat, ran_ = previousRan;
    return st;
  }
  previous.destroy(d);
  if (st.ok()) ran_ = true;
  else if (state_.plans() != plans) ran_ = false;  // a new configuration whose frame failed
  return st;
}

Status EngineEffect::readOutput(FloatImage& out) const {
  if (!ran_) return Status::error(StatusCode::InvalidInput, "vk-engine-example: no frame wrote the output yet");
  if (!state_.planInputs().userOutput) return readImage(gen::ResourceId::ao, 0, out);
  return vkengine::readImage(*device_, output_, outputFormat_, 0, out);
}

Status EngineEffect::readImage(gen::ResourceId resource, std::uint32_t level, FloatImage& out) const {
  const PlannedImage* planned = state_.configured() ? state_.plan().image(resource) : nullptr;
  if (!planned)
    return Status::error(StatusCode::InvalidInput,
                         std::string("vk-engine-example: the plan has no ") + nameOf(std::size_t(resource)));
  const std::uint32_t copy = imageCopy(executor_->historyParity(), resource, /*previousFrame=*/false);
  const Image* image = executor_->image(*planned, copy);
  if (!image)
    return Status::error(StatusCode::InvalidInput,
                         std::string("vk-engine-example: no image made for ") + nameOf(std::size_t(resource)));
  return vkengine::readImage(*device_, *image, planned->format, level, out);
}

}  // namespace sao::vkengine
