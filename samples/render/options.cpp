#include "options.h"

#include <cmath>
#include <initializer_list>
#include <optional>

#include "help.h"
#include "sao/cli/command_line.h"
#include "sao/cli/shared_options.h"
#include "sao/samples/output_files.h"

namespace sao::render {
namespace {

constexpr const char* kTool = "sao-render";

constexpr const char* kDescription =
    R"(Renders a scene's depth, runs Scalable Ambient Obscurance and writes into the output folder:
ao.png (8-bit), ao.exr (float), lit.png and lit_no_ao.png (environment light with and without
AO; a scene only), reference.png (with --reference), bent_normal.exr (camera space, X Y Z) and
bent_normal.png (0.5 + 0.5 b) with --set bent_normals=true, summary.txt (per-pass times, the plan
and its memory), summary.json (with --json) and sao-render-outputs.txt (the list of these files).)";

constexpr const char* kRules = R"(Any option but --set given twice: the last one counts. Options that would have no effect are
refused (e.g. --fovy for a scene without --eye, --size with --depth, --reference-rays without
--reference), and so is a --set setting that the final settings (the preset, every --set and
--resolution-divisor) make inert, as the effect declares (the list below): --set fade_start
while fade_end = 0. A preset's own values are never refused.
Outputs (--out, --dump-passes, --save-depth) replace no file sao-render did not write unless
--overwrite is given, never an input, and a file's name must end in its format's extension; they
are checked before rendering (a bad name: exit 2; a file or folder in the way: exit 1).
Exit status: 0 on success, 1 when the run fails (nothing is written then), 2 for bad options;
errors are one line on stderr.
)";

[[noreturn]] void usageError(const std::string& message) { cli::exitWithUsageError(kTool, message); }

glm::dvec3 parsePoint(const std::string& option, const std::string& v) {
  glm::dvec3 p;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = v.find(',', start);
    if ((i < 2) != (comma != std::string::npos)) cli::reject(option + " expects X,Y,Z, got '" + v + "'");
    p[i] = cli::parseNumber(option, v.substr(start, i < 2 ? comma - start : std::string::npos));
    start = comma + 1;
  }
  return p;
}

// One of `words`, for cli::CommandLine::choice.
auto oneOf(std::initializer_list<const char*> words) {
  std::set<std::string> set(words.begin(), words.end());
  return [set](const std::string& v) { return set.count(v) ? std::optional<std::string>(v) : std::nullopt; };
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
    if (o.depthDistances)
      for (const char* flag : {"--clip", "--reversed-z"})
        if (o.has(flag))
          usageError(std::string(flag) + " has no effect with --depth-distances: distances have no depth-buffer "
                     "convention");
    if (o.units == scenes::LengthUnit::Auto)
      usageError("--units auto needs a scene's bounding box: a --depth file takes m, cm, mm, in or ft");
  } else {
    for (const char* flag : {"--fovy", "--near", "--ortho"})
      if (o.has(flag) && !o.has("--eye"))
        usageError(std::string(flag) + " has no effect without --eye: a scene's view has its own camera");
    if (o.depthDistances) usageError("--depth-distances describes a --depth file: it has no effect without --depth");
    for (const char* flag : {"--far", "--clip", "--reversed-z"})
      if (o.has(flag))
        usageError(std::string(flag) + " is for a --depth file without a camera: a scene's depth is always "
                   "reversed-Z, [0,1] clip, infinite far (orthographic: a far plane just beyond the scene)");
    if (o.has("--view") && o.has("--eye"))
      usageError("--view has no effect with --eye/--target, which replace the view");
  }
  if (o.has("--ortho") && o.has("--fovy"))
    usageError("--ortho and --fovy exclude each other: an orthographic camera has a view height, not a field of view");
  if (o.has("--reference-rays") && !o.reference) usageError("--reference-rays has no effect without --reference");
  if (o.has("--path") && !o.has("--frames")) usageError("--path has no effect without --frames");
  if (o.has("--frames") && o.has("--depth")) usageError("--frames needs a scene: a --depth file has one view");
  if (o.settings.temporal && !o.has("--frames"))
    usageError("--set temporal=true accumulates frames: it needs --frames N along a --path (a single frame has "
               "no history)");
}

}  // namespace

Options parseOptions(int argc, char** argv) {
  Options o;
  cli::CommandLine cl(kTool, kDescription, kRules + settingsHelp() + depthExrHelp() + depthConventionHelp());
  cl.text("--out", o.out, "DIR",
          "output folder (default: out/render). It is replaced as a whole, so no file of an earlier run survives: "
          "the run writes into a new folder beside it and swaps it in only once every output is written (a failed "
          "run leaves DIR as it was). DIR must be missing, empty, or an earlier output holding only the files its "
          "sao-render-outputs.txt lists; any other file in it stops the run before rendering (nothing of yours is "
          "deleted), unless --overwrite. It must not hold an input file (the depth or scene file read)");
  cl.text("--backend", o.backend, "NAME",
          "gl | vulkan | cpu (the CPU reference in float, as a GPU computes) | cpu-double (the CPU reference in "
          "double) | auto (default: the first of gl, vulkan, cpu that starts)");
  cl.text("--scene", o.scene, "NAME|PATH",
          "built-in scene: sponza-like (default), sphere-plane, crease, thin, gears; or a mesh file (.gltf .glb .obj "
          ".ply; one view looking at the whole mesh) or a scene file (.scene, docs/scene-format.md)");
  cl.choice("--units", o.units, scenes::parseLengthUnit, std::string(scenes::kLengthUnitNames), "U",
            "the scene's length unit: m | cm | mm | in | ft, or auto (OBJ and PLY: a scale that makes the "
            "bounding-box diagonal 5 m, printed on stderr and in the summary; glTF and built-in scenes keep metres). "
            "Default: the scene's own (built-in and glTF metres, a .scene file's `units` line), else metres. "
            "Settings stay in metres and are converted; --eye, --target and --near are in the scene's units. With "
            "--depth: a file without a sao.* camera (one with it carries sao.metersToViewUnits)");
  cli::addViewNumber(cl, o.view);
  cl.value("--eye", "X,Y,Z",
           "with --target: an explicit camera for the scene (scene units, y up), with --fovy DEG (default 60) and "
           "--near D (default 0.1); replaces --view",
           [&o](const std::string& v) { o.eye = parsePoint("--eye", v); });
  cl.value("--target", "X,Y,Z", "the point the --eye camera looks at",
           [&o](const std::string& v) { o.target = parsePoint("--target", v); });
  cli::addImageSize(cl, o.size, "AO size in pixels", "default 1280x720");
  cli::addGuardBand(cl, o.guard, "guard band in pixels on each side", "default 0");
  cli::addSettings(cl, o.settings, "any setting below (repeatable), checked against its range");
  // Declared after --preset and --set, so CLI11 applies it after them: it overrides both.
  cl.value("--resolution-divisor", "N",
           "the AO at full (1), half (2) or quarter (4) resolution per axis, with a depth-aware upsample to the full "
           "size; the same as --set resolution_divisor=N, applied after --preset and --set (default: theirs, 1)",
           [&o](const std::string& v) {
             if (Status s = setFromText(o.settings, "resolution_divisor", v); !s) cli::reject(s.message);
           });
  cli::addDepthFormat(cl, "--depth-format", o.depthFormat,
                      "D16 | D24 | D32F: the precision of a scene's depth (default D32F; always reversed-Z, [0,1] "
                      "clip, infinite far; orthographic views: a far plane just beyond the scene)");
  cl.choice("--depth-source", o.depthSource, oneOf({"raster", "raytrace", "auto"}), "raster, raytrace or auto", "S",
            "how a scene's depth is made: raster (the rasterising prepass of the backend's API; cpu uses GL, else "
            "Vulkan), raytrace (Embree primary rays), auto (default: raster when a prepass starts, else raytrace; the "
            "summary says which)");
  cl.text("--depth", o.depthPath, "FILE.exr",
          "run on your own depth buffer instead of a scene (format below); the camera comes from the file's sao.* "
          "attributes or, for a file without them, from --fovy --near --far --clip --reversed-z --guard");
  cl.value("--fovy", "DEG", "vertical field of view in degrees, in (0, 180) (default 60): with --eye, or for a "
           "--depth file without a camera",
           [&o](const std::string& v) { o.fovyDegrees = cli::parseNumber("--fovy", v); });
  cl.value("--ortho", "HEIGHT",
           "an orthographic camera instead of a perspective one, HEIGHT units tall (the full view height, > 0; the "
           "width follows the aspect): with --eye (scene units; replaces --fovy, far just beyond the scene), or for a "
           "--depth file without a camera (with a finite --far). A .scene view takes `ortho HEIGHT`",
           [&o](const std::string& v) {
             const double h = cli::parseNumber("--ortho", v);
             if (!(h > 0)) cli::reject("--ortho expects a view height > 0, got '" + v + "'");
             o.orthoHeight = h;
           });
  cl.value("--near", "D", "near distance (default 0.1): with --eye, or for a --depth file without a camera",
           [&o](const std::string& v) { o.nearDistance = cli::parseNumber("--near", v); });
  cl.value("--far", "D|inf", "far distance of a --depth file without a camera (default inf)",
           [&o](const std::string& v) { o.far = v == "inf" ? INFINITY : cli::parseNumber("--far", v); });
  cl.choice("--clip", o.clip, oneOf({"gl", "zero-one"}), "gl or zero-one", "gl|zero-one",
            "the clip-space depth range of a --depth file without a camera: gl [-1,1] or zero-one [0,1] (default)");
  cl.flag("--reversed-z", o.reversedZ, "a --depth file without a camera holds reversed-Z depth (default off)");
  cl.flag("--depth-distances", o.depthDistances,
          "a --depth file without a camera holds positive distances along the view axis, in its units (--units; "
          "e.g. a Blender Z pass), not hardware depth; the camera comes from --fovy (or --ortho), --near, --far and "
          "--guard; sky is a value at or above --far, 0 or not finite (Blender writes 1e10: give a --far below "
          "it, e.g. --far 1e9)");
  cl.text("--save-depth", o.saveDepth, "FILE.exr",
          "write the depth input with its camera (a file --depth reads back); the name must end in .exr, its folder "
          "must exist, an existing file is replaced only with --overwrite, the --depth input never");
  cl.text("--dump-passes", o.dumpDir, "DIR", "every intermediate image as EXR (a folder handled as --out is)");
  cl.flag("--reference", o.reference,
          "also the ray-traced reference (near-field AO within the radius) and the error metrics, for a scene (not "
          "--depth); \"n/a\" (JSON null) marks a metric that is undefined for the images (e.g. SSIM of two "
          "constant ones)");
  cli::addRays(cl, "--reference-rays", o.referenceRays, "rays per pixel of the reference", "default 256");
  cli::addRuns(cl, o.runs, 1, "measured runs of the effect after one warm-up run",
               "default 1; the summary gives each pass's median and the fastest..slowest run");
  cl.value("--progress", "S",
           "a line on stderr every S seconds for a step running longer than S seconds, with the elapsed time and the "
           "reference's share done, and one when it ends; S in [0, 3600] (default 2; 0: every step, every 0.5 s and "
           "each tenth of the reference done)",
           [&o](const std::string& v) {
             o.progressSeconds = cli::parseNumber("--progress", v);
             if (!(o.progressSeconds >= 0 && o.progressSeconds <= 3600))
               cli::reject("--progress expects seconds in [0, 3600], got '" + v + "'");
           });
  cl.value("--frames", "N",
           "a camera path of N frames, 2..10000 (a scene only): the view moved along --path, each frame's depth "
           "rendered and the effect run on it, its AO written as frames/ao_NNNN.png and a line in frames.csv (eye, "
           "effect time, flicker: mean |A_t - A_t-1| on the same surface after reprojection); the other outputs are "
           "the last frame's",
           [&o](const std::string& v) {
             const double n = cli::parseNumber("--frames", v);
             if (!(n >= 2 && n <= 10000 && n == std::floor(n)))
               cli::reject("--frames expects a whole number of frames in 2..10000, got '" + v + "'");
             o.frames = std::uint32_t(n);
           });
  cl.choice("--path", o.path, scenes::parsePathKind, "orbit, dolly or strafe", "P",
            "the camera path of --frames: orbit (30 degrees about the target's vertical, default), dolly (towards "
            "the target, to 60 % of its distance) or strafe (sideways, 30 % of the distance)");
  cl.flag("--json", o.json, "write summary.json too");
  cl.flag(samples::kOverwriteOption, o.overwrite, samples::kOverwriteHelp);
  cl.parse(argc, argv);

  o.given = cl.givenNames();
  for (const char* flag : {"--fovy", "--ortho", "--near", "--far", "--clip", "--reversed-z", "--depth-distances"})
    o.cameraFlags |= o.has(flag);
  refuseIneffectiveOptions(o);
  if (o.eye.has_value() != o.target.has_value()) usageError("--eye and --target go together");
  // Refused here, not after the AO was written: a depth file has no geometry to trace.
  if (o.reference && !o.depthPath.empty()) usageError("--reference needs a scene, not a --depth file (no geometry to trace)");
  return o;
}

}  // namespace sao::render
