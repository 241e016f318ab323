// sao-bench: what each preset costs and how far it is from two ray-traced truths, plus the sweeps
// of the paper (radius: Figure 5, with the AlchemyAO-style baseline; resolution: Table 3) and the
// two-layer variant. Writes CSV, JSON and SVG plots.
// `sao-bench --help` lists the options; `--quick` is the small run the tests use.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "calibrate.h"
#include "frames_section.h"
#include "paths_section.h"
#include "spiral_section.h"
#include "measure.h"
#include "per_tap_section.h"
#include "precision_report.h"
#include "reference_check.h"
#include "report.h"
#include "scene_cache.h"
#include "traffic_section.h"
#include "tune.h"
#include "tune_report.h"
#include "sao/cli/command_line.h"
#include "sao/cli/shared_options.h"
#include "sao/prepass/precision.h"
#include "sao/prepass/prepass.h"
#include "sao/presets.h"
#include "sao/raytrace/converged.h"
#include "sao/raytrace/raytrace.h"
#include "sao/samples/error_structure.h"
#include "sao/samples/output_files.h"
#include "sao/scenes/scene.h"

namespace fs = std::filesystem;
using namespace sao;
using namespace sao::bench;

namespace {

constexpr const char* kDescription =
    R"(Measures every preset on every scene and backend (median per-pass time of --runs runs, and the
error against two ray-traced references, (a) near-field AO and (b) the AlchemyAO obscurance integral,
and against (c) the converged screen-space estimator, with signed error maps as PNG),
then the sweeps: samples, MIP and blur on/off, radius (paper Fig. 5: SAO with and without the z
hierarchy and an AlchemyAO-style baseline), resolution (paper Table 3) and the two-layer variant.
Every run first checks reference (a) against the analytic sphere case (reference_check.csv).
Writes results.csv, results.json and SVG plots; the traffic section (ao_sample's texel reads through
a cache model: a paper-like GPU and this CPU) writes traffic.csv; the calibrate section (intensity, contrast,
bias and epsilon of the medium preset fitted to (a) over a grid) writes calibration.csv; the spiral section
(our former lattice criterion against G3D's table, the shipped one, by error against (c)) writes spiral.csv;
the frames section (a static camera's frames averaged, Inputs::frameIndex, against one frame with 4x
the taps, by error against (c)) writes frames.csv; the paths section (every scene along the orbit, dolly
and strafe camera paths, with and without temporal accumulation: flicker and time per frame, 60
frames at 320x180 unless --size) writes paths.csv; the divisor section (every preset at resolution_divisor 1, 2
and 4: error vs (c) on every scene at --size on the first backend, time at 1920x1080 on every backend) writes
rows "divisor" and "divisor_time" into results.csv; the intermediates section (every preset with rg32f and with
rg16f (A, key) intermediates, half_intermediates: error vs (c) on every scene at --size on the first backend,
time at 1920x1080 on every backend) writes rows "intermediates" and "intermediates_time"; the per_tap section (GL only: ao_sample's time per tap at
s = 7, 16, 32, 48 beside a ladder of minimal passes of our own, a fragment pass, the same as compute, and
compute plus one of ao_sample's features each, on the main scene at --size, default 1920x1080) writes per_tap.csv.)";

// The parts of the run, in the order they run (--sections picks some).
const std::vector<std::string> kSections = {"presets",    "samples",   "mip_blur", "radius",
                                            "resolution", "two_layer", "precision", "traffic",
                                            "divisor",    "intermediates", "spiral", "frames",  "paths",     "per_tap",
                                            "calibrate"};

// The calibrate section searches a grid (about 20 minutes at 640x360 here), the spiral section
// every differing sample count (about 5), the frames section 16 frames of three presets per scene,
// the divisor section every preset at three divisors on every scene (the intermediates section at
// two formats), the per_tap section a ladder of passes at 1920x1080: asked for by name only.
bool inDefaultRun(const std::string& section) {
  return section != "calibrate" && section != "spiral" && section != "frames" && section != "divisor" &&
         section != "intermediates" && section != "per_tap" && section != "paths";
}

std::string sectionNames() {
  std::string names;
  for (const auto& s : kSections) names += (names.empty() ? "" : ",") + s;
  return names;
}

struct Options {
  std::string out = "out/bench", backends = "gl,vulkan,cpu", depthSource = "raster";
  std::set<std::string> sections = [] {
    std::set<std::string> out;
    for (const auto& s : kSections)
      if (inDefaultRun(s)) out.insert(s);
    return out;
  }();
  std::uint32_t runs = 5, rays = 256, convergedTaps = 4096, warmupMs = 0;
  std::uint32_t framesAveraged = 1;  // --frames-averaged: the presets section's AO, the mean of this many frames
  Extent size{1280, 720};
  bool sizeGiven = false;  // --size given (the per_tap section's default is 1920x1080)
  bool quick = false;
  bool overwrite = false;       // --overwrite (sao/samples/output_files.h)
  bool tune = false;            // --tune: the preset tuner (tune.h) instead of the sections
  bool convergedNoise = false;  // --converged-noise
  bool aoNoise = false;         // --ao-noise
  bool ortho = false;           // --ortho: every scene's view made orthographic
  bool timeOnly = false;        // --time-only: no references, so no error columns
  std::string objective = "c";  // --objective: the reference --tune minimises the error against
  std::string mapsAgainst = "c";  // --maps-against: the reference each row's error map is drawn against
  std::string screenThickness;  // --screen-thickness: reference (d)'s thickness model ("": the setting thickness_model)
  std::vector<std::string> sets;  // --set NAME=VALUE, in order: applied to every preset of the presets section
  std::optional<scenes::LengthUnit> units;  // --units
  std::vector<std::string> scenes;          // --scenes; empty: benchScenes(quick)
};

std::set<std::string> parseSections(const std::string& list) {
  std::set<std::string> out;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    if (std::find(kSections.begin(), kSections.end(), name) == kSections.end())
      cli::reject("--sections: unknown section '" + name + "' (expected some of " + sectionNames() + ")");
    out.insert(name);
  }
  if (out.empty()) cli::reject("--sections needs at least one section");
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  cli::CommandLine cl("sao-bench", kDescription);
  cl.text("--out", o.out, "DIR",
          "output folder (default out/bench). Written as sao-render's --out is: into a new folder beside it, swapped "
          "in when the run ends; DIR must be missing, empty or an earlier sao-bench output holding only the files its "
          "sao-bench-outputs.txt lists, else the run stops before it starts (with --overwrite: the run's files "
          "replace those of the same names, the others are kept). --tune writes DIR in place (tune.csv is resumed) "
          "by the same rule");
  cl.value("--backends", "LIST",
           "comma-separated: cpu,gl,vulkan (default: gl,vulkan,cpu, those that start; the others are skipped)",
           [&o](const std::string& v) {
             std::stringstream in(v);
             for (std::string name; std::getline(in, name, ',');)
               if (Status s = samples::checkBackendName(name); !s) cli::reject("--backends: " + s.message);
             if (v.empty() || v.back() == ',') cli::reject("--backends: an empty name in '" + v + "'");
             o.backends = v;
           });
  cl.value("--sections", "LIST", "comma-separated parts to run (default: all but calibrate, spiral, frames, paths, divisor, intermediates and per_tap: grid searches of about 20 and 5 minutes, a frame accumulation, camera paths, a preset x divisor matrix, a preset x intermediate format matrix and a ladder of GL passes at 1920x1080):\n" + sectionNames(),
           [&o](const std::string& v) { o.sections = parseSections(v); });
  cli::addRuns(cl, o.runs, 1, "measured runs per point, after one warm-up", "default 5");
  cl.value("--warmup-ms", "N",
           "before each point's timed runs, render it back to back for N ms, 0..10000 (default 0: one warm-up run "
           "only): a GPU lowers its clocks under the light load of single runs and their read-backs "
           "(ci/gpu-bench.sh uses 200)",
           [&o](const std::string& v) { o.warmupMs = cli::parseWhole("--warmup-ms", v, 0, 10000); });
  cli::addRays(cl, "--rays", o.rays, "reference rays per pixel of (a) and (b)",
               "default 256; (a)'s own noise stays below 0.005 on every built-in scene from 4096 on, "
               "docs/reference.md, --ao-noise measures it");
  cli::addRays(cl, "--converged-taps", o.convergedTaps, "taps per pixel of reference (c), the converged estimator",
               "default 4096");
  cli::addImageSize(cl, o.size, "size of the preset matrix and sweeps",
                    "default 1280x720; the radius sweep always runs at 1920x1080 unless --quick, the per_tap section "
                    "at 1920x1080 unless --size or --quick (320x180)");
  cl.choice("--depth-source", o.depthSource,
            [](const std::string& v) { return v == "raster" || v == "raytrace" ? std::optional(v) : std::nullopt; },
            "raster or raytrace", "S",
            "raster (default): the scene's depth, positions, normals and peeled second layer from the rasterising "
            "prepass (GL, else Vulkan; D32F, reversed-Z, [0,1], infinite far); raytrace: from Embree primary rays "
            "(raytrace::castPrimary)");
  cl.choice("--units", o.units, scenes::parseLengthUnit, std::string(scenes::kLengthUnitNames), "U",
            "the scenes' length unit: m | cm | mm | in | ft | auto (default: each scene's own, the built-in scenes' "
            "metres). Settings stay in metres and are converted (Camera::metersToViewUnits); the choice is printed "
            "per scene");
  cl.value("--scenes", "LIST",
           "comma-separated scenes instead of the built-in set: built-in names or mesh/scene files (.obj, .ply, "
           ".gltf, .glb, .scene; each file's first view), e.g. a hold-out mesh not used in tuning",
           [&o](const std::string& v) {
             std::stringstream in(v);
             for (std::string name; std::getline(in, name, ',');)
               if (!name.empty()) o.scenes.push_back(name);
             if (o.scenes.empty()) cli::reject("--scenes needs at least one scene");
           });
  cl.flag("--converged-noise", o.convergedNoise,
          "compute each reference (c) a second time with another seed and report its own noise, the RMS of the "
          "difference / sqrt(2) over the pixels with geometry (doubles the time (c) takes)");
  cl.flag("--ao-noise", o.aoNoise,
          "compute each reference (a) a second time with another seed and report its own noise as --converged-noise "
          "does, beside sqrt(mean V (1 - V) / rays), the noise its independent rays predict (doubles the time (a) "
          "takes)");
  cl.flag("--ortho", o.ortho,
          "orthographic cameras: each scene's view made orthographic, as tall as its field of view spans at the "
          "target (scenes::toOrthographic: the eye moved back clear of the scene, a finite far plane just beyond it); "
          "the report's depth note says so");
  cl.flag("--time-only", o.timeOnly,
          "time the effect only: no ray-traced or converged references, so the error columns are empty (the "
          "references take minutes of CPU per scene; a GPU machine's figures to add are its times: "
          "ci/gpu-bench.sh). The reference check on the analytic sphere still runs");
  cl.flag("--quick", o.quick, "the smoke run: 160x90, 3 runs, 16 rays, two scenes, short sweeps (it sets --size, "
          "--runs and --rays: they are refused with it)");
  cl.flag("--tune", o.tune,
          "instead of the sections: search a fixed grid of samples, z hierarchy q', blur radius/stride and "
          "resolution_divisor for the lowest error vs (c) per time, relative to the medium preset, over the built-in "
          "scenes, and choose presets on that front (tune.csv, resumable; tune_front.csv/.svg, tune_presets.txt). Uses "
          "the first of --backends that starts (default gl), --size default 640x360, --runs, --converged-taps, --quick");
  cl.value("--set", "NAME=VALUE",
           "with --sections presets only (repeatable): a setting applied on top of every preset, e.g. --set estimator=1 "
           "to measure the visibility estimator at each preset's cost; the rows' variant column lists them. Checked as "
           "sao-render checks it (name, type, range; a setting a preset's final settings make inert is refused)",
           [&o](const std::string& v) {
             Settings probe;
             if (Status s = setFromAssignment(probe, v); !s) cli::reject("--set: " + s.message);
             o.sets.push_back(v);
           });
  cl.value("--frames-averaged", "N",
           "with --sections presets: each row's errors are those of the mean of N frames (Inputs::frameIndex 0 to "
           "N-1, untimed, after the timed runs), 1..1024 (default 1): the preset's own converged value without its "
           "sampling noise, what a static camera's frames converge to; the rows' variant column says so. Not with "
           "--time-only, nor with the setting temporal (which blends frames itself)",
           [&o](const std::string& v) { o.framesAveraged = cli::parseWhole("--frames-averaged", v, 1, 1024); });
  cl.choice("--objective", o.objective,
            [](const std::string& v) { return v == "c" || v == "a" ? std::optional(v) : std::nullopt; }, "c or a", "R",
            "with --tune: the reference whose error the front and the presets minimise: c (default), the converged "
            "estimator (what the knobs trade); a, ray-traced near-field AO (what users see, model error included), with "
            "--rays rays per pixel (default 4096 here, which keeps (a)'s own noise below 0.005; --quick: 16). Blotch and silhouette stay against (c)");
  cl.choice("--screen-thickness", o.screenThickness,
            [](const std::string& v) { return v == "constant" || v == "width" ? std::optional(v) : std::nullopt; },
            "constant or width", "M",
            "with --sections presets: reference (d)'s thickness model whatever the setting thickness_model (which it "
            "follows by default, as the visibility estimator does): constant (the setting thickness for every slab) or "
            "width (each run of continuous depth along a slice taken as deep as half its width, from 0.02 m up to "
            "thickness: raytrace::ScreenVisibilityOptions::thicknessFromWidth, docs/reference.md)");
  cl.choice("--maps-against", o.mapsAgainst,
            [](const std::string& v) { return v == "c" || v == "a" || v == "d" ? std::optional(v) : std::nullopt; },
            "c, a or d", "R",
            "the reference each row's error map (maps/) is drawn against: c (default), the "
            "converged alchemy estimator; a, ray-traced near-field AO; d, converged screen-space visibility (then "
            "maps/NNN_screen_<scene>_<inputs>_<constant|width>.png, (d) - (a), once per reference (d))");
  cl.flag(samples::kOverwriteOption, o.overwrite, samples::kOverwriteHelp);
  cl.parse(argc, argv);
  o.sizeGiven = cl.given("--size");
  if (o.quick)
    for (const char* option : {"--size", "--runs", "--rays"})
      if (cl.given(option))
        cl.fail(std::string("--quick and ") + option + " cannot be combined: --quick sets " + option +
                " (--size 160x90, --runs 3, --rays 16); drop one of them");
  if (o.tune) {
    if (cl.given("--sections") || cl.given("--converged-noise") || cl.given("--ao-noise") || cl.given("--ortho") ||
        cl.given("--scenes") || cl.given("--time-only") || cl.given("--warmup-ms"))
      cl.fail("--tune takes --out, --backends, --size, --runs, --converged-taps, --objective, --rays (with --objective "
              "a), --depth-source, --units, --quick and --overwrite only");
    if (cl.given("--rays") && o.objective != "a")
      cl.fail("--tune: --rays sets reference (a)'s rays, which only --objective a uses; add --objective a or drop --rays");
    if (o.objective == "a" && !cl.given("--rays")) o.rays = 4096;  // (a)'s own noise below 0.005 on every scene (docs/reference.md)
    if (!cl.given("--backends")) o.backends = "gl";
    if (!cl.given("--size")) o.size = {640, 360};
  }
  if (!o.sets.empty()) {
    if (o.tune || o.sections != std::set<std::string>{"presets"})
      cl.fail("--set applies to the presets section only: add --sections presets (and no --tune)");
    for (const PresetInfo& p : presets()) {
      Settings s = presetSettings(p.preset);
      std::vector<SettingId> given;
      for (const std::string& a : o.sets) {
        if (Status st = setFromAssignment(s, a); !st) cl.fail("--set: " + st.message);
        given.push_back(*findSetting(a.substr(0, a.find('='))));
      }
      if (Status st = validate(s); !st) cl.fail("--set: preset " + std::string(p.name) + ": " + st.message);
      if (s.temporal && cl.given("--frames-averaged"))
        cl.fail("--frames-averaged averages independent frames: the setting temporal blends frames itself; drop one");
      for (SettingId id : given)
        if (const gen::InertRule* rule = inertRule(s, id))
          cl.fail("--set " + describeInert(*rule) + " (preset " + std::string(p.name) + ")");
    }
  }
  if (cl.given("--screen-thickness") && (o.tune || o.timeOnly || o.sections != std::set<std::string>{"presets"}))
    cl.fail("--screen-thickness sets reference (d) of the presets section: add --sections presets (and no --tune or "
            "--time-only)");
  if (cl.given("--maps-against") && (o.tune || o.timeOnly))
    cl.fail("--maps-against chooses the reference of the sections' error maps: --tune and --time-only draw none");
  if (cl.given("--frames-averaged") && (o.tune || o.timeOnly || o.sections != std::set<std::string>{"presets"}))
    cl.fail("--frames-averaged sets the presets section's errors: add --sections presets (and no --tune or --time-only)");
  if (cl.given("--objective") && !o.tune) cl.fail("--objective chooses what --tune minimises: add --tune, or drop it");
  if (o.timeOnly) {
    if (cl.given("--rays") || cl.given("--converged-taps") || cl.given("--converged-noise") || cl.given("--ao-noise"))
      cl.fail("--time-only computes no references: --rays, --converged-taps, --converged-noise and --ao-noise do not "
              "apply");
    for (const char* section : {"calibrate", "spiral", "frames"})
      if (o.sections.count(section))
        cl.fail(std::string("--time-only: the ") + section + " section measures error only; leave it out or drop --time-only");
  }
  if (o.quick) o.size = {160, 90}, o.runs = 3, o.rays = 16;
  return o;
}

// A file name for a row's map: its index, section, scene, backend, preset and variant, with every
// character but [A-Za-z0-9.-] as '_'.
std::string mapName(std::size_t index, const std::vector<std::string>& parts) {
  char prefix[16];
  std::snprintf(prefix, sizeof prefix, "%03zu", index);
  std::string name = prefix;
  for (const std::string& part : parts) {
    if (part.empty()) continue;
    name += '_';
    for (char ch : part) name += std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' ? ch : '_';
  }
  return name + ".png";
}

// What the outputs mean, in results.json ("notes") and on stdout.
std::vector<std::pair<std::string, std::string>> notes(const std::string& depthSource) {
  char separation[32];
  std::snprintf(separation, sizeof separation, "%g", kSecondLayerSeparation);
  return {
      {"depth", depthSource},
      {"ao_*", "error against reference (a), near-field ambient occlusion: the fraction of cosine-weighted rays from "
               "the visible point (geometric normal) that travel the radius r without a hit "
               "(raytrace::referenceAmbientOcclusion). No falloff; intensity, bias and epsilon play no part."},
      {"obscurance_*", "error against reference (b), AlchemyAO obscurance: clamp(1 - O, 0, 1)^k with O = (sigma/pi) "
                       "times the integral over the hemisphere of H(r - t) max(0, t cos + z_C beta) / (t^2 + eps), t the "
                       "first hit along each direction, with the run's radius, intensity, bias, epsilon and contrast "
                       "(raytrace::referenceObscurance, docs/reference.md): the integral the effect's estimator "
                       "(AlchemyAO eq. 10) approximates."},
      {"converged_*", "error against reference (c), the converged screen-space estimator: the effect's own estimator "
                      "(same depth, normals rebuilt from depth or the supplied ones, second layer, radius cut, bias, "
                      "epsilon, intensity, contrast) with every tap on csz level 0, no 2x2 reconstruction, no blur, in "
                      "double, integrated over the spiral's tap distribution by stratified taps "
                      "(raytrace::convergedEstimator, --converged-taps per pixel, docs/reference.md). The error vs (c) "
                      "is what taps, MIP use, blur and resolution trade."},
      {"screen_*", "error against reference (d), converged screen-space visibility: the cosine-weighted fraction of "
                   "directions from the effect's point (same depth, normals rebuilt or supplied, second layer) that "
                   "travel the radius r without passing through the slab of thickness 0.3 m behind a stored depth "
                   "sample (0.3 % of the depth behind it onward), 64 slices per pixel, each marched to r' and "
                   "integrated exactly, in double (raytrace::screenVisibility, docs/reference.md \"Reference (d)\"). "
                   "What a screen-space estimator that sees these inputs converges to at best; the error vs (d) is the "
                   "effect's estimator, sampling and reconstruction together."},
      {"screen_model_rmse_vs_ao / model_rmse_converged_vs_screen",
       "per scene, radius and inputs: RMSE of (d) against (a), what screen space cannot see (hidden and off-screen "
       "geometry, the thickness), and of (c) against (d), the estimator's definition (AlchemyAO's falloff, bias "
       "and intensity against cosine-weighted visibility); model_rmse_vs_ao is about their sum."},
      {"converged_blotch_rmse / converged_highfreq_rmse", "the error vs (c) split by a Gaussian low-pass of sigma = 8 px "
                                                          "(a normalised convolution over the pixels with geometry only): "
                                                          "RMSE of the low-passed error (blotches, what a blur cannot "
                                                          "remove) and of the remainder (noise)."},
      {"converged_silhouette_rmse", "RMSE of the error vs (c) over the pixels with geometry within 3 px (Euclidean) of a "
                                    "depth discontinuity: 4-neighbours of the depth input where one is sky and the other "
                                    "geometry, or whose camera-space z differ by more than 10% of the nearer |z| (halos)."},
      {"model_rmse_vs_ao / model_rmse_vs_obscurance", "the model error, the same on every row of a scene, settings and "
                                                      "inputs: RMSE of (c) against (a) and against (b). The share of the "
                                                      "error vs (a) that no preset can fix (the heightfield and the "
                                                      "estimator's definition)."},
      {"error_map", "maps/NNN_<row>.png: the signed error of the row's output against (c) (--maps-against: a or d), white "
                    "at 0, blue where the output is darker (more occluded), red where lighter, full colour at +-0.1 "
                    "and beyond (fixed scale), grey without geometry; maps/NNN_model_<scene>_<inputs>.png: (c) - (a) on "
                    "the same scale; with --maps-against d maps/NNN_screen_<scene>_<inputs>_<constant|width>.png: (d) - (a) for "
                    "each reference (d) (its thickness model)."},
      {"*_flip_raw / *_flip_fitted", "mean FLIP (Andersson et al., HPG 2020, LDR; samples/flip.h) over the pixels with "
                                     "geometry: the difference a viewer flipping between output and reference would "
                                     "notice, 0 none to 1, at 67 pixels per degree, AO values read as the sRGB greys "
                                     "ao.png stores; sky set to 1 in both images first."},
      {"raw / fitted", "raw: the effect's output against the reference over the pixels with geometry; fitted: after "
                       "scaling the effect's occlusion 1 - A by the least-squares factor fitted_scale."},
      {"radius: SAO (z hierarchy)", "the effect as shipped: z MIP hierarchy (Z_HIERARCHY=1), normals rebuilt from depth."},
      {"radius: SAO (no hierarchy)", "Z_HIERARCHY=0: every tap reads full-resolution z; normals rebuilt from depth "
                                    "(NORMALS_SUPPLIED=0)."},
      {"radius: AlchemyAO-style", "the AlchemyAO baseline: full-resolution z (Z_HIERARCHY=0) and a supplied normal "
                                  "buffer (NORMALS_SUPPLIED=1, the ray-cast camera-space geometric normals as rgba16f), "
                                  "same sample count, taps and estimator as SAO. It is not AlchemyAO itself: its taps "
                                  "read r32f z and rebuild positions, where AlchemyAO read float3 camera-space "
                                  "positions (3x the bytes per tap); taps follow SAO's spiral; the 2x2 and bilateral "
                                  "blur passes are SAO's."},
      {"radius: visibility (z hierarchy)", "the visibility estimator (estimator=1, docs/effect-math.md 5.9) with the z "
                                           "MIP hierarchy, normals rebuilt from depth: its cost against the radius."},
      {"radius: visibility from width (z hierarchy)", "the same with thickness_model=1 (thickness from width): the width pass "
                                                  "and the tap's csz_share fetch (z and shares) against the radius."},
      {"two_layer", std::string("medium settings with and without TWO_LAYER; depth2 is the nearest surface at least ") +
                        separation +
                        " m behind the first layer in camera-space z, D32F like depth: with the raster depth source "
                        "the prepass's depth peeling (front faces only, so the floor behind a closed object), with "
                        "raytrace the primary ray continued (raytrace::castSecondLayer, front or back face)."},
      {"precision", "precision.csv / precision.txt: camera-space z and face-normal error of the rasterised depth per "
                    "format x far plane x convention, binned at 1, 10, 100 m (prepass::measurePrecision: three "
                    "45-degree panels with analytic truth; z rebuilt as linear_z does, normals as ao_sample does)."},
  };
}

// The output folder being written, staged beside its place until the run ends (an exit on an
// error destroys it, and with it the staging folder).
std::unique_ptr<samples::OutputFolder> g_output;

// A refused --out: a bad option (exit 2) or something in the way on disk (exit 1), one line.
[[noreturn]] void refuseOutput(const Status& s) {
  if (s.code == StatusCode::InvalidInput) cli::exitWithUsageError("sao-bench", s.message);
  std::fprintf(stderr, "sao-bench: %s\n", s.message.c_str());
  std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  samples::WriteRules rules{"sao-bench", o.overwrite, {}};
  for (const std::string& scene : o.scenes) rules.addInput("--scenes", scene);
  if (o.tune) {
    if (Status s = samples::prepareFolderInPlace(o.out, "--out", rules, bench::kTuneFiles); !s) refuseOutput(s);
    return bench::runTune({o.out, o.backends, o.depthSource, o.units, o.size, o.runs, o.convergedTaps,
                           o.objective == "a" ? o.rays : 0, o.quick});
  }
  if (Status s = samples::OutputFolder::stage(o.out, "--out", rules, g_output); !s) refuseOutput(s);
  const std::string out = g_output->stagingPath().string();  // every file of the run goes in here
  std::error_code ec;

  // Reference (a) against the analytic sphere first: every figure below leans on it.
  std::vector<raytrace::SphereCheck> checks;
  if (Status s = bench::checkReference(checks); !s) fail("reference check: " + s.message);
  bench::writeReferenceCheck((fs::path(out) / "reference_check.csv").string(), checks);
  double worst = 0;
  std::string angles;
  for (const auto& c : checks) {
    worst = std::max(worst, c.absError());
    angles += (angles.empty() ? "" : "/") + std::to_string(int(c.sphere.thetaDegrees));
  }
  std::printf("reference check: analytic sphere (R %g, D %g) at %s deg, max |traced - analytic| %.4f (%s %g)\n",
              checks[0].sphere.radius, checks[0].sphere.distance, angles.c_str(), worst,
              worst <= bench::kReferenceTolerance ? "within" : "BEYOND", bench::kReferenceTolerance);

  std::vector<std::unique_ptr<samples::BackendRunner>> backends;
  std::stringstream list(o.backends);
  std::string name, machine;
  while (std::getline(list, name, ',')) {
    std::unique_ptr<samples::BackendRunner> b;
    if (Status s = samples::createBackend(name, b); !s) {
      std::fprintf(stderr, "sao-bench: skipping backend %s: %s\n", name.c_str(), s.message.c_str());
      continue;
    }
    machine += (machine.empty() ? "" : "; ") + b->description();
    backends.push_back(std::move(b));
  }
  if (backends.empty()) fail("no backend could start");

  // The depth every backend is given: rasterised once by a prepass (the same bits on GL and
  // Vulkan, tests/prepass), or ray-cast.
  std::unique_ptr<prepass::Prepass> depthPrepass;
  std::string depthSource = "Embree primary rays (raytrace::castPrimary), D32F reversed-Z [0,1] infinite far";
  if (o.depthSource == "raster") {
    if (Status s = prepass::createPrepass("auto", depthPrepass); !s) fail(s.message + " (--depth-source raytrace works without one)");
    depthSource = "rasterised by the " + std::string(depthPrepass->name()) + " prepass (" + depthPrepass->description() +
                  "), D32F reversed-Z [0,1] infinite far";
  }

  const std::vector<std::string> sceneNames = o.scenes.empty() ? benchScenes(o.quick) : o.scenes;
  const std::string mainScene =
      !o.scenes.empty() ? o.scenes.front() : o.quick ? "sphere-plane" : std::string(scenes::kDefaultScene);
  SceneCache cache(depthPrepass.get(), o.units);
  if (o.ortho) {
    cache.setOrthographic(true);
    const std::size_t at = depthSource.find("infinite far");
    if (at != std::string::npos)
      depthSource.replace(at, 12, "finite far: orthographic views (--ortho), the far plane just beyond each scene");
  }
  std::vector<bench::Row> rows;
  std::vector<std::string> convergedTimes;  // how long each reference (c) took
  std::vector<std::string> screenTimes;     // and each reference (d)
  std::vector<std::string> aoNoises;        // --ao-noise: each reference (a)'s own noise
  int step = 0;
  auto progress = [&](const std::string& what) {
    std::fprintf(stderr, "\r\033[K[%d] %s", ++step, what.c_str());
    std::fflush(stderr);
  };
  // withError: compare with both references (a) and (b). averagedFrames: bench::measure's.
  auto run = [&](const std::string& section, const std::string& scene, samples::BackendRunner& b,
                 const std::string& preset, const std::string& variant, const Settings& s, Extent size,
                 bool withError, std::uint32_t averagedFrames = 1, Extra extra = Extra::None) {
    progress(section + ": " + scene + " " + std::string(b.name()) + " " + preset + " " + variant + " " +
             std::to_string(size.width) + "x" + std::to_string(size.height));
    Prepared& p = cache.prepare(scene, size.width, size.height);
    const samples::RunInputs inputs = runInputs(p, extra);
    const std::string what = inputsName(extra);
    bench::References refs;
    Converged* converged = nullptr;
    std::pair<double, double> screenModel{NAN, NAN};  // (d) vs (a), (c) vs (d)
    Screen* screenUsed = nullptr;
    bool screenFromWidth = false;  // its thickness model
    if (withError && !o.timeOnly) {
      refs.nearFieldAo = &nearFieldReference(p, s.radius, o.rays);
      if (o.aoNoise && !p.referenceNoise.count(s.radius)) {
        const auto [measured, predicted] = nearFieldNoise(p, s.radius, o.rays);
        char t[160];
        std::snprintf(t, sizeof t, "%s at %g m: %.4f (predicted %.4f)", scene.c_str(), double(s.radius), measured, predicted);
        aoNoises.push_back(t);
      }
      refs.obscurance = &obscuranceReference(p, s, o.rays);
      const bool fresh = !p.converged.count({obscuranceKey(s), extra});
      converged = &convergedReference(p, s, extra, {o.convergedTaps, o.convergedNoise, refs.nearFieldAo, refs.obscurance});
      if (fresh) {
        char t[96];
        std::snprintf(t, sizeof t, ": %.1f s (%.1f s CPU)", converged->seconds, converged->cpuSeconds);
        convergedTimes.push_back(scene + " (" + what + ")" + t);
        if (o.convergedNoise) {
          std::snprintf(t, sizeof t, ", own noise %.2g (RMS)", converged->noise);
          convergedTimes.back() += t;
        }
      }
      refs.converged = &converged->ao;
      ScreenOptions screenOptions;  // 64 slices, every pixel
      if (!o.screenThickness.empty()) screenOptions.thicknessFromWidth = o.screenThickness == "width";
      const ScreenKey key = screenKey(s, extra, screenOptions.thicknessFromWidth);
      const bool freshScreen = !p.screen.count(key);
      screenFromWidth = std::get<4>(key);
      screenOptions.nearFieldAo = refs.nearFieldAo;
      screenOptions.converged = &converged->ao;
      Screen& screen = screenReference(p, s, extra, screenOptions);
      if (freshScreen) {
        char t[96];
        std::snprintf(t, sizeof t, ": %.1f s (%.1f s CPU)", screen.seconds, screen.cpuSeconds);
        screenTimes.push_back(scene + " (" + what + (screenFromWidth ? ", thickness from width" : "") + ")" + t);
      }
      screenUsed = &screen;
      refs.screen = &screen.ao;
      refs.screenMask = &screen.mask;
      screenModel = {screen.rmseVsAo, screen.rmseConvergedVsScreen};
      refs.mask = &p.mask;
      refs.silhouette = &p.silhouette;
    }
    bench::Row r{section, scene, std::string(b.name()), preset, variant, what, size, s, {}, NAN, NAN, {}};
    if (Status st = bench::measure(b, s, p.camera, inputs, int(o.runs), refs, r.m, double(o.warmupMs), averagedFrames);
        !st)
      fail(section + " " + scene + " " + variant + ": " + st.message);
    if (converged) {
      if (fs::create_directories(fs::path(out) / "maps", ec); ec)
        fail("cannot create '" + (fs::path(out) / "maps").string() + "': " + ec.message());
      r.modelRmseVsAo = converged->rmseVsAo;
      r.modelRmseVsObscurance = converged->rmseVsObscurance;
      std::tie(r.screenRmseVsAo, r.convergedRmseVsScreen) = screenModel;
      r.errorMap = "maps/" + mapName(rows.size(), {section, scene, r.backend, preset, variant});
      const bool againstScreen = o.mapsAgainst == "d";
      const FloatImage& mapReference = againstScreen ? screenUsed->ao : o.mapsAgainst == "a" ? *refs.nearFieldAo : converged->ao;
      const std::vector<unsigned char>& mapMask = againstScreen ? screenUsed->mask : p.mask;
      if (Status st = samples::writeErrorMapPng((fs::path(out) / r.errorMap).string(), r.m.ao, mapReference, mapMask); !st)
        fail(st.message);
      if (againstScreen && screenUsed->map.empty()) {  // once per reference (d): (d) - (a)
        screenUsed->map = "maps/" + mapName(rows.size(), {"screen", scene, what, screenFromWidth ? "width" : "constant"});
        if (Status st = samples::writeErrorMapPng((fs::path(out) / screenUsed->map).string(), screenUsed->ao,
                                                  *refs.nearFieldAo, screenUsed->mask);
            !st)
          fail(st.message);
      }
      if (converged->modelMap.empty()) {  // once per scene, settings and inputs: (c) - (a)
        converged->modelMap = "maps/" + mapName(rows.size(), {"model", scene, what});
        if (Status st = samples::writeErrorMapPng((fs::path(out) / converged->modelMap).string(), converged->ao,
                                                  *refs.nearFieldAo, p.mask);
            !st)
          fail(st.message);
      }
    }
    rows.push_back(std::move(r));
  };
  auto want = [&](const char* section) { return o.sections.count(section) > 0; };
  const Extent size = o.size;
  auto& first = *backends.front();
  const Settings base = presetSettings(Preset::Medium);

  // presets: every preset on every scene and backend, the speed/accuracy trade.
  if (want("presets"))
    for (const auto& scene : sceneNames)
      for (auto& b : backends)
        for (const auto& p : presets()) {
          Settings s = presetSettings(p.preset);
          std::string variant;
          for (const std::string& a : o.sets) {
            if (Status st = setFromAssignment(s, a); !st) fail("--set " + a + ": " + st.message);  // parse() checked it
            variant += (variant.empty() ? "" : " ") + a;
          }
          if (o.framesAveraged > 1)
            variant += (variant.empty() ? "" : " ") + std::string("frames_averaged=") + std::to_string(o.framesAveraged);
          run("presets", scene, *b, std::string(p.name), variant, s, size, true, o.framesAveraged);
        }

  // samples, mip_blur: sweeps on the main scene and the first backend.
  if (want("samples"))
    for (int s : o.quick ? std::vector<int>{4, 16} : std::vector<int>{4, 8, 11, 16, 24, 32, 48, 64}) {
      Settings t = base;
      t.samples = s;
      run("samples", mainScene, first, "medium", "samples=" + std::to_string(s), t, size, true);
    }
  if (want("mip_blur"))
    for (bool mips : {true, false})
      for (bool blur : {true, false}) {
        Settings t = base;
        t.use_z_hierarchy = mips;
        t.blur_radius = blur ? base.blur_radius : 0;
        run("mip_blur", mainScene, first, "medium", std::string("mips=") + (mips ? "on" : "off") + " blur=" + (blur ? "on" : "off"), t, size, true);
      }

  // radius (paper Fig. 5): three curves on the same scene, backend and size. Timing only (a
  // reference per radius at 1920x1080 would dominate the run).
  if (want("radius")) {
    const Extent radiusSize = o.quick ? size : Extent{1920, 1080};
    struct Curve {
      const char* label;
      bool hierarchy;
      Extra extra;
      int estimator;
      int thicknessModel;
    };
    const Curve curves[] = {{"SAO (z hierarchy)", true, Extra::None, 0, 0},
                            {"SAO (no hierarchy)", false, Extra::None, 0, 0},
                            {"AlchemyAO-style", false, Extra::Normals, 0, 0},
                            {"visibility (z hierarchy)", true, Extra::None, 1, 0},
                            {"visibility from width (z hierarchy)", true, Extra::None, 1, 1}};
    for (double r : o.quick ? std::vector<double>{0.1, 1.5} : std::vector<double>{0.1, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0})
      for (const Curve& c : curves) {
        Settings t = base;
        t.radius = float(r);
        t.use_z_hierarchy = c.hierarchy;
        t.estimator = c.estimator;
        t.thickness_model = c.thicknessModel;
        run("radius", mainScene, first, "medium", c.label, t, radiusSize, false, 1, c.extra);
      }
  }

  // resolution (paper Table 3): every backend.
  if (want("resolution"))
    for (Extent e : o.quick ? std::vector<Extent>{{160, 90}, {320, 180}}
                            : std::vector<Extent>{{1280, 720}, {1920, 1080}, {2560, 1600}})
      for (auto& b : backends) run("resolution", mainScene, *b, "medium", "", base, e, false);

  // divisor ([resolution]): every preset at resolution_divisor 1, 2 and 4, the rest of the preset
  // unchanged. Error vs (c) on every scene at --size (first backend); time on the main scene at
  // 1920x1080 on every backend, the three divisors of a preset one after another so that their
  // ratios come from the same minute of this noisy machine.
  if (want("divisor")) {
    const std::vector<int> divisors = o.quick ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 4};
    const Extent timeSize = o.quick ? size : Extent{1920, 1080};
    for (const auto& p : presets()) {
      if (o.quick && p.preset != Preset::High) continue;
      for (int d : divisors) {
        Settings t = presetSettings(p.preset);
        t.resolution_divisor = d;
        const std::string variant = "divisor=" + std::to_string(d);
        for (const auto& scene : sceneNames) run("divisor", scene, first, std::string(p.name), variant, t, size, true);
        for (auto& b : backends) run("divisor_time", mainScene, *b, std::string(p.name), variant, t, timeSize, false);
      }
    }
  }

  // intermediates ([bandwidth]): every preset with rg32f and with rg16f (A, key) images
  // (half_intermediates), the rest unchanged; error vs (c) as the divisor section measures it, time
  // at 1920x1080 with a preset's two formats one after another.
  if (want("intermediates")) {
    const Extent timeSize = o.quick ? size : Extent{1920, 1080};
    for (const auto& p : presets()) {
      if (o.quick && p.preset != Preset::Medium) continue;
      for (bool half : {false, true}) {
        Settings t = presetSettings(p.preset);
        t.half_intermediates = half;
        const std::string variant = half ? "rg16f" : "rg32f";
        for (const auto& scene : sceneNames)
          run("intermediates", scene, first, std::string(p.name), variant, t, size, true);
        for (auto& b : backends)
          run("intermediates_time", mainScene, *b, std::string(p.name), variant, t, timeSize, false);
      }
    }
  }

  // two_layer: the default scene with and without the second depth layer, every backend.
  if (want("two_layer"))
    for (auto& b : backends) {
      run("two_layer", mainScene, *b, "medium", "one layer", base, size, true);
      run("two_layer", mainScene, *b, "medium", "two layers", base, size, true, 1, Extra::SecondLayer);
    }

  // precision (paper Figures 3 and 4): every prepass that starts, on the dedicated panel scene.
  std::vector<std::pair<std::string, std::vector<prepass::PrecisionRow>>> precision;
  if (want("precision"))
    for (const char* api : {"gl", "vulkan"}) {
      std::unique_ptr<prepass::Prepass> pp;
      if (Status s = prepass::createPrepass(api, pp); !s) {
        std::fprintf(stderr, "\nsao-bench: precision: skipping the %s prepass: %s\n", api, s.message.c_str());
        continue;
      }
      progress(std::string("precision: ") + api + " prepass");
      prepass::PrecisionOptions po;
      if (o.quick) po.width = 320, po.height = 180;
      else po.width = o.size.width, po.height = o.size.height;
      std::vector<prepass::PrecisionRow> rowsOut;
      if (Status s = prepass::measurePrecision(*pp, po, rowsOut); !s) fail(std::string("precision on ") + api + ": " + s.message);
      precision.emplace_back(api, std::move(rowsOut));
    }

  std::fprintf(stderr, "\n");

  // calibrate: the appearance defaults fitted to reference (a) at --size, confirmed at 1280x720 (calibrate.h).
  if (want("calibrate"))
    if (Status s = bench::calibrateSection({out, sceneNames, size, o.quick ? size : Extent{1280, 720}, o.rays,
                                            int(o.runs), o.quick}, first, cache);
        !s)
      fail("calibrate: " + s.message);

  // spiral: the lattice criterion against G3D's table (shipped), by error vs (c) (spiral_section.h).
  if (want("spiral")) {
    bench::SpiralOptions so;
    so.outDir = out;
    so.scenes = sceneNames;
    so.size = size;
    so.convergedTaps = o.convergedTaps;
    if (o.quick) so.sampleCounts = {16};
    if (Status s = bench::spiralSection(so, first, cache); !s) fail("spiral: " + s.message);
  }

  // frames: a static camera's frames averaged against 4x the taps, by error vs (c) (frames_section.h).
  if (want("frames")) {
    bench::FramesOptions fo;
    fo.outDir = out;
    fo.scenes = sceneNames;
    fo.size = size;
    fo.convergedTaps = o.convergedTaps;
    if (o.quick) fo.frames = 4, fo.presets = {Preset::Medium};
    if (Status s = bench::framesSection(fo, first, cache); !s) fail("frames: " + s.message);
  }

  // paths: the camera paths with and without temporal accumulation (paths_section.h).
  if (want("paths")) {
    bench::PathsOptions po;
    po.outDir = out;
    po.scenes = sceneNames;
    if (o.sizeGiven) po.size = o.size;
    if (o.quick) po.frames = 4, po.size = Extent{96, 54};
    if (Status s = bench::pathsSection(po, first, cache); !s) fail("paths: " + s.message);
  }

  // per_tap: ao_sample's time per tap beside a ladder of minimal GL passes (per_tap_section.h).
  if (want("per_tap")) {
    bench::PerTapOptions po;
    po.outDir = out;
    po.scene = mainScene;
    po.size = o.quick ? Extent{320, 180} : o.sizeGiven ? o.size : Extent{1920, 1080};
    po.runs = int(o.runs);
    samples::BackendRunner* gl = nullptr;
    for (auto& b : backends)
      if (b->name() == "gl") gl = b.get();
    if (Status s = bench::perTapSection(po, gl, cache); !s) fail("per_tap: " + s.message);
  }

  // traffic: the memory-traffic model on the main scene (traffic_section.h).
  if (want("traffic"))
    if (Status s = bench::trafficSection(out, mainScene, o.quick, [&](Extent e) {
          Prepared& p = cache.prepare(mainScene, e.width, e.height);
          return bench::TrafficInput{&p.primary.depth, p.camera};
        });
        !s)
      fail("traffic: " + s.message);

  // Reports.
  auto legend = notes(depthSource);
  std::string times;
  for (const std::string& t : convergedTimes) times += (times.empty() ? "" : "; ") + t;
  if (!times.empty()) legend.emplace_back("converged time", "wall (and CPU, all threads) time of each reference (c): " + times);
  std::string dTimes;
  for (const std::string& t : screenTimes) dTimes += (dTimes.empty() ? "" : "; ") + t;
  if (!dTimes.empty()) legend.emplace_back("screen time", "wall (and CPU, all threads) time of each reference (d): " + dTimes);
  std::string noises;
  for (const std::string& t : aoNoises) noises += (noises.empty() ? "" : "; ") + t;
  if (!noises.empty())
    legend.emplace_back("ao noise", "reference (a)'s own noise at " + std::to_string(o.rays) +
                                        " rays, RMS over the pixels with geometry of (a1 - a2)/sqrt(2) (two seeds): " + noises);
  bench::writeCsv((fs::path(out) / "results.csv").string(), rows);
  bench::writeJson((fs::path(out) / "results.json").string(), rows, machine, legend);
  const auto charts = bench::writeCharts(out, rows, mainScene, std::string(first.name()));
  std::string files = "reference_check.csv,results.csv,results.json";
  for (const auto& c : charts) files += "," + c;
  if (!precision.empty()) {
    bench::writePrecision(out, precision);
    files += ",precision.csv,precision.txt";
  }
  for (const auto& [section, file] : {std::pair{"spiral", ",spiral.csv"}, {"frames", ",frames.csv"}, {"paths", ",paths.csv"},
                                     {"calibrate", ",calibration.csv"}, {"traffic", ",traffic.csv"}, {"per_tap", ",per_tap.csv"}})
    if (want(section) && fs::exists(fs::path(out) / (file + 1))) files += file;  // per_tap may skip
  if (Status s = g_output->commit(); !s) fail(s.message);
  std::printf("sao-bench: %zu measurements on %s\nwrote %s/{%s}\n", rows.size(), machine.c_str(),
              g_output->path().string().c_str(), files.c_str());
  for (const auto& [key, text] : legend) std::printf("  %s: %s\n", key.c_str(), text.c_str());
  return 0;
}
