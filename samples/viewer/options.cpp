#include "options.h"

#include <cstdio>
#include <cstdlib>

#include "sao/presets.h"

namespace sao::viewer {
namespace {

constexpr const char* kUsage = R"(usage: sao-viewer [options]
Interactive Scalable Ambient Obscurance: a GLFW window that rasterises a scene's depth, runs the
sao effect on it every frame and shows the result, with a Dear ImGui panel generated from the
effect's settings metadata, live per-pass timings and the plan.

  --backend gl|vulkan   gl (default): a GL 4.3+ core context; the viewer renders its own D32F
                        depth texture (reversed-Z via glClipControl when available) and runs
                        sao::gl::Effect on it. vulkan: a Vulkan window (VK_KHR_swapchain) with a
                        depth-only prepass pipeline, sao::vk::Effect recorded into the frame's
                        command buffer, the composite and ImGui (imgui_impl_vulkan) presented
                        through the swapchain.
  --scene NAME|PATH     built-in scene: sponza-like (default), sphere-plane, crease, thin, gears;
                        or a mesh file (.gltf .glb .obj .ply) or a scene file (.scene)
  --view N              the scene's view number (default 0)
  --units U             the --scene's length unit: m | cm | mm | in | ft, or auto (OBJ and PLY: a
                        scale that makes the bounding-box diagonal 5 m, printed at start).
                        Default: the scene's own (built-in and glTF metres, a .scene file's
                        `units` line), else metres. Settings stay in metres and are converted
  --size WxH            window size (default 1280x720)
  --preset NAME         low | medium | high | ultra | reference
  --set NAME=VALUE      any setting (repeatable), checked against its range
  --view-mode MODE      ao | lit (default) | lit-no-ao | split | raw-ao | z-mip | normals | error
  --z-level N           csz MIP level for the z-mip view (default 1)
  --reference           compute the ray-traced reference at start (the error view needs it)
  --reference-rays N    rays per pixel of the reference (default 32)
  --screenshot FILE     with --frames: save the window as PNG after the last frame and exit
  --frames N            render N frames, then exit (0: until the window closes)
  --hide-ui             start with the panel hidden (H toggles)
  --standard-depth      gl: no glClipControl; standard depth, [-1,1] clip, finite far plane
  --validation          vulkan: VK_LAYER_KHRONOS_validation with synchronization validation
                        (messages on stderr; exit status 3 if it reported any)
  --no-vsync            do not wait for vertical sync
  --help                this text

Keys: 1-8 view modes, F12 screenshot (sao-viewer-<time>.png), R compute the reference,
H hide/show the panel, Tab orbit/fly camera, Home reset the camera, Esc quit.
Mouse: drag to rotate, right or middle drag to pan, wheel to dolly; WASD, Q/E to move.
Exit status: 0 on success, 1 when the run fails, 2 for bad options, 3 when the graphics API
reported errors (GL errors, or Vulkan validation messages with --validation).
)";

[[noreturn]] void usageError(const std::string& message) {
  std::fprintf(stderr, "sao-viewer: %s (see --help)\n", message.c_str());
  std::exit(2);
}

long long parseWhole(const std::string& flag, const std::string& v, long long lo, long long hi) {
  char* end = nullptr;
  const long long n = std::strtoll(v.c_str(), &end, 10);
  if (v.empty() || *end || n < lo || n > hi)
    usageError(flag + " expects a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" +
               v + "'");
  return n;
}

Settings settingsFromOptions(const Options& o) {
  Settings s;
  if (!o.preset.empty()) {
    const auto p = findPreset(o.preset);
    if (!p) usageError("unknown preset '" + o.preset + "' (low, medium, high, ultra, reference)");
    s = presetSettings(*p);
  }
  for (const auto& set : o.sets)
    if (Status st = setFromAssignment(s, set); !st) usageError(st.message);
  if (Status st = validate(s); !st) usageError(st.message);
  return s;
}

}  // namespace

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a == "--backend") {
      o.backend = value();
      if (o.backend != "gl" && o.backend != "vulkan") usageError("--backend expects gl or vulkan, got '" + o.backend + "'");
    } else if (a == "--scene") o.scene = value();
    else if (a == "--view") o.view = std::uint32_t(parseWhole(a, value(), 0, 1000));
    else if (a == "--units") {
      const std::string v = value();
      o.units = scenes::parseLengthUnit(v);
      if (!o.units) usageError("--units expects " + std::string(scenes::kLengthUnitNames) + ", got '" + v + "'");
    }
    else if (a == "--size") {
      const std::string v = value();
      const auto x = v.find('x');
      if (x == std::string::npos) usageError("--size expects WxH, got '" + v + "'");
      o.width = int(parseWhole("--size width", v.substr(0, x), 64, 8192));
      o.height = int(parseWhole("--size height", v.substr(x + 1), 64, 8192));
    } else if (a == "--preset") o.preset = value();
    else if (a == "--set") o.sets.push_back(value());
    else if (a == "--view-mode") {
      const std::string v = value();
      const auto mode = findViewMode(v);
      if (!mode) usageError("--view-mode expects one of " + viewModeNames() + ", got '" + v + "'");
      o.mode = *mode;
    } else if (a == "--z-level") o.zLevel = int(parseWhole(a, value(), 0, 15));
    else if (a == "--reference") o.reference = true;
    else if (a == "--reference-rays") o.referenceRays = std::uint32_t(parseWhole(a, value(), 1, 65536));
    else if (a == "--screenshot") o.screenshot = value();
    else if (a == "--frames") o.frames = std::uint32_t(parseWhole(a, value(), 0, 1000000000));
    else if (a == "--hide-ui") o.hideUi = true;
    else if (a == "--standard-depth") o.standardDepth = true;
    else if (a == "--validation") o.validation = true;
    else if (a == "--no-vsync") o.vsync = false;
    else usageError("unknown option '" + a + "'");
  }
  if (!o.screenshot.empty() && o.frames == 0) usageError("--screenshot needs --frames N");
  if (o.frames > 0) o.vsync = false;  // scripted runs go as fast as they can
  o.settings = settingsFromOptions(o);
  return o;
}

}  // namespace sao::viewer
