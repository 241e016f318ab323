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
#include <string>

#include "sao/cli/command_line.h"
#include "sao/io.h"
#include "sao/prepass/prepass.h"
#include "sao/raytrace/raytrace.h"
#include "sao/samples/backend_runner.h"
#include "sao/samples/output_files.h"
#include "sao/samples/scale_warnings.h"
#include "sao/samples/shading.h"
#include "sao/scenes/scene.h"
#include "options.h"
#include "depth_input.h"
#include "frames.h"
#include "progress.h"
#include "run_timing.h"
#include "summary.h"

namespace fs = std::filesystem;
using namespace sao;
using sao::render::Options;

namespace {

// The outputs being written (staged beside their places until the run succeeds); an error exit
// removes them.
struct StagedOutputs {
  std::unique_ptr<samples::OutputFolder> out, dump;
  std::unique_ptr<samples::OutputFile> depth;
  void abandon() {  // inner ones first: a folder made for --out may hold the others
    depth.reset();
    dump.reset();
    out.reset();
  }
} g_staged;

[[noreturn]] void usageError(const std::string& message) {
  g_staged.abandon();
  cli::exitWithUsageError("sao-render", message);
}

[[noreturn]] void runError(const Status& s) {
  g_staged.abandon();
  std::fprintf(stderr, "sao-render: %s: %s\n", toString(s.code), s.message.c_str());
  std::exit(1);
}

// The projection in words for the summary: its kind, fovy or view height, near and far.
std::string describeProjection(const Camera& camera) {
  DepthModel model;
  if (!analyze(camera, model)) return "?";
  char text[160];
  const double p11 = camera.projection[5];
  if (camera.kind == ProjectionKind::Orthographic)
    std::snprintf(text, sizeof text, "orthographic, view height %g (view units), near %g, far %g", 2.0 / p11,
                  model.nearDistance, model.farDistance);
  else
    std::snprintf(text, sizeof text, "perspective, fovy %g degrees, near %g, far %g",
                  2.0 * std::atan(1.0 / p11) * 180.0 / std::numbers::pi, model.nearDistance, model.farDistance);
  return text;
}

Camera cameraFromFlags(const Options& o, Extent inputExtent) {
  if (!(o.fovyDegrees > 0 && o.fovyDegrees < 180)) usageError("--fovy must be in (0, 180) degrees");
  // The viewport is the file's size less the guard band: a band as wide as the file leaves none.
  if (2ull * o.guard >= std::min(inputExtent.width, inputExtent.height))
    usageError("--guard " + std::to_string(o.guard) + " leaves no viewport inside the " +
               std::to_string(inputExtent.width) + "x" + std::to_string(inputExtent.height) +
               " depth file: at most " + std::to_string((std::min(inputExtent.width, inputExtent.height) - 1) / 2));
  const std::uint32_t w = inputExtent.width - 2 * o.guard, h = inputExtent.height - 2 * o.guard;
  const ClipDepth clip = o.clip == "gl" ? ClipDepth::NegativeOneToOne : ClipDepth::ZeroToOne;
  if (o.orthoHeight) {
    if (Status s = checkOrthographicArguments(0.5 * *o.orthoHeight, w, h, o.nearDistance, o.far); !s)
      usageError("--ortho/--near/--far: " + s.message);
    Camera c = orthographicCamera(0.5 * *o.orthoHeight, w, h, o.nearDistance, o.far, clip, o.reversedZ);
    c.guardBand = o.guard;
    return c;
  }
  if (Status s = checkPerspectiveArguments(o.fovyDegrees * std::numbers::pi / 180.0, w, h, o.nearDistance, o.far); !s)
    usageError("--fovy/--near/--far: " + s.message);
  Camera c = perspectiveCamera(o.fovyDegrees * std::numbers::pi / 180.0, w, h, o.nearDistance, o.far, clip,
                               o.reversedZ);
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

// Where each output is written: staged paths (see sao/samples/output_files.h).
struct OutputPaths {
  std::string aoPng, aoExr, lit, litNoAo, reference, summaryTxt, summaryJson;
  std::string bentExr, bentPng;  // with the setting bent_normals
  std::string saveDepth;   // staged inside an output folder; else g_staged.depth has it
  std::string dumpPrefix;  // the intermediates' names in their folder ("passes/", or "")
};

// The part of `path` inside `folder` ("" for the folder itself), or nullopt when outside.
std::optional<std::string> inside(const fs::path& folder, const std::string& path) {
  const fs::path rel = samples::normalizedPath(path).lexically_relative(folder);
  if (rel.empty() || *rel.begin() == "..") return std::nullopt;
  return rel == "." ? std::string() : rel.string();
}

// A refused output path: a bad option (exit 2) or something in the way on disk (exit 1).
[[noreturn]] void outputError(const Status& s) {
  if (s.code == StatusCode::InvalidInput) usageError(s.message);
  runError(s);
}

// Checks every output path and stages it, before anything is rendered. Exits on a problem.
OutputPaths stageOutputs(const Options& o) {
  OutputPaths p;
  samples::WriteRules rules{"sao-render", o.overwrite, {}};
  if (o.depthPath.empty()) rules.addInput("--scene", o.scene);
  rules.addInput("--depth", o.depthPath);
  if (Status s = samples::OutputFolder::stage(o.out, "--out", rules, g_staged.out); !s) outputError(s);
  samples::OutputFolder& out = *g_staged.out;
  auto reserve = [](samples::OutputFolder& folder, const std::string& name, std::string& path) {
    if (Status s = folder.file(name, path); !s) usageError(s.message);
  };
  reserve(out, "ao.png", p.aoPng);
  reserve(out, "ao.exr", p.aoExr);
  reserve(out, "summary.txt", p.summaryTxt);
  if (o.settings.bent_normals) {
    reserve(out, "bent_normal.exr", p.bentExr);
    reserve(out, "bent_normal.png", p.bentPng);
  }
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
      if (inside(samples::normalizedPath(o.dumpDir), o.out))
        usageError("--out '" + o.out + "' lies inside --dump-passes '" + o.dumpDir + "': give two separate folders");
      if (Status s = samples::OutputFolder::stage(o.dumpDir, "--dump-passes", rules, g_staged.dump); !s)
        outputError(s);
    }
  }
  if (!o.saveDepth.empty()) {
    auto checkName = [&] {  // OutputFile::stage checks it outside the output folders
      if (Status s = samples::checkExtension(o.saveDepth, "--save-depth", rules.program, samples::kExrFormat); !s)
        usageError(s.message);
    };
    if (const auto rel = inside(out.path(), o.saveDepth); rel && !rel->empty()) {
      checkName();
      reserve(out, *rel, p.saveDepth);
    } else if (const auto relDump = g_staged.dump ? inside(g_staged.dump->path(), o.saveDepth) : std::nullopt;
               relDump && !relDump->empty()) {
      checkName();
      reserve(*g_staged.dump, *relDump, p.saveDepth);
    } else if (rel || relDump) {
      usageError("--save-depth '" + o.saveDepth + "' is an output folder, not a file name");
    } else if (Status s = samples::OutputFile::stage(o.saveDepth, "--save-depth", samples::kExrFormat, rules,
                                                     g_staged.depth);
               !s) {
      outputError(s);
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
  const Options o = render::parseOptions(argc, argv);
  const Settings& settings = o.settings;

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
  scenes::View renderedView;         // the scene view the outputs show (--frames: the path's last)
  std::unique_ptr<raytrace::RayScene> rayScene;
  render::Progress progress(o.progressSeconds);
  const OutputPaths paths = stageOutputs(o);  // before rendering: a bad path costs no render
  const auto t0 = std::chrono::steady_clock::now();

  if (!o.depthPath.empty()) {
    progress.begin("reading the depth file");
    DepthFileInfo file;
    DepthReadOptions reading;  // the sky around a cropped data window, in the file's convention
    reading.skyWithoutCamera = o.depthDistances ? INFINITY : o.reversedZ ? 0.0f : 1.0f;
    if (Status s = readDepthExr(o.depthPath, depth, camera, file, reading); !s) runError(s);
    progress.end();
    const bool hasCamera = file.hasCamera;
    if (hasCamera) {
      for (const char* flag : {"--fovy", "--ortho", "--near", "--far", "--clip", "--reversed-z", "--guard", "--units",
                               "--depth-distances"})
        if (o.has(flag))
          usageError(std::string(flag) + " has no effect: '" + o.depthPath +
                     "' carries its own camera (its sao.* attributes)");
    } else {
      std::string saoNames;  // a camera that lacks only sao.version
      for (const std::string& a : file.saoAttributes) saoNames += (saoNames.empty() ? "" : ", ") + a;
      if (!o.cameraFlags && !saoNames.empty())
        usageError("'" + o.depthPath + "' has sao.* attributes (" + saoNames + ") but no sao.version, so they are "
                   "not read as its camera: add the int attribute sao.version = " + std::to_string(kDepthExrVersion) +
                   " (sao/io.h), or give the camera as --fovy (or --ortho), --near, --far, --clip (and --reversed-z)");
      if (!o.cameraFlags)
        usageError("'" + o.depthPath + "' carries no sao.* camera: give --fovy (or --ortho), --near, --far, --clip (and "
                   "--reversed-z), or --depth-distances for distances along the view axis");
      if (!saoNames.empty())
        std::fprintf(stderr, "sao-render: warning: '%s' has sao.* attributes but no sao.version: they are ignored, the "
                     "camera comes from the options\n", o.depthPath.c_str());
      camera = cameraFromFlags(o, depth.extent);
      if (o.units) camera.metersToViewUnits = scenes::metersToViewUnits(*o.units);
      if (o.depthDistances)
        if (Status s = render::distancesToLinearZ(depth, o.far); !s)
          runError(Status::error(s.code, "'" + o.depthPath + "': " + s.message));
    }
    for (const std::string& note : render::depthFileNotes(o.depthPath, file)) {
      std::fprintf(stderr, "sao-render: warning: %s\n", note.c_str());
      summary.inputWarnings.push_back(note);
    }
    summary.units = hasCamera ? "the depth file's sao.metersToViewUnits"
                              : o.units ? std::string(scenes::toString(*o.units)) + " (--units)" : "m (the default)";
    summary.metersToViewUnits = camera.metersToViewUnits;
    // The same refusal on every backend (a GL D32F texture would clamp what the others read as sky).
    if (Status s = checkDepthValues(depth); !s) runError(Status::error(s.code, "'" + o.depthPath + "': " + s.message));
    summary.input = "depth file " + o.depthPath + " (" + toString(depth.format) + ")";
    if (file.storedAsHalf)
      if (const auto w = render::halfPrecisionWarning(o.depthPath, depth, camera, settings.radius)) {
        std::fprintf(stderr, "sao-render: warning: %s\n", w->c_str());
        summary.inputWarnings.push_back(*w);
      }
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
      if (o.orthoHeight) {
        v.orthoHeight = *o.orthoHeight;
        scenes::fitOrthoFar(v, scene.mesh);
      }
      scene.views.push_back(v);
      viewIndex = std::uint32_t(scene.views.size() - 1);
    }
    scenes::View view = scene.views[viewIndex];  // with --frames: the path's last frame below
    camera = scenes::makeCamera(view, o.size.width, o.size.height, INFINITY, ClipDepth::ZeroToOne, true, o.guard);
    const scenes::UnitChoice units = scenes::chooseUnits(scene.mesh, scene.units, o.units);
    camera.metersToViewUnits = units.metersToViewUnits;
    if (units.unit == "auto") std::fprintf(stderr, "sao-render: units %s\n", units.note.c_str());
    summary.units = units.note;
    summary.metersToViewUnits = units.metersToViewUnits;
    progress.begin("building the ray-tracing structure");
    if (Status s = raytrace::RayScene::create(scene.mesh, rayScene); !s) runError(s);
    std::string how;
    // The scene's world is already in its own units, the view units: the depth is drawn with a factor
    // of 1 (the prepass would scale a world in metres by metersToViewUnits; ray casting never does).
    Camera depthCamera = camera;
    depthCamera.metersToViewUnits = 1.0;
    if (o.frames > 1) {
      progress.begin("running " + std::to_string(o.frames) + " frames along the " +
                     std::string(scenes::toString(o.path)) + " path");
      const render::DepthMaker makeDepth = [&](const scenes::View& v, raytrace::Primary& out) {
        return makeSceneDepth(o, *backend, scene, v, depthCamera, *rayScene, out, how);
      };
      render::FramesSummary frames;
      if (Status s = render::runFramePath(o, *backend, settings, view, camera, makeDepth, *g_staged.out, frames,
                                          primary);
          !s)
        runError(s);
      progress.end();
      summary.frames = frames;
      view = scenes::pathView(view, o.path, o.frames - 1, o.frames);
      camera.view = scenes::viewArray(view);  // the path's last pose: the runs below continue from it
    } else {
      progress.begin("rendering the depth");
      if (Status s = makeSceneDepth(o, *backend, scene, view, depthCamera, *rayScene, primary, how); !s) runError(s);
      progress.end();
    }
    depth = primary.depth;
    havePrimary = true;
    renderedView = view;
    summary.input = "scene " + o.scene + ", view " + std::to_string(viewIndex) + " '" + view.name + "', " +
                    toString(depth.format) + " reversed-Z [0,1] " +
                    (view.orthographic() ? "finite far" : "infinite far") +
                    ", depth " + how;
  }
  summary.projection = describeProjection(camera);
  summary.prepareSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (g_staged.depth || !paths.saveDepth.empty())
    if (Status s = writeDepthExr(g_staged.depth ? g_staged.depth->stagedPath() : paths.saveDepth, depth, camera); !s)
      runError(s);

  // One warm-up run (pipelines, allocations, caches), then the measured ones.
  samples::RunInputs inputs{&depth, nullptr, nullptr};
  samples::RunOutputs result;
  std::vector<Timings> timings;
  // Temporal accumulation after a path: these runs are its next frames, at its last pose.
  if (settings.temporal) inputs.frameIndex = o.frames;
  progress.begin("running the effect on " + std::string(backend->name()) + " (1 warm-up + " + std::to_string(o.runs) +
                 " measured run" + (o.runs == 1 ? ")" : "s)"));
  for (std::uint32_t r = 0; r <= o.runs; ++r) {
    result = {};
    if (Status s = backend->run(settings, camera, inputs, true, !o.dumpDir.empty() && r == o.runs, result); !s)
      runError(s);
    if (settings.temporal) ++inputs.frameIndex;
    if (r > 0) timings.push_back(result.timings);
  }
  progress.begin("writing the outputs");
  if (Status s = writeAoPng(paths.aoPng, result.ao); !s) runError(s);
  if (Status s = writeFloatExr(paths.aoExr, result.ao, {"A"}); !s) runError(s);
  if (settings.bent_normals) {
    if (Status s = writeFloatExr(paths.bentExr, result.bentNormals, {"X", "Y", "Z"}); !s) runError(s);
    if (Status s = samples::writeNormalPng(paths.bentPng, result.bentNormals); !s) runError(s);
  }
  if (havePrimary) {
    const FloatImage lit = samples::shadeEnvironment(primary.normal, primary.position, &result.ao, camera.guardBand);
    const FloatImage unlit = samples::shadeEnvironment(primary.normal, primary.position, nullptr, camera.guardBand);
    if (Status s = samples::writeRgbPng(paths.lit, lit); !s) runError(s);
    if (Status s = samples::writeRgbPng(paths.litNoAo, unlit); !s) runError(s);
  }
  if (!o.dumpDir.empty()) {
    samples::OutputFolder& folder = g_staged.dump ? *g_staged.dump : *g_staged.out;
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
    if (Status s = raytrace::referenceAmbientOcclusion(*rayScene, camera, primary, renderedView, ro, ref); !s)
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
