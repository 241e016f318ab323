// sao-render: the main job. Renders a scene's depth, runs SAO on a backend and writes the AO, a
// lit image with and without it, and a summary. `sao-render --help` lists the options.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "sao/io.h"
#include "sao/presets.h"
#include "sao/prepass/prepass.h"
#include "sao/raytrace/raytrace.h"
#include "sao/samples/backend_runner.h"
#include "sao/samples/scale_warnings.h"
#include "sao/samples/shading.h"
#include "sao/scenes/scene.h"
#include "help.h"
#include "output_folder.h"
#include "progress.h"
#include "run_timing.h"
#include "summary.h"

namespace fs = std::filesystem;
using namespace sao;

namespace {

constexpr const char* kUsage = R"(usage: sao-render [options]
Renders a scene's depth, runs Scalable Ambient Obscurance and writes into the output folder:
ao.png (8-bit), ao.exr (float), lit.png and lit_no_ao.png (environment light with and without
AO; a scene only), reference.png (with --reference), summary.txt (per-pass times, the plan and
its memory), summary.json (with --json) and sao-render-outputs.txt (the list of these files).

  --out DIR             output folder (default: out/render). It is replaced as a whole, so no
                        file of an earlier run survives: the run writes into a new folder beside
                        it and swaps it in only once every output is written (a failed run
                        leaves DIR as it was). DIR must be missing, empty, or an earlier output
                        holding only the files its sao-render-outputs.txt lists; any other file
                        in it stops the run before rendering (nothing of yours is deleted)
  --backend NAME        gl | vulkan | cpu (the CPU reference in float, as a GPU computes) |
                        cpu-double (the CPU reference in double) | auto (default: the first of
                        gl, vulkan, cpu that starts)
  --scene NAME|PATH     built-in scene: sponza-like (default), sphere-plane, crease, thin, gears;
                        or a mesh file (.gltf .glb .obj .ply; one view looking at the whole
                        mesh) or a scene file (.scene, docs/scene-format.md)
  --units U             the scene's length unit: m | cm | mm | in | ft, or auto (OBJ and PLY:
                        a scale that makes the bounding-box diagonal 5 m, printed on stderr
                        and in the summary; glTF and built-in scenes keep metres). Default: the
                        scene's own (built-in and glTF metres, a .scene file's `units` line),
                        else metres. Settings stay in metres and are converted; --eye, --target
                        and --near are in the scene's units. With --depth: a file without a
                        sao.* camera (one with it carries sao.metersToViewUnits)
  --view N              the scene's view number (default 0)
  --eye X,Y,Z --target X,Y,Z
                        an explicit camera for the scene (scene units, y up; both together),
                        with --fovy DEG (default 60) and --near D (default 0.1); replaces --view
  --size WxH            AO size in pixels, 1..16384 each (default 1280x720)
  --guard N             guard band in pixels on each side, 0..4096 (default 0)
  --preset NAME         low | medium | high | ultra | reference (default: the settings' defaults)
  --set NAME=VALUE      any setting below (repeatable), checked against its range
  --depth-format F      D16 | D24 | D32F: the precision of a scene's depth (default D32F; always
                        reversed-Z, [0,1] clip, infinite far)
  --depth-source S      how a scene's depth is made: raster (the rasterising prepass of the
                        backend's API; cpu uses GL, else Vulkan), raytrace (Embree primary rays),
                        auto (default: raster when a prepass starts, else raytrace; the summary
                        says which)
  --depth FILE.exr      run on your own depth buffer instead of a scene (format below); the
                        camera comes from the file's sao.* attributes or, for a file without
                        them, from --fovy DEG --near M --far M|inf --clip gl|zero-one
                        --reversed-z --guard N (defaults 60, 0.1, inf, zero-one, off, 0)
  --save-depth FILE.exr write the depth input with its camera (a file --depth reads back); its
                        folder must exist
  --dump-passes DIR     every intermediate image as EXR (a folder handled as --out is)
  --reference           also the ray-traced reference (near-field AO within the radius) and the
                        error metrics, for a scene (not --depth); "n/a" (JSON null) marks a
                        metric that is undefined for the images (e.g. SSIM of two constant ones)
  --reference-rays N    rays per pixel of the reference, 1..65536 (default 256)
  --runs N              measured runs of the effect after one warm-up run, 1..1000 (default 1);
                        the summary gives each pass's median and the fastest..slowest run
  --progress S          a line on stderr every S seconds for a step running longer than S
                        seconds, with the elapsed time and the reference's share done, and one
                        when it ends (default 2; 0: every step, every 0.5 s and each tenth
                        of the reference done)
  --json                write summary.json too
  --help                this text
Any option but --set given twice: the last one counts. Options that would have no effect are
refused (e.g. --fovy for a scene without --eye, --size with --depth, --reference-rays without
--reference).
Exit status: 0 on success, 1 when the run fails (nothing is written then), 2 for bad options;
errors are one line on stderr.
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
  std::uint32_t runs = 1;
  double progressSeconds = 2;
  std::optional<scenes::LengthUnit> units;  // --units
  std::set<std::string> given;  // the options on the command line
  bool has(const char* option) const { return given.count(option) > 0; }
};

// The outputs being written (staged beside their places until the run succeeds); an error exit
// removes them.
struct StagedOutputs {
  std::unique_ptr<render::OutputFolder> out, dump;
  std::unique_ptr<render::OutputFile> depth;
  void abandon() {  // inner ones first: a folder made for --out may hold the others
    depth.reset();
    dump.reset();
    out.reset();
  }
} g_staged;

[[noreturn]] void usageError(const std::string& message) {
  g_staged.abandon();
  std::fprintf(stderr, "sao-render: %s (see --help)\n", message.c_str());
  std::exit(2);
}

[[noreturn]] void runError(const Status& s) {
  g_staged.abandon();
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

// Options that would change nothing in this combination are refused rather than ignored.
void refuseIneffectiveOptions(const Options& o) {
  if (o.has("--depth")) {
    if (o.has("--scene")) usageError("--scene and --depth are two inputs: give one");
    for (const char* scene : {"--view", "--eye", "--target"})
      if (o.has(scene))
        usageError(std::string(scene) + " has no effect with --depth: a depth file carries its camera, or takes "
                   "--fovy/--near/--far/--clip/--reversed-z");
    if (o.has("--size")) usageError("--size has no effect with --depth: the AO has the depth file's size");
    if (o.has("--depth-format")) usageError("--depth-format has no effect with --depth: the file gives its format");
    if (o.has("--depth-source")) usageError("--depth-source has no effect with --depth: the file is the depth");
    if (o.units == scenes::LengthUnit::Auto)
      usageError("--units auto needs a scene's bounding box: a --depth file takes m, cm, mm, in or ft");
  } else {
    for (const char* flag : {"--fovy", "--near"})
      if (o.has(flag) && !o.has("--eye"))
        usageError(std::string(flag) + " has no effect without --eye: a scene's view has its own camera");
    for (const char* flag : {"--far", "--clip", "--reversed-z"})
      if (o.has(flag))
        usageError(std::string(flag) + " is for a --depth file without a camera: a scene's depth is always "
                   "reversed-Z, [0,1] clip, infinite far");
    if (o.has("--view") && o.has("--eye"))
      usageError("--view has no effect with --eye/--target, which replace the view");
  }
  if (o.has("--reference-rays") && !o.reference) usageError("--reference-rays has no effect without --reference");
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usageError(a + " needs a value");
      if (!*argv[i + 1]) usageError(a + " needs a value, got an empty string");
      return argv[++i];
    };
    o.given.insert(a);
    if (a == "--help" || a == "-h") {
      const std::string help = kUsage + render::settingsHelp() + render::depthExrHelp();
      std::fputs(help.c_str(), stdout);
      std::exit(std::fflush(stdout) == 0 && !std::ferror(stdout) ? 0 : 1);
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
    else if (a == "--units") {
      const std::string v = value();
      o.units = scenes::parseLengthUnit(v);
      if (!o.units) usageError("--units expects " + std::string(scenes::kLengthUnitNames) + ", got '" + v + "'");
    }
    else if (a == "--runs") o.runs = parseCount(a, value(), 1, 1000);
    else if (a == "--progress") {
      o.progressSeconds = parseNumber(a, value());
      if (!(o.progressSeconds >= 0 && o.progressSeconds <= 3600)) usageError("--progress expects seconds in [0, 3600]");
    } else usageError("unknown option '" + a + "'");
  }
  refuseIneffectiveOptions(o);
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
  // The viewport is the file's size less the guard band: a band as wide as the file leaves none.
  if (2ull * o.guard >= std::min(inputExtent.width, inputExtent.height))
    usageError("--guard " + std::to_string(o.guard) + " leaves no viewport inside the " +
               std::to_string(inputExtent.width) + "x" + std::to_string(inputExtent.height) +
               " depth file: at most " + std::to_string((std::min(inputExtent.width, inputExtent.height) - 1) / 2));
  if (Status s = checkPerspectiveArguments(o.fovyDegrees * std::numbers::pi / 180.0, inputExtent.width - 2 * o.guard,
                                           inputExtent.height - 2 * o.guard, o.nearDistance, o.far);
      !s)
    usageError("--fovy/--near/--far: " + s.message);
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

// Where each output is written: staged paths (see output_folder.h).
struct OutputPaths {
  std::string aoPng, aoExr, lit, litNoAo, reference, summaryTxt, summaryJson;
  std::string saveDepth;   // staged inside an output folder; else g_staged.depth has it
  std::string dumpPrefix;  // the intermediates' names in their folder ("passes/", or "")
};

// The part of `path` inside `folder` ("" for the folder itself), or nullopt when outside.
std::optional<std::string> inside(const fs::path& folder, const std::string& path) {
  const fs::path rel = render::normalizedPath(path).lexically_relative(folder);
  if (rel.empty() || *rel.begin() == "..") return std::nullopt;
  return rel == "." ? std::string() : rel.string();
}

// Checks every output path and stages it, before anything is rendered. Exits on a problem.
OutputPaths stageOutputs(const Options& o) {
  OutputPaths p;
  if (Status s = render::OutputFolder::stage(o.out, "--out", g_staged.out); !s) runError(s);
  render::OutputFolder& out = *g_staged.out;
  auto reserve = [](render::OutputFolder& folder, const std::string& name, std::string& path) {
    if (Status s = folder.file(name, path); !s) usageError(s.message);
  };
  reserve(out, "ao.png", p.aoPng);
  reserve(out, "ao.exr", p.aoExr);
  reserve(out, "summary.txt", p.summaryTxt);
  if (o.depthPath.empty()) {
    reserve(out, "lit.png", p.lit);
    reserve(out, "lit_no_ao.png", p.litNoAo);
  }
  if (o.reference) reserve(out, "reference.png", p.reference);
  if (o.json) reserve(out, "summary.json", p.summaryJson);
  if (!o.dumpDir.empty()) {
    if (const auto rel = inside(out.path(), o.dumpDir)) {
      p.dumpPrefix = rel->empty() ? "" : *rel + "/";
      if (!rel->empty())
        if (Status s = out.folder(*rel); !s) usageError("--dump-passes: " + s.message);
    } else {
      if (inside(render::normalizedPath(o.dumpDir), o.out))
        usageError("--out '" + o.out + "' lies inside --dump-passes '" + o.dumpDir + "': give two separate folders");
      if (Status s = render::OutputFolder::stage(o.dumpDir, "--dump-passes", g_staged.dump); !s) runError(s);
    }
  }
  if (!o.saveDepth.empty()) {
    if (const auto rel = inside(out.path(), o.saveDepth); rel && !rel->empty()) {
      reserve(out, *rel, p.saveDepth);
    } else if (const auto relDump = g_staged.dump ? inside(g_staged.dump->path(), o.saveDepth) : std::nullopt;
               relDump && !relDump->empty()) {
      reserve(*g_staged.dump, *relDump, p.saveDepth);
    } else if (rel || relDump) {
      usageError("--save-depth '" + o.saveDepth + "' is an output folder, not a file name");
    } else if (Status s = render::OutputFile::stage(o.saveDepth, "--save-depth", g_staged.depth); !s) {
      runError(s);
    }
  }
  return p;
}

// A text output, every step of the write checked.
Status writeText(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  if (f) f << text;
  if (f) f.close();
  if (!f) return Status::error(StatusCode::IoError, "cannot write '" + path + "': " + std::strerror(errno));
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
  render::Progress progress(o.progressSeconds);
  const OutputPaths paths = stageOutputs(o);  // before rendering: a bad path costs no render
  const auto t0 = std::chrono::steady_clock::now();

  if (!o.depthPath.empty()) {
    bool hasCamera = false;
    progress.begin("reading the depth file");
    if (Status s = readDepthExr(o.depthPath, depth, camera, hasCamera); !s) runError(s);
    progress.end();
    if (hasCamera) {
      for (const char* flag : {"--fovy", "--near", "--far", "--clip", "--reversed-z", "--guard", "--units"})
        if (o.has(flag))
          usageError(std::string(flag) + " has no effect: '" + o.depthPath +
                     "' carries its own camera (its sao.* attributes)");
    } else {
      if (!o.cameraFlags)
        usageError("'" + o.depthPath + "' carries no sao.* camera: give --fovy, --near, --far, --clip (and --reversed-z)");
      camera = cameraFromFlags(o, depth.extent);
      if (o.units) camera.metersToViewUnits = scenes::metersToViewUnits(*o.units);
    }
    summary.units = hasCamera ? "the depth file's sao.metersToViewUnits"
                              : o.units ? std::string(scenes::toString(*o.units)) + " (--units)" : "m (the default)";
    summary.metersToViewUnits = camera.metersToViewUnits;
    // The same refusal on every backend (a GL D32F texture would clamp what the others read as sky).
    if (Status s = checkDepthValues(depth); !s) runError(Status::error(s.code, "'" + o.depthPath + "': " + s.message));
    summary.input = "depth file " + o.depthPath + " (" + toString(depth.format) + ")";
  } else {
    progress.begin("loading the scene");
    if (Status s = scenes::loadScene(o.scene, scene); !s) runError(s);
    progress.end();
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "sao-render: warning: %s\n", w.c_str());
    summary.inputWarnings = scene.warnings;
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
    const scenes::UnitChoice units = scenes::chooseUnits(scene.mesh, scene.units, o.units);
    camera.metersToViewUnits = units.metersToViewUnits;
    if (units.unit == "auto") std::fprintf(stderr, "sao-render: units %s\n", units.note.c_str());
    summary.units = units.note;
    summary.metersToViewUnits = units.metersToViewUnits;
    progress.begin("building the ray-tracing structure");
    if (Status s = raytrace::RayScene::create(scene.mesh, rayScene); !s) runError(s);
    std::string how;
    progress.begin("rendering the depth");
    // The scene's world is already in its own units, the view units: the depth is drawn with a factor
    // of 1 (the prepass would scale a world in metres by metersToViewUnits; ray casting never does).
    Camera depthCamera = camera;
    depthCamera.metersToViewUnits = 1.0;
    if (Status s = makeSceneDepth(o, *backend, scene, view, depthCamera, *rayScene, primary, how); !s) runError(s);
    progress.end();
    depth = primary.depth;
    havePrimary = true;
    summary.input = "scene " + o.scene + ", view " + std::to_string(viewIndex) + " '" + view.name + "', " +
                    toString(depth.format) + " reversed-Z [0,1] infinite far, depth " + how;
  }
  summary.prepareSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (g_staged.depth || !paths.saveDepth.empty())
    if (Status s = writeDepthExr(g_staged.depth ? g_staged.depth->stagedPath() : paths.saveDepth, depth, camera); !s)
      runError(s);

  // One warm-up run (pipelines, allocations, caches), then the measured ones.
  samples::RunInputs inputs{&depth, nullptr, nullptr};
  samples::RunOutputs result;
  std::vector<Timings> timings;
  progress.begin("running the effect on " + std::string(backend->name()) + " (1 warm-up + " + std::to_string(o.runs) +
                 " measured run" + (o.runs == 1 ? ")" : "s)"));
  for (std::uint32_t r = 0; r <= o.runs; ++r) {
    result = {};
    if (Status s = backend->run(settings, camera, inputs, true, !o.dumpDir.empty() && r == o.runs, result); !s)
      runError(s);
    if (r > 0) timings.push_back(result.timings);
  }
  progress.begin("writing the outputs");
  if (Status s = writeAoPng(paths.aoPng, result.ao); !s) runError(s);
  if (Status s = writeFloatExr(paths.aoExr, result.ao, {"A"}); !s) runError(s);
  if (havePrimary) {
    const FloatImage lit = samples::shadeEnvironment(primary.normal, primary.position, &result.ao, camera.guardBand);
    const FloatImage unlit = samples::shadeEnvironment(primary.normal, primary.position, nullptr, camera.guardBand);
    if (Status s = samples::writeRgbPng(paths.lit, lit); !s) runError(s);
    if (Status s = samples::writeRgbPng(paths.litNoAo, unlit); !s) runError(s);
  }
  if (!o.dumpDir.empty()) {
    render::OutputFolder& folder = g_staged.dump ? *g_staged.dump : *g_staged.out;
    for (const auto& [name, image] : result.intermediates) {
      std::vector<std::string> channels;
      for (std::uint32_t c = 0; c < image.channels; ++c) channels.push_back(image.channels == 1 ? "Y" : std::string(1, "RGBA"[c]));
      std::string path;
      if (Status s = folder.file(paths.dumpPrefix + name + ".exr", path); !s) runError(s);
      if (Status s = writeFloatExr(path, image, channels); !s) runError(s);
    }
  }
  progress.end();
  if (o.reference) {
    raytrace::ReferenceOptions ro;
    ro.radius = settings.radius * camera.metersToViewUnits;  // the scene's units
    ro.rays = o.referenceRays;
    ro.progress = [&](std::uint32_t rows, std::uint32_t of) { progress.fraction(double(rows) / of); };
    FloatImage ref;
    progress.begin("tracing the reference (" + std::to_string(o.referenceRays) + " rays/pixel)");
    if (Status s = raytrace::referenceAmbientOcclusion(*rayScene, camera, primary, scene.views[viewIndex], ro, ref); !s)
      runError(s);
    progress.end();
    if (Status s = writeAoPng(paths.reference, ref); !s) runError(s);
    summary.metrics = samples::compareToReference(result.ao, ref, samples::geometryMask(primary.position, camera.guardBand));
    summary.referenceRays = o.referenceRays;
  }
  samples::ScaleCheck scale;  // does the radius suit the scene's scale? (scale_warnings.h)
  if (Status s = samples::checkScale(settings, camera, depth, result.ao, scale); !s) runError(s);
  for (const std::string& w : scale.warnings) std::fprintf(stderr, "sao-render: warning: %s\n", w.c_str());
  summary.scale = scale;
  summary.settings = settings;
  summary.plan = result.plan;
  summary.timing = render::summarizeRuns(timings);
  summary.size = {camera.width, camera.height};
  summary.guard = camera.guardBand;
  const std::string text = summary.text();
  if (Status s = writeText(paths.summaryTxt, text); !s) runError(s);
  if (o.json)
    if (Status s = writeText(paths.summaryJson, summary.json()); !s) runError(s);
  std::fputs(text.c_str(), stdout);
  std::printf("output: %s\n", g_staged.out->path().string().c_str());
  if (std::fflush(stdout) != 0 || std::ferror(stdout))
    runError(Status::error(StatusCode::IoError, std::string("cannot write the summary to stdout: ") +
                                                    std::strerror(errno)));
  // Into place only now that every output is written.
  if (g_staged.depth)
    if (Status s = g_staged.depth->commit(); !s) runError(s);
  if (g_staged.dump)
    if (Status s = g_staged.dump->commit(); !s) runError(s);
  if (Status s = g_staged.out->commit(); !s) runError(s);
  return 0;
}
