// The Vulkan backend as a sample backend: a headless instance and device of its own (a real GPU
// when there is one, else lavapipe), the depth uploaded as the matching format, results read back.
#include <chrono>
#include <cstdlib>
#include <string>

#include "runners.h"
#include "sao/frame.h"
#include "sao/vulkan/effect.h"
#include "sao/vulkan/headless.h"

namespace sao::samples {
namespace {

class VulkanRunner final : public BackendRunner {
 public:
  explicit VulkanRunner(std::unique_ptr<vk::headless::Context> context) : context_(std::move(context)) {}
  std::string_view name() const override { return "vulkan"; }
  std::string description() const override { return "Vulkan: " + context_->description(); }

  Status run(const Settings& settings, const Camera& camera, const RunInputs& in, bool measureTime, bool dumpPasses,
             RunOutputs& out) override {
    auto& ctx = *context_;
    Prepared p{ctx};
    if (Status s = prepare(settings, in, measureTime, p); !s) return s;
    if (measureTime) {
      if (Status s = effect_->measure(ctx.queue(), camera, settings, p.inputs, nullptr, out.timings); !s) return s;
    } else if (Status s = recordOnce(camera, settings, p.inputs); !s) {
      return s;
    }
    const vk::Config& config = effect_->config();
    out.plan = effect_->plan();
    const vk::OutputImage o = effect_->output();
    FloatImage output;
    if (Status s = ctx.readback(o.image, o.format, o.extent, 0, o.layout, config.outputDstStages, config.outputDstAccess,
                                output);
        !s)
      return s;
    splitOutput(std::move(output), out);
    auto readOwned = [&](gen::ResourceId id, std::uint32_t level, FloatImage& image) {
      const auto info = effect_->ownedImage(id);
      return ctx.readback(info.image, info.format, info.extent, level, info.layout, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                          VK_ACCESS_SHADER_WRITE_BIT, image);
    };
    if (out.plan.image(gen::ResourceId::ao_raw))  // not planned when ao_sample_output writes the output
      if (Status s = readOwned(gen::ResourceId::ao_raw, 0, out.aoRaw); !s) return s;
    if (dumpPasses) {
      if (const auto* csz = out.plan.image(gen::ResourceId::csz))
        for (std::uint32_t m = 0; m < csz->mipLevels; ++m) {
          FloatImage level;
          if (Status s = readOwned(gen::ResourceId::csz, m, level); !s) return s;
          out.intermediates.push_back({"csz_level" + std::to_string(m), std::move(level)});
        }
      if (!out.aoRaw.data.empty()) out.intermediates.push_back({"ao_raw", out.aoRaw});
      if (out.plan.image(gen::ResourceId::ao_low)) {  // the blurred (A, key), the upsample's input
        FloatImage low;
        if (Status s = readOwned(gen::ResourceId::ao_low, 0, low); !s) return s;
        out.intermediates.push_back({"ao_low", std::move(low)});
      }
    }
    return validationMessages();
  }

  Status keepBusy(const Settings& settings, const Camera& camera, const RunInputs& in, double milliseconds) override {
    Prepared p{*context_};
    // The effect of the runs around it, timestamps included: no new effect in between.
    const bool timestamps = effect_ && effect_->config().timestamps;
    if (Status s = prepare(settings, in, timestamps, p); !s) return s;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(milliseconds);
    do {
      if (Status s = recordOnce(camera, settings, p.inputs); !s) return s;
    } while (std::chrono::steady_clock::now() < end);
    return validationMessages();
  }

 private:
  // A run's uploaded inputs, destroyed with it.
  struct Prepared {
    explicit Prepared(vk::headless::Context& context) : ctx(context) {}
    vk::headless::Context& ctx;
    vk::headless::Image depth, depth2, normals;
    vk::Inputs inputs;
    ~Prepared() {
      for (auto* i : {&depth, &depth2, &normals}) ctx.destroy(*i);
    }
  };

  // Uploads the inputs (each with its format) and makes sure of an effect whose Config matches the
  // run: one with timestamps to measure, one without otherwise, and with the run's output format.
  // Settings and camera go to each record() (or measure()), which plans again only when they (or
  // the inputs) change the plan: a camera path's frames that plan alike keep the effect's plan and
  // its temporal history.
  Status prepare(const Settings& settings, const RunInputs& in, bool measureTime, Prepared& p) {
    if (!in.depth) return Status::error(StatusCode::InvalidInput, "no depth image");
    auto& ctx = *context_;
    const VkImageLayout readLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    vk::Inputs& inputs = p.inputs;
    const VkFormat depthFormat = vk::depthVkFormat(in.depth->format);
    if (Status s = ctx.uploadDepth(*in.depth, depthFormat, readLayout, p.depth); !s) return s;
    inputs.depth = {p.depth.view, readLayout, in.depth->extent, depthFormat};
    if (in.depth2) {
      const VkFormat depth2Format = vk::depthVkFormat(in.depth2->format);
      if (Status s = ctx.uploadDepth(*in.depth2, depth2Format, readLayout, p.depth2); !s) return s;
      inputs.depth2 = {p.depth2.view, readLayout, in.depth2->extent, depth2Format};
    }
    if (in.normals) {
      const VkFormat normalsFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
      if (Status s = ctx.uploadColor(*in.normals, normalsFormat, readLayout, p.normals); !s) return s;
      inputs.normals = {p.normals.view, readLayout, in.normals->extent, normalsFormat};
    }
    inputs.frameIndex = in.frameIndex;
    inputs.resetHistory = in.resetHistory;
    // Timestamps and the output format (RGBA16F for bent normals, runnerOutputFormat) are what of
    // the Config a run changes (a new effect: its plan and history start again, as a change of
    // timing choice did before).
    const auto outputFormat = static_cast<VkFormat>(gen::formatInfo(runnerOutputFormat(settings)).vkFormat);
    if (effect_ && effect_->config().timestamps == measureTime && effect_->config().outputFormat == outputFormat)
      return Status::success();
    effect_.reset();
    vk::Config config;
    config.timestamps = measureTime;
    config.outputFormat = outputFormat;
    return vk::Effect::create(ctx.deviceContext(), config, effect_);
  }

  // One frame recorded, submitted and waited for.
  Status recordOnce(const Camera& camera, const Settings& settings, const vk::Inputs& inputs) {
    Status recorded;
    if (Status s = context_->submit(
            [&](VkCommandBuffer cmd) { recorded = effect_->record(cmd, camera, settings, inputs); });
        !s)
      return s;
    return recorded;
  }

  Status validationMessages() {
    if (context_->messageCount())
      return Status::error(StatusCode::DriverError, "Vulkan validation: " + vk::headless::toString(context_->takeMessages()));
    return Status::success();
  }

  std::unique_ptr<vk::headless::Context> context_;
  std::unique_ptr<vk::Effect> effect_;  // destroyed before the context (declared after it)
};

}  // namespace

Status makeVulkanRunner(std::unique_ptr<BackendRunner>& out) {
  std::unique_ptr<vk::headless::Context> context;
  vk::headless::Options options;
  // SAO_VK_VALIDATION=1 turns on the validation layers (with synchronization validation).
  const char* validation = std::getenv("SAO_VK_VALIDATION");
  options.synchronizationValidation = options.validation = validation && std::string(validation) == "1";
  if (Status s = vk::headless::Context::create(options, context); !s) return s;
  out = std::make_unique<VulkanRunner>(std::move(context));
  return Status::success();
}

}  // namespace sao::samples
