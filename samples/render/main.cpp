// sao-render: the main job. Renders a scene's depth, runs SAO on a backend and writes the AO, a
// lit image with and without it, and a summary. `sao-render --help` lists the options.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "sao/io.h"
#include "sao/presets.h"
#include "sao/prepass/prepass.h"
#include "sao/raytrace/raytrace.h"
#include "sao/samples/backend_runner.h"
#include "sao/samples/shading.h"
#include "sao/scenes/scene.h"
#include "summary.h"

namespace fs = std::filesystem;
using namespace sao;

namespace {

constexpr const char* kUsage = R"(usage: sao-render [options]
Renders a scene's depth, runs Scalable Ambient Obscurance and writes into the output folder:
ao.png (8-bit), ao.exr (float), lit.png and lit_no_ao.png (environment light with and without
AO), summary.txt (per-pass times, the plan and its memory) and, with --json, summary.json.

  --out DIR             output folder (default: out/render)
  --backend NAME        gl | vulkan | cpu | auto (default auto: the first that starts)
  --scene NAME|PATH     built-in scene: sponza-like (default), sphere-plane, crease, thin, gears;
                        or a mesh file (.gltf .glb .obj .ply; file units as metres, one view
                        looking at the whole mesh) or a scene file (.scene, docs/scene-format.md)
  --view N              the scene's view number (default 0)
  --eye X,Y,Z --target X,Y,Z
                        an explicit camera for the scene (metres, y up; both together), with
                        --fovy (default 60) and --near (default 0.1); replaces --view
  --size WxH            AO size in pixels (default 1280x720)
  --guard N             guard band in pixels on each side (default 0)
  --preset NAME         low | medium | high | ultra | reference (default: the settings' defaults)
  --set NAME=VALUE      any setting (repeatable), checked against its range
  --depth-format F      D16 | D24 | D32F (default D32F, reversed-Z, [0,1] clip, infinite far)
  --depth-source S      how a scene's depth is made: raster (the rasterising prepass of the
                        backend's API; cpu uses GL, else Vulkan), raytrace (Embree primary rays),
                        auto (default: raster when a prepass starts, else raytrace; the summary
                        says which)
  --depth FILE.exr      run on your own depth buffer; the camera comes from the file's sao.*
                        attributes or from --fovy/--near/--far/--clip/--reversed-z
  --fovy DEG --near M --far M|inf --clip gl|zero-one --reversed-z
  --save-depth FILE.exr write the depth input with its camera (a file --depth reads back)
  --dump-passes DIR     every intermediate image as EXR
  --reference           also the ray-traced reference (near-field AO within the radius) and the
                        error metrics, for a scene (not --depth); --reference-rays N (default 256)
  --json                write summary.json too
  --help                this text
Exit status: 0 on success, 1 when the run fails, 2 for bad options; errors are one line on stderr.
)";

struct Options {
  std::string out = "out/render", backend = "auto", scene = std::string(scenes::kDefaultScene), depthPath, dumpDir,
              saveDepth, depthSource = "auto";
  std::uint32_t view = 0, width = 1280, height = 720, guard = 0, referenceRays = 256;
  std::string preset, clip = "zero-one";
  DepthFormat depthFormat = DepthFormat::D32F;
  double fovyDegrees = 60, nearDistance = 0.1, far = INFINITY;
  std::optional<glm::dvec3> eye, target;
  bool reversedZ = false, reversedGiven = false, cameraFlags = false, reference = false, json = false;
  std::vector<std::string> sets;
};

[[noreturn]] void usageError(const std::string& message) {
  std::fprintf(stderr, "sao-render: %s (see --help)\n", message.c_str());
  std::exit(2);
}

[[noreturn]] void runError(const Status& s) {
  std::fprintf(stderr, "sao-render: %s: %s\n", toString(s.code), s.message.c_str());
  std::exit(1);
}

std::uint32_t parseCount(const std::string& flag, const std::string& v, std::uint32_t lo, std::uint32_t hi) {
  char* end = nullptr;
  const long long n = std::strtoll(v.c_str(), &end, 10);
  if (v.empty() || *end || n < lo || n > hi)
    usageError(flag + " expects a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" + v + "'");
  return static_cast<std::uint32_t>(n);
}

double parseNumber(const std::string& flag, const std::string& v) {
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (v.empty() || *end || !std::isfinite(d)) usageError(flag + " expects a finite number, got '" + v + "'");
  return d;
}

glm::dvec3 parsePoint(const std::string& flag, const std::string& v) {
  glm::dvec3 p;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = v.find(',', start);
    if ((i < 2) != (comma != std::string::npos)) usageError(flag + " expects X,Y,Z, got '" + v + "'");
    p[i] = parseNumber(flag, v.substr(start, i < 2 ? comma - start : std::string::npos));
    start = comma + 1;
  }
  return p;
}

DepthFormat parseDepthFormat(const std::string& f) {
  if (f == "D16") return DepthFormat::D16;
  if (f == "D24") return DepthFormat::D24;
  if (f == "D32F") return DepthFormat::D32F;
  usageError("--depth-format expects D16, D24 or D32F, got '" + f + "'");
}

Options parse(int argc, char** argv) {
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
    } else if (a == "--out") o.out = value();
    else if (a == "--backend") o.backend = value();
    else if (a == "--scene") o.scene = value();
    else if (a == "--depth-source") {
      o.depthSource = value();
      if (o.depthSource != "auto" && o.depthSource != "raster" && o.depthSource != "raytrace")
        usageError("--depth-source expects raster, raytrace or auto");
    } else if (a == "--view") o.view = parseCount(a, value(), 0, 1000);
    else if (a == "--size") {
      const std::string v = value();
      const auto x = v.find('x');
      if (x == std::string::npos) usageError("--size expects WxH, got '" + v + "'");
      o.width = parseCount("--size width", v.substr(0, x), 1, kMaxImageSide);
      o.height = parseCount("--size height", v.substr(x + 1), 1, kMaxImageSide);
    } else if (a == "--guard") o.guard = parseCount(a, value(), 0, 4096);
    else if (a == "--preset") o.preset = value();
    else if (a == "--set") o.sets.push_back(value());
    else if (a == "--depth-format") o.depthFormat = parseDepthFormat(value());
    else if (a == "--depth") o.depthPath = value();
    else if (a == "--eye") o.eye = parsePoint(a, value());
    else if (a == "--target") o.target = parsePoint(a, value());
    else if (a == "--fovy") o.fovyDegrees = parseNumber(a, value()), o.cameraFlags = true;
    else if (a == "--near") o.nearDistance = parseNumber(a, value()), o.cameraFlags = true;
    else if (a == "--far") {
      const std::string v = value();
      o.far = v == "inf" ? INFINITY : parseNumber(a, v);
      o.cameraFlags = true;
    } else if (a == "--clip") {
      o.clip = value();
      o.cameraFlags = true;
      if (o.clip != "gl" && o.clip != "zero-one") usageError("--clip expects gl or zero-one, got '" + o.clip + "'");
    }
    else if (a == "--reversed-z") o.reversedZ = o.reversedGiven = o.cameraFlags = true;
    else if (a == "--dump-passes") o.dumpDir = value();
    else if (a == "--save-depth") o.saveDepth = value();
    else if (a == "--reference") o.reference = true;
    else if (a == "--reference-rays") o.referenceRays = parseCount(a, value(), 1, 1u << 16);
    else if (a == "--json") o.json = true;
    else usageError("unknown option '" + a + "'");
  }
  if (o.eye.has_value() != o.target.has_value()) usageError("--eye and --target go together");
  // Refused here, not after the AO was written: a depth file has no geometry to trace.
  if (o.reference && !o.depthPath.empty()) usageError("--reference needs a scene, not a --depth file (no geometry to trace)");
  return o;
}

Settings buildSettings(const Options& o) {
  Settings s;
  if (!o.preset.empty()) {
    const auto p = findPreset(o.preset);
    if (!p) usageError("unknown preset '" + o.preset + "' (low, medium, high, ultra, reference)");
    s = presetSettings(*p);
  }
  for (const auto& set : o.sets)
    if (Status st = setFromAssignment(s, set); !st) usageError(st.message);
  return s;
}

Camera cameraFromFlags(const Options& o, Extent inputExtent) {
  if (!(o.fovyDegrees > 0 && o.fovyDegrees < 180)) usageError("--fovy must be in (0, 180) degrees");
  Camera c = perspectiveCamera(o.fovyDegrees * std::numbers::pi / 180.0, inputExtent.width - 2 * o.guard,
                               inputExtent.height - 2 * o.guard, o.nearDistance, o.far,
                               o.clip == "gl" ? ClipDepth::NegativeOneToOne : ClipDepth::ZeroToOne, o.reversedZ);
  c.guardBand = o.guard;
  return c;
}

// The depth of a scene view: rasterised by a prepass (the backend's own API where it has one), or
// ray-cast. `how` says which, for the summary.
Status makeSceneDepth(const Options& o, const samples::BackendRunner& backend, const scenes::Scene& scene,
                      const scenes::View& view, const Camera& camera, const raytrace::RayScene& rays,
                      raytrace::Primary& primary, std::string& how) {
  std::string whyNot;
  if (o.depthSource != "raytrace") {
    const std::string api = backend.name() == "gl" || backend.name() == "vulkan" ? std::string(backend.name()) : "auto";
    std::unique_ptr<prepass::Prepass> prepass;
    Status started = prepass::createPrepass(api, prepass);
    if (started) {
      prepass::PrepassOptions po;
      po.format = o.depthFormat;
      prepass::PrepassResult r;
      if (Status s = prepass->render(scene.mesh, view, camera, po, r); !s) return s;
      primary.depth = std::move(r.depth);
      primary.position = std::move(r.position);
      primary.normal = std::move(r.normal);
      how = "rasterised by the " + std::string(prepass->name()) + " prepass";
      return Status::success();
    }
    if (o.depthSource == "raster") return started;
    whyNot = " (no rasterising prepass: " + started.message + ")";
  }
  if (Status s = raytrace::castPrimary(rays, view, camera, o.depthFormat, primary); !s) return s;
  how = "by ray casting" + whyNot;
  return Status::success();
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const Settings settings = buildSettings(o);
  if (Status s = validate(settings); !s) usageError(s.message);

  std::unique_ptr<samples::BackendRunner> backend;
  if (Status s = samples::createBackend(o.backend, backend); !s) {
    if (s.code == StatusCode::InvalidInput) usageError(s.message);  // an unknown name is a bad option
    runError(s);
  }

  samples::Summary summary;
  summary.backend = backend->description();
  Camera camera;
  DepthImage depth;
  raytrace::Primary primary;
  bool havePrimary = false;
  scenes::Scene scene;
  std::uint32_t viewIndex = o.view;  // or the explicit --eye/--target view, appended
  std::unique_ptr<raytrace::RayScene> rayScene;
  const auto t0 = std::chrono::steady_clock::now();

  if (!o.depthPath.empty()) {
    bool hasCamera = false;
    if (Status s = readDepthExr(o.depthPath, depth, camera, hasCamera); !s) runError(s);
    if (!hasCamera) {
      if (!o.cameraFlags)
        usageError("'" + o.depthPath + "' carries no sao.* camera: give --fovy, --near, --far, --clip (and --reversed-z)");
      camera = cameraFromFlags(o, depth.extent);
    }
    summary.input = "depth file " + o.depthPath + " (" + toString(depth.format) + ")";
  } else {
    if (Status s = scenes::loadScene(o.scene, scene); !s) runError(s);
    if (o.view >= scene.views.size())
      usageError("--view " + std::to_string(o.view) + " is out of range: scene '" + o.scene + "' has views 0.." +
                 std::to_string(scene.views.size() - 1));
    if (o.eye) {
      const glm::dvec3 forward = *o.target - *o.eye;
      if (glm::length(glm::cross(forward, glm::dvec3(0, 1, 0))) <= 1e-9 * glm::length(forward))
        usageError("--eye and --target must differ and not look straight up or down (y is up)");
      if (!(o.fovyDegrees > 0 && o.fovyDegrees < 180)) usageError("--fovy must be in (0, 180) degrees");
      if (!(o.nearDistance > 0)) usageError("--near must be > 0");
      scenes::View v;
      v.name = "explicit";
      v.eye = *o.eye;
      v.target = *o.target;
      v.fovyRadians = o.fovyDegrees * std::numbers::pi / 180.0;
      v.nearDistance = o.nearDistance;
      scene.views.push_back(v);
      viewIndex = std::uint32_t(scene.views.size() - 1);
    }
    const scenes::View& view = scene.views[viewIndex];
    camera = scenes::makeCamera(view, o.width, o.height, INFINITY, ClipDepth::ZeroToOne, true, o.guard);
    if (Status s = raytrace::RayScene::create(scene.mesh, rayScene); !s) runError(s);
    std::string how;
    if (Status s = makeSceneDepth(o, *backend, scene, view, camera, *rayScene, primary, how); !s) runError(s);
    depth = primary.depth;
    havePrimary = true;
    summary.input = "scene " + o.scene + ", view " + std::to_string(viewIndex) + " '" + view.name + "', " +
                    toString(depth.format) + " reversed-Z [0,1] infinite far, depth " + how;
  }
  summary.prepareSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Only once the input is known good, so a refused run leaves no output folder behind.
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) runError(Status::error(StatusCode::IoError, "cannot create output folder '" + o.out + "': " + ec.message()));
  if (!o.saveDepth.empty())
    if (Status s = writeDepthExr(o.saveDepth, depth, camera); !s) runError(s);

  samples::RunInputs inputs{&depth, nullptr, nullptr};
  samples::RunOutputs result;
  if (Status s = backend->run(settings, camera, inputs, true, !o.dumpDir.empty(), result); !s) runError(s);

  const std::string aoPng = (fs::path(o.out) / "ao.png").string();
  if (Status s = writeAoPng(aoPng, result.ao); !s) runError(s);
  if (Status s = writeFloatExr((fs::path(o.out) / "ao.exr").string(), result.ao, {"A"}); !s) runError(s);
  if (havePrimary) {
    const FloatImage lit = samples::shadeEnvironment(primary.normal, primary.position, &result.ao, camera.guardBand);
    const FloatImage unlit = samples::shadeEnvironment(primary.normal, primary.position, nullptr, camera.guardBand);
    if (Status s = samples::writeRgbPng((fs::path(o.out) / "lit.png").string(), lit); !s) runError(s);
    if (Status s = samples::writeRgbPng((fs::path(o.out) / "lit_no_ao.png").string(), unlit); !s) runError(s);
  }
  if (!o.dumpDir.empty()) {
    fs::create_directories(o.dumpDir, ec);
    if (ec) runError(Status::error(StatusCode::IoError, "cannot create '" + o.dumpDir + "': " + ec.message()));
    for (const auto& [name, image] : result.intermediates) {
      std::vector<std::string> channels;
      for (std::uint32_t c = 0; c < image.channels; ++c) channels.push_back(image.channels == 1 ? "Y" : std::string(1, "RGBA"[c]));
      if (Status s = writeFloatExr((fs::path(o.dumpDir) / (name + ".exr")).string(), image, channels); !s) runError(s);
    }
  }
  if (o.reference) {
    raytrace::ReferenceOptions ro;
    ro.radius = settings.radius;
    ro.rays = o.referenceRays;
    FloatImage ref;
    if (Status s = raytrace::referenceAmbientOcclusion(*rayScene, camera, primary, scene.views[viewIndex], ro, ref); !s)
      runError(s);
    if (Status s = writeAoPng((fs::path(o.out) / "reference.png").string(), ref); !s) runError(s);
    summary.metrics = samples::compareToReference(result.ao, ref, samples::geometryMask(primary.position, camera.guardBand));
    summary.referenceRays = o.referenceRays;
  }
  summary.settings = settings;
  summary.plan = result.plan;
  summary.timings = result.timings;
  summary.size = {camera.width, camera.height};
  summary.guard = camera.guardBand;
  const std::string text = summary.text();
  std::ofstream((fs::path(o.out) / "summary.txt").string()) << text;
  if (o.json) std::ofstream((fs::path(o.out) / "summary.json").string()) << summary.json();
  std::fputs(text.c_str(), stdout);
  std::printf("output: %s\n", fs::absolute(o.out).lexically_normal().string().c_str());
  return 0;
}
