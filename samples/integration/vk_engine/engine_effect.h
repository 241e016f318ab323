// The effect as this engine runs it: a sao::FrameState (core decides the plan, the schedule, the
// parameter block and the history) driving the engine's own executor (engine_executor.h) on a
// device the engine was handed, the shaders read from the installed .spv files. The output is the
// engine's own image (PlanInputs::userOutput: of the plan's AO extent in the frame's output format,
// made again when either changes) or, with EngineFrame::engineOutput false, one of the effect's
// images, which the executor makes with the plan's others; either is written whole every frame (no
// channel mask or blend: the engine keeps nothing of an output's earlier texels).
//
//   std::unique_ptr<EngineEffect> effect;
//   EngineEffect::create(handles, shaderDir, effect);
//   each frame: effect->run(settings, camera, frame);  then effect->readOutput(ao) when wanted
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "engine_device.h"
#include "engine_executor.h"
#include "engine_images.h"
#include "sao/camera.h"
#include "sao/executor.h"
#include "sao/image.h"
#include "sao/plan.h"
#include "sao/settings.h"

namespace sao::vkengine {

// An input the engine rendered: single-sampled, sampled in `layout` (SHADER_READ_ONLY_OPTIMAL, or
// DEPTH_STENCIL_READ_ONLY_OPTIMAL for depth), last written by a transfer. A depth's view selects
// the depth aspect only; R32_SFLOAT depth is linear camera-space z.
struct InputImage {
  VkImage image = VK_NULL_HANDLE;  // null: not supplied
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  Extent extent;
};
InputImage inputOf(const Image& image, VkImageLayout layout);  // one of the engine's own images

struct EngineFrame {
  // By resource id, the kind=input resources only: the depth always, the others when supplied
  // (their variants read them: normals, a second depth layer, motion vectors).
  std::array<InputImage, gen::kResources.size()> inputs{};
  std::optional<Offset> region{};  // the inputs are larger images holding the region from here
  gen::Format outputFormat = gen::Format::R16F;
  bool engineOutput = true;                    // false: the effect's own output image
  std::uint32_t frameIndex = 0;                // the frame's spiral (sao/spiral.h)
  bool resetHistory = false;                   // temporal: a camera cut
  const Camera* previousCamera = nullptr;      // temporal: null, the camera of the frame before
};

class EngineEffect {
 public:
  static Status create(const DeviceHandles& device, std::string shaderDir, std::unique_ptr<EngineEffect>& out);
  ~EngineEffect();
  EngineEffect(const EngineEffect&) = delete;
  EngineEffect& operator=(const EngineEffect&) = delete;

  // Plans for these settings, camera and the plan inputs `frame` implies (which inputs, the
  // depth's encoding, the output's owner and format) and makes the engine's output; the temporal
  // history starts again.
  // On error the current configuration, if any, still runs.
  Status configure(const Settings& settings, const Camera& camera, const EngineFrame& frame);
  // One frame, recorded, submitted and waited for (FrameState::render): configures first when the
  // settings, the plan inputs or a plan-changing camera changed, once the frame's images passed
  // core's checks against the new plan; a refused frame keeps the configuration and the output.
  Status run(const Settings& settings, const Camera& camera, const EngineFrame& frame);

  // After a frame: the output (its format's channels), and level `level` of an effect image of the
  // plan (a history's copy this frame wrote).
  Status readOutput(FloatImage& out) const;
  Status readImage(gen::ResourceId resource, std::uint32_t level, FloatImage& out) const;

  const Device& device() const { return *device_; }  // for the engine's own uploads
  const Plan& plan() const { return state_.plan(); }
  const ParamBlock& params() const { return state_.block(); }  // the last frame's
  std::uint64_t plans() const { return state_.plans(); }
  // Device images made so far (the effect's, every copy, and the engine's outputs), and pipelines built.
  std::uint64_t imageAllocations() const { return executor_->imagesMade() + engineOutputs_; }
  std::size_t pipelines() const { return executor_->pipelineCount(); }
  // How many output images were made, the engine's and the effect's: a new one each time the
  // owner, the AO extent or the format changes.
  std::uint64_t outputGeneration() const { return executor_->outputsMade() + engineOutputs_; }

 private:
  EngineEffect() = default;
  Status makeOutput(Extent extent, gen::Format format);

  std::unique_ptr<Device> device_;
  std::unique_ptr<EngineExecutor> executor_;
  FrameState state_{"vk-engine-example"};
  Image output_;  // the engine's output (EngineFrame::engineOutput)
  gen::Format outputFormat_ = gen::Format::R16F;
  std::uint64_t engineOutputs_ = 0;  // engine outputs made
  bool ran_ = false;                 // a frame ran on the current configuration and output
};

}  // namespace sao::vkengine
