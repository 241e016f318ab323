// sao-bench: what each preset costs and how far it is from the ray-traced truth, plus the sweeps
// of the paper (radius: Figure 5; resolution: Table 3). Writes CSV, JSON and SVG plots.
// `sao-bench --help` lists the options; `--quick` is the small run the tests use.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "measure.h"
#include "sao/presets.h"
#include "sao/raytrace/raytrace.h"
#include "sao/scenes/scene.h"
#include "svg_plot.h"

namespace fs = std::filesystem;
using namespace sao;

namespace {

constexpr const char* kUsage = R"(usage: sao-bench [options]
Measures every preset on every scene and backend (median per-pass time of --runs runs, and the
error against a ray-traced near-field AO reference), then the sweeps: samples, MIP and blur on/off,
radius (paper Fig. 5) and resolution (paper Table 3). Writes results.csv, results.json and SVG plots.
  --out DIR        output folder (default out/bench)
  --backends LIST  comma-separated: cpu,gl,vulkan (default: gl,vulkan,cpu, those that start)
  --runs N         measured runs per point, after one warm-up (default 5)
  --rays N         reference rays per pixel (default 256)
  --size WxH       size of the preset matrix and sweeps (default 1280x720)
  --quick          the smoke run: 160x90, 3 runs, 16 rays, two scenes, short sweeps
  --help
)";

struct Options {
  std::string out = "out/bench", backends = "gl,vulkan,cpu";
  int runs = 5;
  std::uint32_t rays = 256, width = 1280, height = 720;
  bool quick = false;
};

[[noreturn]] void fail(const std::string& m, int code = 1) {
  std::fprintf(stderr, "\nsao-bench: %s\n", m.c_str());
  std::exit(code);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) fail(a + " needs a value (see --help)", 2);
      return argv[++i];
    };
    auto count = [&](const std::string& v, long lo, long hi) {
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end || n < lo || n > hi) fail(a + " expects a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", 2);
      return n;
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a == "--out") o.out = value();
    else if (a == "--backends") o.backends = value();
    else if (a == "--runs") o.runs = int(count(value(), 1, 1000));
    else if (a == "--rays") o.rays = std::uint32_t(count(value(), 1, 65536));
    else if (a == "--size") {
      const std::string v = value();
      const auto x = v.find('x');
      if (x == std::string::npos) fail("--size expects WxH", 2);
      o.width = std::uint32_t(count(v.substr(0, x), 1, 8192));
      o.height = std::uint32_t(count(v.substr(x + 1), 1, 8192));
    } else if (a == "--quick") o.quick = true;
    else fail("unknown option '" + a + "' (see --help)", 2);
  }
  if (o.quick) o.width = 160, o.height = 90, o.runs = 3, o.rays = 16;
  return o;
}

// A scene at one size: its ray caster, primary rays and references per radius.
struct Prepared {
  scenes::Scene scene;
  std::unique_ptr<raytrace::RayScene> rays;
  Camera camera;
  raytrace::Primary primary;
  std::vector<unsigned char> mask;
  std::map<double, FloatImage> references;
};

Prepared& prepare(std::map<std::string, Prepared>& cache, const std::string& name, std::uint32_t w, std::uint32_t h) {
  const std::string key = name + "@" + std::to_string(w) + "x" + std::to_string(h);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Prepared& p = cache[key];
  if (Status s = scenes::makeBuiltinScene(name, p.scene); !s) fail(s.message);
  if (Status s = raytrace::RayScene::create(p.scene.mesh, p.rays); !s) fail(s.message);
  p.camera = scenes::makeCamera(p.scene.views[0], w, h, INFINITY, ClipDepth::ZeroToOne, true);
  if (Status s = raytrace::castPrimary(*p.rays, p.scene.views[0], p.camera, DepthFormat::D32F, p.primary); !s) fail(s.message);
  p.mask = samples::geometryMask(p.primary.position, 0);
  return p;
}

const FloatImage& reference(Prepared& p, double radius, std::uint32_t rays) {
  auto it = p.references.find(radius);
  if (it != p.references.end()) return it->second;
  raytrace::ReferenceOptions o;
  o.radius = radius;
  o.rays = rays;
  FloatImage& ref = p.references[radius];
  if (Status s = raytrace::referenceAmbientOcclusion(*p.rays, p.camera, p.primary, p.scene.views[0], o, ref); !s)
    fail(s.message);
  return ref;
}

struct Row {
  std::string section, scene, backend, preset, variant;
  Extent size;
  Settings settings;
  bench::Measurement m;
};

double passMs(const bench::Measurement& m, const char* name) {
  for (const auto& p : m.passes)
    if (p.pass == name) return p.milliseconds;
  return 0;
}

void writeCsv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream f(path);
  f << "section,scene,backend,preset,variant,width,height,radius_m,samples,use_z_hierarchy,blur_radius,runs,"
       "timing_method,linear_z_ms,mips_ms,ao_sample_ms,blur_h_ms,blur_v_ms,total_ms,ns_per_pixel,plan_bytes,"
       "csz_levels,rmse_raw,bias_raw,ssim_raw,over_0_1_raw,fitted_scale,rmse_fitted,bias_fitted,ssim_fitted,"
       "over_0_1_fitted\n";
  for (const auto& r : rows) {
    const auto& m = r.m;
    f << r.section << "," << r.scene << "," << r.backend << "," << r.preset << "," << r.variant << "," << r.size.width
      << "," << r.size.height << "," << r.settings.radius << "," << r.settings.samples << ","
      << r.settings.use_z_hierarchy << "," << r.settings.blur_radius << "," << m.runs << ",\"" << toString(m.method)
      << "\"," << passMs(m, "linear_z") << "," << passMs(m, "mips") << "," << passMs(m, "ao_sample") << ","
      << passMs(m, "blur_h") << "," << passMs(m, "blur_v") << "," << m.totalMs << ","
      << m.totalMs * 1e6 / (double(r.size.width) * r.size.height) << "," << m.planBytes << "," << m.cszLevels;
    if (m.error) {
      const auto& e = *m.error;
      f << "," << e.raw.rmse << "," << e.raw.meanBias << "," << e.raw.ssim << "," << e.raw.fractionOver01 << ","
        << e.fittedIntensity << "," << e.fitted.rmse << "," << e.fitted.meanBias << "," << e.fitted.ssim << ","
        << e.fitted.fractionOver01;
    } else {
      f << ",,,,,,,,,";
    }
    f << "\n";
  }
}

void writeJson(const std::string& path, const std::vector<Row>& rows, const std::string& machine) {
  std::ofstream f(path);
  f << "{\n  \"machine\": \"" << machine << "\",\n  \"rows\": [\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    f << "    {\"section\": \"" << r.section << "\", \"scene\": \"" << r.scene << "\", \"backend\": \"" << r.backend
      << "\", \"preset\": \"" << r.preset << "\", \"variant\": \"" << r.variant << "\", \"width\": " << r.size.width
      << ", \"height\": " << r.size.height << ", \"radius_m\": " << r.settings.radius
      << ", \"samples\": " << r.settings.samples << ", \"timing_method\": \"" << toString(r.m.method)
      << "\", \"runs\": " << r.m.runs << ", \"total_ms\": " << r.m.totalMs << ", \"pass_ms\": {";
    for (std::size_t k = 0; k < r.m.passes.size(); ++k)
      f << (k ? ", " : "") << "\"" << r.m.passes[k].pass << "\": " << r.m.passes[k].milliseconds;
    f << "}";
    if (r.m.error)
      f << ", \"rmse_raw\": " << r.m.error->raw.rmse << ", \"bias_raw\": " << r.m.error->raw.meanBias
        << ", \"ssim_raw\": " << r.m.error->raw.ssim << ", \"fitted_scale\": " << r.m.error->fittedIntensity
        << ", \"rmse_fitted\": " << r.m.error->fitted.rmse;
    f << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
  }
  f << "  ]\n}\n";
}

void writeSvg(const std::string& path, const bench::Chart& chart) { std::ofstream(path) << bench::renderSvg(chart); }

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) fail("cannot create '" + o.out + "': " + ec.message());

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

  const std::vector<std::string> sceneNames =
      o.quick ? std::vector<std::string>{"crease", "sphere-plane"}
              : std::vector<std::string>{"sponza-like", "sphere-plane", "crease", "thin", "gears"};
  const std::string mainScene = o.quick ? "sphere-plane" : std::string(scenes::kDefaultScene);
  std::map<std::string, Prepared> cache;
  std::vector<Row> rows;
  int step = 0;
  auto progress = [&](const std::string& what) {
    std::fprintf(stderr, "\r\033[K[%d] %s", ++step, what.c_str());
    std::fflush(stderr);
  };
  auto run = [&](const std::string& section, const std::string& scene, samples::BackendRunner& b,
                 const std::string& preset, const std::string& variant, const Settings& s, Extent size, bool withError) {
    progress(section + ": " + scene + " " + std::string(b.name()) + " " + preset + " " + variant + " " +
             std::to_string(size.width) + "x" + std::to_string(size.height));
    Prepared& p = prepare(cache, scene, size.width, size.height);
    const FloatImage* ref = withError ? &reference(p, s.radius, o.rays) : nullptr;
    Row r{section, scene, std::string(b.name()), preset, variant, size, s, {}};
    if (Status st = bench::measure(b, s, p.camera, p.primary.depth, o.runs, ref, &p.mask, r.m); !st)
      fail(section + " " + scene + ": " + st.message);
    rows.push_back(std::move(r));
  };
  const Extent size{o.width, o.height};

  // 1. Every preset on every scene and backend: the speed/accuracy trade.
  for (const auto& scene : sceneNames)
    for (auto& b : backends)
      for (const auto& p : presets()) run("presets", scene, *b, std::string(p.name), "", presetSettings(p.preset), size, true);

  // 2. Sweeps on the main scene and the first backend.
  auto& first = *backends.front();
  const Settings base = presetSettings(Preset::Medium);
  for (int s : o.quick ? std::vector<int>{4, 16} : std::vector<int>{4, 8, 11, 16, 24, 32, 48, 64}) {
    Settings t = base;
    t.samples = s;
    run("samples", mainScene, first, "medium", "samples=" + std::to_string(s), t, size, true);
  }
  for (bool mips : {true, false})
    for (bool blur : {true, false}) {
      Settings t = base;
      t.use_z_hierarchy = mips;
      t.blur_radius = blur ? base.blur_radius : 0;
      run("mip_blur", mainScene, first, "medium", std::string("mips=") + (mips ? "on" : "off") + " blur=" + (blur ? "on" : "off"), t, size, true);
    }
  const Extent radiusSize = o.quick ? size : Extent{1920, 1080};
  for (double r : o.quick ? std::vector<double>{0.1, 1.5} : std::vector<double>{0.1, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0})
    for (bool mips : {true, false}) {
      Settings t = base;
      t.radius = float(r);
      t.use_z_hierarchy = mips;
      run("radius", mainScene, first, "medium", mips ? "z hierarchy" : "no hierarchy (full-res z)", t, radiusSize, false);
    }
  for (Extent e : o.quick ? std::vector<Extent>{{160, 90}, {320, 180}}
                          : std::vector<Extent>{{1280, 720}, {1920, 1080}, {2560, 1600}})
    for (auto& b : backends) run("resolution", mainScene, *b, "medium", "", base, e, false);
  std::fprintf(stderr, "\n");

  // Reports.
  writeCsv((fs::path(o.out) / "results.csv").string(), rows);
  writeJson((fs::path(o.out) / "results.json").string(), rows, machine);
  bench::Chart pareto{"Error vs time per preset (" + mainScene + ")", "total time, ms", "RMSE vs reference (raw)", true, false, {}};
  bench::Chart radius{"Time vs radius (" + mainScene + ", " + std::string(first.name()) + ")", "radius, m", "ao_sample time, ms", false, false, {}};
  bench::Chart resolution{"Time vs resolution (" + mainScene + ", medium)", "pixels", "total time, ms", true, false, {}};
  std::map<std::string, bench::Series> paretoSeries, radiusSeries, resolutionSeries;
  for (const auto& r : rows) {
    if (r.section == "presets" && r.scene == mainScene && r.m.error) {
      auto& s = paretoSeries[r.backend];
      s.label = r.backend;
      s.x.push_back(r.m.totalMs);
      s.y.push_back(r.m.error->raw.rmse);
      s.pointLabels.push_back(r.preset);
    } else if (r.section == "radius") {
      auto& s = radiusSeries[r.variant];
      s.label = r.variant;
      s.x.push_back(r.settings.radius);
      s.y.push_back(passMs(r.m, "ao_sample"));
    } else if (r.section == "resolution") {
      auto& s = resolutionSeries[r.backend];
      s.label = r.backend;
      s.x.push_back(double(r.size.width) * r.size.height);
      s.y.push_back(r.m.totalMs);
    }
  }
  for (auto& [k, s] : paretoSeries) pareto.series.push_back(s);
  for (auto& [k, s] : radiusSeries) radius.series.push_back(s);
  for (auto& [k, s] : resolutionSeries) resolution.series.push_back(s);
  writeSvg((fs::path(o.out) / "pareto.svg").string(), pareto);
  writeSvg((fs::path(o.out) / "radius.svg").string(), radius);
  writeSvg((fs::path(o.out) / "resolution.svg").string(), resolution);
  std::printf("sao-bench: %zu measurements on %s\nwrote %s/{results.csv,results.json,pareto.svg,radius.svg,resolution.svg}\n",
              rows.size(), machine.c_str(), fs::absolute(o.out).lexically_normal().string().c_str());
  return 0;
}
