#include "options.h"

#include <cstdio>
#include <cstdlib>

#include "sao/cli/command_line.h"
#include "sao/cli/shared_options.h"
#include "screenshot.h"

namespace sao::viewer {
namespace {

constexpr const char* kDescription =
    R"(Interactive Scalable Ambient Obscurance: a GLFW window that rasterises a scene's depth, runs the
sao effect on it every frame and shows the result, with a Dear ImGui panel generated from the
effect's settings metadata, live per-pass timings and the plan.)";

constexpr const char* kFooter = R"(Keys: 1-9 view modes, F12 screenshot (sao-viewer-<time>.png), R compute the reference,
H hide/show the panel, Tab orbit/fly camera, O perspective/orthographic, Home reset the camera,
Esc quit.
Mouse: drag to rotate, right or middle drag to pan, wheel to dolly; WASD, Q/E to move.
Options that would have no effect are refused: --validation without --backend vulkan,
--standard-depth without --backend gl, and a --set setting that the final settings make inert
(e.g. blur_stride while blur_radius = 0; the panel greys such settings out and says why).
Exit status: 0 on success, 1 when the run fails, 2 for bad options, 3 when the graphics API
reported errors (GL errors, or Vulkan validation messages with --validation).
)";

}  // namespace

Options parseOptions(int argc, char** argv) {
  Options o;
  Extent window{std::uint32_t(o.width), std::uint32_t(o.height)};
  bool noVsync = false;
  cli::CommandLine cl("sao-viewer", kDescription, kFooter);
  cl.choice("--backend", o.backend,
            [](const std::string& v) { return v == "gl" || v == "vulkan" ? std::optional(v) : std::nullopt; },
            "gl or vulkan", "gl|vulkan",
            "gl (default): a GL 4.3+ core context; the viewer renders its own D32F depth texture (reversed-Z via "
            "glClipControl when available) and runs sao::gl::Effect on it. vulkan: a Vulkan window "
            "(VK_KHR_swapchain) with a depth-only prepass pipeline, sao::vk::Effect recorded into the frame's "
            "command buffer, the composite and ImGui (imgui_impl_vulkan) presented through the swapchain.");
  cl.text("--scene", o.scene, "NAME|PATH",
          "built-in scene: sponza-like (default), sphere-plane, crease, thin, gears; or a mesh file (.gltf .glb .obj "
          ".ply) or a scene file (.scene)");
  cli::addViewNumber(cl, o.view);
  cl.choice("--units", o.units, scenes::parseLengthUnit, std::string(scenes::kLengthUnitNames), "U",
            "the --scene's length unit: m | cm | mm | in | ft, or auto (OBJ and PLY: a scale that makes the "
            "bounding-box diagonal 5 m, printed at start). Default: the scene's own (built-in and glTF metres, a "
            ".scene file's `units` line), else metres. Settings stay in metres and are converted");
  // The window is the effect's image: the plan's limit (the window system may refuse less).
  cli::addImageSize(cl, window, "window size", "default 1280x720");
  cli::addSettings(cl, o.settings, "any setting (repeatable), checked against its range");
  cl.choice("--view-mode", o.mode, findViewMode, "one of " + viewModeNames(), "MODE",
            "ao | lit (default) | lit-no-ao | split | raw-ao | z-mip | normals | error | split-resolution (the AO "
            "at resolution_divisor 1 left of the divider, at the --set resolution_divisor right of it, 2 when that "
            "is 1; a second effect runs only in this mode)");
  cl.value("--z-level", "N", "csz MIP level for the z-mip view, 0..15 (default 1)",
           [&o](const std::string& v) { o.zLevel = int(cli::parseWhole("--z-level", v, 0, 15)); });
  cl.flag("--reference", o.reference, "compute the ray-traced reference at start (the error view needs it)");
  cli::addRays(cl, "--reference-rays", o.referenceRays, "rays per pixel of the reference", "default 32");
  cl.text("--screenshot", o.screenshot, "FILE",
          "with --frames: save the window as PNG after the last frame and exit. FILE must end in .png and its folder "
          "exist; an existing file is replaced only with --overwrite, the --scene file never (checked before the "
          "window opens)");
  cl.whole("--frames", o.frames, 0, 1000000000, "N", "render N frames, then exit (0: until the window closes)");
  cl.value("--orbit-step", "DEG",
           "turn the camera about the orbit target's vertical by DEG degrees every frame, -30..30 (a moving camera "
           "for temporal accumulation: --set temporal=true)",
           [&o](const std::string& v) {
             const double d = cli::parseNumber("--orbit-step", v);
             if (d < -30 || d > 30) cli::reject("--orbit-step expects degrees in [-30, 30], got '" + v + "'");
             o.orbitStepDegrees = d;
           });
  cl.whole("--min-frame-ms", o.minFrameMs, 0, 5000, "MS",
           "hold every frame at least MS milliseconds (a slow machine: key presses shorter than a frame "
           "still count; tests/apps/viewer_keys.sh)");
  cl.flag("--hide-ui", o.hideUi, "start with the panel hidden (H toggles)");
  cl.flag("--ortho", o.ortho,
          "start with the orthographic camera, as tall as the view's field of view spans at its target (O "
          "toggles; a .scene view with `ortho H` starts orthographic anyway)");
  cl.flag("--standard-depth", o.standardDepth,
          "gl only (refused with --backend vulkan): no glClipControl; standard depth, [-1,1] clip, finite far plane");
  cl.flag("--validation", o.validation,
          "vulkan only (refused with --backend gl): VK_LAYER_KHRONOS_validation with synchronization validation "
          "(messages on stderr; exit status 3 if it reported any)");
  cl.flag("--no-vsync", noVsync, "do not wait for vertical sync");
  cl.flag(samples::kOverwriteOption, o.overwrite, samples::kOverwriteHelp);
  cl.parse(argc, argv);

  o.width = int(window.width), o.height = int(window.height);
  o.vsync = !noVsync;
  if (!o.screenshot.empty() && o.frames == 0) cl.fail("--screenshot needs --frames N");
  // The backend-specific flags would change nothing on the other backend.
  if (o.validation && o.backend != "vulkan")
    cl.fail("--validation has no effect with --backend " + o.backend +
            ": it adds the Vulkan validation layer (use --backend vulkan, or drop --validation)");
  if (o.standardDepth && o.backend != "gl")
    cl.fail("--standard-depth has no effect with --backend " + o.backend +
            ": it turns off the GL viewer's glClipControl reversed-Z (use --backend gl, or drop --standard-depth)");
  if (o.overwrite && o.screenshot.empty()) cl.fail("--overwrite has no effect without --screenshot");
  samples::WriteRules rules{"sao-viewer", o.overwrite, {}};
  rules.addInput("--scene", o.scene);
  if (Status s = setScreenshotRules(rules, o.screenshot); !s) {
    if (s.code == StatusCode::InvalidInput) cl.fail(s.message);
    std::fprintf(stderr, "sao-viewer: %s: %s\n", toString(s.code), s.message.c_str());  // as a failed run
    std::exit(1);
  }
  if (o.frames > 0) o.vsync = false;  // scripted runs go as fast as they can
  return o;
}

}  // namespace sao::viewer
