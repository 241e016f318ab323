// The Vulkan prepass: a render pass with a depth attachment (D16_UNORM, X8_D24_UNORM_PACK32 or
// D32_SFLOAT, each checked for support) and two RGBA32F colour attachments, a second render pass
// for the peeled layer, copies to a host-visible buffer, one submission per render() waited on.
// Vulkan's clip depth is [0, 1]: cameras with ClipDepth::NegativeOneToOne are refused
// (InvalidCamera). It runs on its own headless instance and device (sao::vk::headless, lavapipe
// without a GPU; validation optional) or on a headless context the caller owns and outlives it.
#pragma once
#include <memory>

#include "sao/prepass/prepass.h"
#include "sao/vulkan/headless.h"

namespace sao::prepass {

class VkPrepass final : public Prepass {
 public:
  // Its own instance and device.
  static Status create(std::unique_ptr<VkPrepass>& out, const vk::headless::Options& options = {});
  // On the caller's context (which must outlive the prepass).
  static Status create(vk::headless::Context& context, std::unique_ptr<VkPrepass>& out);
  ~VkPrepass() override;
  VkPrepass(const VkPrepass&) = delete;
  VkPrepass& operator=(const VkPrepass&) = delete;

  std::string_view name() const override { return "vulkan"; }
  std::string description() const override;
  bool supportsClip(ClipDepth clip) const override { return clip == ClipDepth::ZeroToOne; }
  Status render(const scenes::Mesh& mesh, const scenes::View& view, const Camera& camera,
                const PrepassOptions& options, PrepassResult& out) override;

  // Whether the device can render into, sample and copy from the format (UnsupportedFormat names
  // the missing feature).
  Status checkFormat(DepthFormat format, bool secondLayer) const;
  vk::headless::Context& context() { return *context_; }

 private:
  VkPrepass() = default;
  struct State;
  Status init();
  std::unique_ptr<vk::headless::Context> owned_;
  vk::headless::Context* context_ = nullptr;
  std::unique_ptr<State> state_;
};

}  // namespace sao::prepass
