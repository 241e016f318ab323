// The Vulkan prepass: a render pass with a depth attachment (D16_UNORM, X8_D24_UNORM_PACK32 or
// D32_SFLOAT, each checked for support) and two RGBA32F colour attachments, a second render pass
// for the peeled layer, copies to a host-visible buffer, one submission per render() waited on.
// Vulkan's clip depth is [0, 1]: cameras with ClipDepth::NegativeOneToOne are refused
// (InvalidCamera). It runs on its own headless instance and device (sao::vk::headless, lavapipe
// without a GPU; validation optional) or on a headless context the caller owns and outlives it.
//
// A renderer that draws every frame (sao-viewer) uses setMesh() and record() instead of render():
// the first layer's depth only, recorded into the caller's command buffer.
#pragma once
#include <memory>

#include <glm/glm.hpp>

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

  // Checks and uploads the mesh record() draws (render() replaces it with its own).
  Status setMesh(const scenes::Mesh& mesh);
  // Records the depth of `view` (world -> camera, scenes::viewMatrix) into `cmd`, outside a render
  // pass, with render()'s conventions: no positions, normals, peeling or read-back, and no
  // Camera::flipY. `out` is the depth image (valid until the next record() with another size or
  // format), left in DEPTH_STENCIL_READ_ONLY_OPTIMAL and visible to compute and fragment shaders;
  // the clear waits for such reads of the previous frame. Neither this nor setMesh() while a
  // command buffer from an earlier record() is pending (the uniforms and images are rewritten).
  Status record(VkCommandBuffer cmd, const glm::dmat4& view, const Camera& camera, DepthFormat format,
                vk::headless::Image& out);

 private:
  VkPrepass() = default;
  struct State;
  Status init();
  Status checkExtent(Extent extent) const;  // InvalidExtent beyond the device's limits
  std::unique_ptr<vk::headless::Context> owned_;
  vk::headless::Context* context_ = nullptr;
  std::unique_ptr<State> state_;
};

}  // namespace sao::prepass
