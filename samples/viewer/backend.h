// What the viewer needs from a graphics API: render the scene's depth, run the effect on it,
// composite the view mode, draw the ImGui panel, present, and save screenshots. One
// implementation per API (gl_backend.cpp, vk_backend.cpp).
#pragma once
#include <memory>
#include <string>

#include "sao/image.h"
#include "sao/scenes/mesh.h"
#include "viewer_types.h"
#include "window.h"

namespace sao::viewer {

struct BackendOptions {
  bool vsync = true;
  bool validation = false;     // Vulkan: VK_LAYER_KHRONOS_validation, messages on stderr
  bool standardDepth = false;  // OpenGL: no glClipControl (standard depth, [-1, 1] clip, finite far)
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string description() const = 0;
  // The conventions the prepass renders depth with (the sao::Camera must say the same).
  virtual ClipDepth clipDepth() const = 0;
  virtual bool reversedZ() const = 0;
  virtual Status setMesh(const scenes::Mesh& mesh) = 0;
  // The reference AO (1 channel, the frame's AO extent) for the error view; null forgets it.
  virtual Status setReference(const FloatImage* reference) = 0;
  // Starts the ImGui frame of the renderer and platform backends (before ImGui::NewFrame()).
  virtual void newImGuiFrame() = 0;
  // One frame: prepass, effect, composite, ImGui::GetDrawData(), screenshot if asked, present.
  // Errors of the effect come back in stats.effect (the frame is still shown); a returned error
  // means the frame could not be drawn at all.
  virtual Status renderFrame(const FrameDesc& frame, FrameStats& stats) = 0;
  // The AO of the last frame (1 channel, row 0 at ndc y = -1).
  virtual Status readAo(FloatImage& out) = 0;
  // Validation messages reported so far (Vulkan with --validation; 0 otherwise).
  virtual std::size_t validationErrors() const { return 0; }
};

Status createGlBackend(Window& window, const BackendOptions& options, std::unique_ptr<Backend>& out);
Status createVulkanBackend(Window& window, const BackendOptions& options, std::unique_ptr<Backend>& out);

}  // namespace sao::viewer
