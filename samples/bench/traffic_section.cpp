#include "traffic_section.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "sao/presets.h"
#include "traffic_machines.h"
#include "traffic_replay.h"

namespace sao::bench {

namespace {

struct Row {
  std::string section;
  std::size_t variant;
  std::size_t base;  // the variant of the ratios' denominator at the same point
  Extent size;
  double radius;
  ReplayResult result;
};

double perPixel(std::uint64_t bytes, const ReplayResult& r) { return r.pixels ? double(bytes) / double(r.pixels) : 0; }

// The ratios' denominator at the same point: SAO with the hierarchy (variant 0) in the radius and
// resolution sections, the default preset in the presets section.
const Row& baseRow(const std::vector<Row>& rows, const Row& r) {
  for (const Row& o : rows)
    if (o.variant == r.base && o.section == r.section && o.size == r.size && o.radius == r.radius) return o;
  return r;
}

std::string ratio(double a, double b) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g", b > 0 ? a / b : 0.0);
  return s;
}

Status writeCsv(const std::string& path, const std::string& scene, const std::vector<Machine>& machines,
                const std::vector<TrafficVariant>& variants, const std::vector<Row>& rows) {
  for (const Machine& m : machines)  // plain CSV: names carry no commas
    if (m.name.find(',') != std::string::npos)
      return Status::error(StatusCode::InvalidInput, "traffic: machine name '" + m.name + "' has a comma");
  std::ofstream f(path);
  if (!f) return Status::error(StatusCode::IoError, "cannot write '" + path + "'");
  f << "section,scene,machine,variant,width,height,radius_m,max_mip,reads_per_pixel,l1_hit_rate,l2_hit_rate,"
       "l2_bytes_per_pixel,memory_bytes_per_pixel,l2_bytes_vs_sao,memory_bytes_vs_sao,width_l2_bytes_per_pixel,"
       "width_memory_bytes_per_pixel,ao_pixels\n";
  for (std::size_t m = 0; m < machines.size(); ++m)
    for (const Row& r : rows) {
      const Traffic& t = r.result.traffic[m];
      const Traffic& denom = baseRow(rows, r).result.traffic[m];
      const Traffic& width = r.result.widthTraffic[m];
      char line[512];
      std::snprintf(line, sizeof line, "%s,%s,%s,%s,%u,%u,%g,%d,%.4g,%.4f,%.4f,%.4g,%.4g,%s,%s,%.4g,%.4g,%llu\n",
                    r.section.c_str(),
                    scene.c_str(), machines[m].name.c_str(), variants[r.variant].label.c_str(), r.size.width,
                    r.size.height, r.radius, r.result.maxMip, perPixel(t.reads, r.result),
                    t.reads ? 1.0 - double(t.l1Misses) / double(t.reads) : 0.0,
                    t.l1Misses ? 1.0 - double(t.l2Misses) / double(t.l1Misses) : 0.0,
                    perPixel(t.l2Bytes(), r.result), perPixel(t.memoryBytes(), r.result),
                    ratio(double(t.l2Bytes()), double(denom.l2Bytes())).c_str(),
                    ratio(double(t.memoryBytes()), double(denom.memoryBytes())).c_str(),
                    perPixel(width.l2Bytes(), r.result), perPixel(width.memoryBytes(), r.result),
                    static_cast<unsigned long long>(r.result.pixels));
      f << line;
    }
  f.close();
  if (!f) return Status::error(StatusCode::IoError, "cannot write '" + path + "'");
  return Status::success();
}

void printSummary(const std::vector<Machine>& machines, const std::vector<TrafficVariant>& variants,
                  const std::vector<Row>& rows) {
  for (std::size_t m = 0; m < machines.size(); ++m) {
    std::printf("traffic, %s: %s\n  bytes per AO pixel from L2 / from memory, and ÷ SAO (z hierarchy) (presets: ÷ the default):\n",
                machines[m].name.c_str(), describe(machines[m]).c_str());
    for (const Row& r : rows) {
      const Traffic& t = r.result.traffic[m];
      const Traffic& denom = baseRow(rows, r).result.traffic[m];
      const Traffic& width = r.result.widthTraffic[m];
      std::printf("  %-10s %4ux%-4u r %-4g %-30s %8.1f / %8.1f  (x%s / x%s)", r.section.c_str(), r.size.width,
                  r.size.height, r.radius, variants[r.variant].label.c_str(), perPixel(t.l2Bytes(), r.result),
                  perPixel(t.memoryBytes(), r.result), ratio(double(t.l2Bytes()), double(denom.l2Bytes())).c_str(),
                  ratio(double(t.memoryBytes()), double(denom.memoryBytes())).c_str());
      if (width.reads > 0)
        std::printf("  of which the width passes %.1f / %.1f", perPixel(width.l2Bytes(), r.result),
                    perPixel(width.memoryBytes(), r.result));
      if (r.section == "presets")  // presets differ in resolution: the frame's bytes compare them
        std::printf("  per frame %.2f / %.2f MB", double(t.l2Bytes()) / 1e6, double(t.memoryBytes()) / 1e6);
      std::printf("\n");
    }
  }
}

}  // namespace

Status trafficSection(const std::string& outDir, const std::string& sceneName, bool quick,
                      const std::function<TrafficInput(Extent)>& sceneAt) {
  std::string cpuSource;
  const std::vector<Machine> machines = {paperLikeMachine(), paperLikeMachine(48 * 1024),
                                         thisCpuMachine(cpuSource)};
  // The curves: the medium preset's sampling read four ways, and the ultra preset (the visibility
  // estimator with thickness from width: the width passes, and each tap reads csz_share instead of csz).
  // Then every preset as it is, for the presets section.
  std::vector<TrafficVariant> variants = {{"SAO (z hierarchy)", true, false, 4},
                                          {"SAO (no hierarchy)", false, false, 4},
                                          {"AlchemyAO-style", false, true, 4},
                                          {"AlchemyAO float4 positions", false, true, 16},
                                          {"ultra: visibility from width", true, false, 4}};
  std::vector<Preset> curvePresets = {Preset::Medium, Preset::Medium, Preset::Medium, Preset::Medium, Preset::Ultra};
  const std::size_t curves = variants.size();
  std::size_t defaultVariant = curves;
  for (const PresetInfo& p : presets()) {
    if (p.preset == Preset::High) defaultVariant = variants.size();  // the settings' defaults
    variants.push_back({"preset " + std::string(p.name), presetSettings(p.preset).use_z_hierarchy, false, 4});
    curvePresets.push_back(p.preset);
  }
  const std::vector<double> radii = quick ? std::vector<double>{0.1, 1.5}
                                          : std::vector<double>{0.1, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0};
  const Extent radiusSize = quick ? Extent{160, 90} : Extent{1920, 1080};
  const std::vector<Extent> sizes = quick ? std::vector<Extent>{{160, 90}, {320, 180}}
                                          : std::vector<Extent>{{1280, 720}, {1920, 1080}, {2560, 1600}};
  const Settings base = presetSettings(Preset::Medium);

  std::map<std::pair<std::uint32_t, std::uint32_t>, std::unique_ptr<TrafficScene>> scenes;
  std::vector<Row> rows;
  // Replays done, so that a point met again is copied, not replayed (the radius section's 1 m rows
  // are the resolution section's at its size; the presets' medium and ultra the curves' at 1 m).
  struct Replayed {
    Extent size;
    Settings settings;  // as replay() takes them: use_z_hierarchy from the variant
    bool normalsSupplied;
    std::uint32_t zTexelBytes;
    std::size_t row;
  };
  std::vector<Replayed> replayed;
  auto point = [&](const std::string& section, Extent size, double radius, std::size_t first, std::size_t end,
                   std::size_t ratioBase) -> Status {
    std::unique_ptr<TrafficScene>& scene = scenes[{size.width, size.height}];
    if (!scene) {
      const TrafficInput in = sceneAt(size);
      if (in.depth == nullptr) return Status::error(StatusCode::InvalidInput, "traffic: no depth for the scene");
      if (Status s = TrafficScene::create(*in.depth, in.camera, scene); !s) return s;
    }
    for (std::size_t v = first; v < end; ++v) {
      Settings s = presetSettings(curvePresets[v]);
      s.radius = float(radius);
      s.use_z_hierarchy = variants[v].zHierarchy;
      const auto same = std::find_if(replayed.begin(), replayed.end(), [&](const Replayed& p) {
        return p.size == size && p.settings == s && p.normalsSupplied == variants[v].normalsSupplied &&
               p.zTexelBytes == variants[v].zTexelBytes;
      });
      Row& r = rows.emplace_back(Row{section, v, ratioBase, size, radius, {}});
      if (same != replayed.end()) {
        r.result = rows[same->row].result;
        continue;
      }
      std::fprintf(stderr, "\r\033[Ktraffic: %s %ux%u r %g %s", section.c_str(), size.width, size.height, radius,
                   variants[v].label.c_str());
      std::fflush(stderr);
      if (Status st = scene->replay(s, variants[v], machines, r.result); !st) return st;
      replayed.push_back({size, s, variants[v].normalsSupplied, variants[v].zTexelBytes, rows.size() - 1});
    }
    return Status::success();
  };
  for (double r : radii)
    if (Status s = point("radius", radiusSize, r, 0, curves, 0); !s) return s;
  for (Extent e : sizes)
    if (Status s = point("resolution", e, double(base.radius), 0, curves, 0); !s) return s;
  if (Status s = point("presets", radiusSize, double(base.radius), curves, variants.size(), defaultVariant); !s)
    return s;
  std::fprintf(stderr, "\n");

  const std::string path = (std::filesystem::path(outDir) / "traffic.csv").string();
  if (Status s = writeCsv(path, sceneName, machines, variants, rows); !s) return s;
  printSummary(machines, variants, rows);
  std::printf("traffic: scene %s; this CPU's caches from %s; wrote traffic.csv\n", sceneName.c_str(),
              cpuSource.c_str());  // in the output folder, moved into place when the run ends
  return Status::success();
}

}  // namespace sao::bench
