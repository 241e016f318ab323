// The OpenGL path, the real drop-in case: the viewer owns a GL 4.3+ core context (GLFW),
// rasterises the scene into its own D32F depth texture (reversed-Z with glClipControl where GL
// 4.5 or ARB_clip_control has it), runs sao::gl::Effect on that texture in the same context and
// composites the result with ImGui on top.
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cstdio>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "backend.h"
#include "gl_composite.h"
#include "gl_prepass.h"
#include "sao/gl/effect.h"
#include "screenshot.h"

namespace sao::viewer {
namespace {

class GlBackend final : public Backend {
 public:
  GlBackend(Window& window, const BackendOptions& options) : window_(window), options_(options) {}
  ~GlBackend() override {
    if (imgui_) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
    }
    compareEffect_.reset();  // GL objects go while the context is current
    effect_.reset();
  }

  Status init() {
    if (epoxy_gl_version() < 43)
      return Status::error(StatusCode::DriverError, "OpenGL 4.3 or newer is needed, the context has " +
                                                        std::to_string(epoxy_gl_version() / 10) + "." +
                                                        std::to_string(epoxy_gl_version() % 10));
    const bool clipControl = epoxy_gl_version() >= 45 || epoxy_has_gl_extension("GL_ARB_clip_control");
    reversedZ_ = clipControl && !options_.standardDepth;
    if (reversedZ_) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    window_.setVsync(options_.vsync);
    if (Status s = gl::Effect::create(glfwGetProcAddress, effect_); !s) return s;
    if (Status s = prepass_.init(); !s) return s;
    if (Status s = composite_.init(); !s) return s;
    if (!ImGui_ImplGlfw_InitForOpenGL(window_.handle(), true) || !ImGui_ImplOpenGL3_Init("#version 430 core"))
      return Status::error(StatusCode::DriverError, "cannot initialise ImGui's GLFW / OpenGL 3 backends");
    imgui_ = true;
    description_ = std::string("OpenGL ") + reinterpret_cast<const char*>(glGetString(GL_VERSION)) + ", " +
                   reinterpret_cast<const char*>(glGetString(GL_RENDERER)) +
                   (reversedZ_ ? "; depth: D32F reversed-Z, glClipControl [0,1], infinite far (orthographic: a far "
                                 "plane just beyond the scene)"
                               : "; depth: D32F standard, [-1,1] clip, finite far");
    return drainErrors("initialisation");
  }

  std::string description() const override { return description_; }
  ClipDepth clipDepth() const override { return reversedZ_ ? ClipDepth::ZeroToOne : ClipDepth::NegativeOneToOne; }
  bool reversedZ() const override { return reversedZ_; }
  std::size_t validationErrors() const override { return glErrors_; }

  Status setMesh(const scenes::Mesh& mesh) override {
    prepass_.setMesh(mesh);
    return drainErrors("mesh upload");
  }

  Status setReference(const FloatImage* reference) override {
    composite_.setReference(reference);
    return drainErrors("reference upload");
  }

  void newImGuiFrame() override {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
  }

  Status renderFrame(const FrameDesc& frame, FrameStats& stats) override {
    const Camera& camera = frame.camera;
    const int w = int(camera.width + 2 * camera.guardBand), h = int(camera.height + 2 * camera.guardBand);
    if (Status s = prepass_.resize(w, h); !s) return s;
    const glm::dmat4 projection = glm::make_mat4(camera.projection.data());
    prepass_.render(projection * frame.view, reversedZ_);

    gl::Inputs inputs;
    inputs.depth = {prepass_.depthTexture(), gl::kDepthComponent32F};
    inputs.frameIndex = frame.frameIndex;
    stats.effect = effect_->render(camera, frame.settings, inputs, {frame.measureTime});
    const GLuint compareAo = renderCompare(frame, inputs, stats.compare);
    GlCompositeInputs in;
    in.depth = prepass_.depthTexture();
    std::uint32_t cszLevels = 0;
    if (stats.effect.ok()) {
      stats.plan = effect_->plan();
      stats.timings = effect_->timings();
      stats.timingNote.clear();
      in.ao = effect_->aoTexture();
      in.aoRaw = effect_->texture(gen::ResourceId::ao_raw);
      in.csz = effect_->texture(gen::ResourceId::csz);
      cszLevels = in.csz ? stats.plan.cszLevels : 0;
      aoExtent_ = stats.plan.aoExtent;
    }
    if (stats.compare.active) {  // left the divisor-1 AO, right the reduced one
      const bool mainIsFull = frame.settings.resolution_divisor == 1;
      in.aoReduced = mainIsFull ? compareAo : in.ao;
      in.ao = mainIsFull ? in.ao : compareAo;
    }
    const glm::ivec2 fb = window_.framebufferSize();
    composite_.draw(makeCompositeParams(frame, false, in.aoRaw != 0, cszLevels), in, fb.x, fb.y);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    Status shot;
    if (!frame.screenshotPath.empty()) shot = screenshot(frame.screenshotPath, fb.x, fb.y);
    glfwSwapBuffers(window_.handle());
    if (Status s = drainErrors("the frame"); !s) return s;
    return shot;
  }

  Status readAo(FloatImage& out) override {
    if (!effect_->aoTexture() || aoExtent_.width == 0)
      return Status::error(StatusCode::InvalidInput, "no AO rendered yet");
    out = FloatImage(aoExtent_, 1);
    glBindTexture(GL_TEXTURE_2D, effect_->aoTexture());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_FLOAT, out.data.data());
    glBindTexture(GL_TEXTURE_2D, 0);
    return drainErrors("reading the AO back");
  }

 private:
  // The split-resolution view's second effect: the same depth and camera at the other divisor,
  // created when the mode comes on and deleted when it goes (other modes pay nothing). Returns
  // its AO texture, 0 when it failed (shown white, the error in `out.effect`) or is not needed.
  GLuint renderCompare(const FrameDesc& frame, const gl::Inputs& inputs, CompareStats& out) {
    out = {};
    if (frame.mode != ViewMode::SplitResolution) {
      compareEffect_.reset();
      return 0;
    }
    out.active = true;
    if (!compareEffect_)
      if (out.effect = gl::Effect::create(glfwGetProcAddress, compareEffect_); !out.effect) return 0;
    out.effect = compareEffect_->render(frame.camera, compareSettings(frame.settings), inputs, {frame.measureTime});
    if (!out.effect) return 0;
    out.timings = compareEffect_->timings();
    return compareEffect_->aoTexture();
  }

  Status screenshot(const std::string& path, int width, int height) {
    std::vector<std::uint8_t> pixels(std::size_t(width) * height * 4);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    return writeScreenshot(path, width, height, pixels.data(), {.bottomUp = true, .bgra = false});
  }

  // GL errors are counted (the exit status says so) and reported once each.
  Status drainErrors(const char* where) {
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
      ++glErrors_;
      if (glErrors_ <= 10) std::fprintf(stderr, "sao-viewer: GL error 0x%04x during %s\n", unsigned(e), where);
    }
    return Status::success();
  }

  Window& window_;
  BackendOptions options_;
  std::unique_ptr<gl::Effect> effect_;
  std::unique_ptr<gl::Effect> compareEffect_;  // split-resolution view only
  GlPrepass prepass_;
  GlComposite composite_;
  bool reversedZ_ = false, imgui_ = false;
  std::string description_;
  Extent aoExtent_;
  std::size_t glErrors_ = 0;
};

}  // namespace

Status createGlBackend(Window& window, const BackendOptions& options, std::unique_ptr<Backend>& out) {
  auto backend = std::make_unique<GlBackend>(window, options);
  if (Status s = backend->init(); !s) return s;
  out = std::move(backend);
  return Status::success();
}

}  // namespace sao::viewer
