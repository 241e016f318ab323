#include "calibrate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "measure.h"
#include "sao/presets.h"
#include "sao/samples/metrics.h"

namespace sao::bench {

namespace {

struct Point {
  float intensity, contrast, bias, epsilon;
};

struct SceneResult {
  double rmse = NAN, scale = NAN, rmseFitted = NAN, meanBias = NAN, totalMs = NAN;
};

struct Evaluated {
  std::string stage;
  double radius = 1;
  Extent size;
  Point point{};
  std::vector<SceneResult> scenes;
  double meanRmse = NAN;
  double maxScaleDeviation = NAN;  // max over the scenes of |fitted_scale - 1|
};

// The grid, every value in the settings' ranges (effect/sao.glsl). Each axis also holds the
// current default, so that the "before" row is one of its points whatever the defaults are.
struct Grid {
  std::vector<float> intensity, contrast, bias, epsilon;
  std::vector<Point> points() const {
    std::vector<Point> out;
    for (float i : intensity)
      for (float c : contrast)
        for (float b : bias)
          for (float e : epsilon) out.push_back({i, c, b, e});
    return out;
  }
};

void withValue(std::vector<float>& axis, float value) {
  if (std::find(axis.begin(), axis.end(), value) == axis.end()) axis.push_back(value);
  std::sort(axis.begin(), axis.end());
}

Grid gridFor(bool quick) {
  const Settings d = presetSettings(Preset::Medium);
  // --quick: the defaults and 1.5 times their intensity and contrast, four points.
  if (quick) return {{d.intensity, 1.5f * d.intensity}, {d.contrast, 1.5f * d.contrast}, {d.bias}, {d.epsilon}};
  Grid g{{1.0f, 1.25f, 1.5f, 1.75f, 2.0f, 2.5f, 3.0f},
         {0.75f, 1.0f, 1.25f, 1.5f, 2.0f},
         {0.0f, 0.01f, 0.02f, 0.04f},
         {1e-4f, 1e-3f, 1e-2f}};
  withValue(g.intensity, d.intensity);
  withValue(g.contrast, d.contrast);
  withValue(g.bias, d.bias);
  withValue(g.epsilon, d.epsilon);
  return g;
}

Settings settingsAt(const Point& p, double radius) {
  Settings s = presetSettings(Preset::Medium);
  s.radius = float(radius);
  s.intensity = p.intensity;
  s.contrast = p.contrast;
  s.bias = p.bias;
  s.epsilon = p.epsilon;
  return s;
}

Point defaultPoint() {
  const Settings s = presetSettings(Preset::Medium);
  return {s.intensity, s.contrast, s.bias, s.epsilon};
}

bool samePoint(const Point& a, const Point& b) {
  return a.intensity == b.intensity && a.contrast == b.contrast && a.bias == b.bias && a.epsilon == b.epsilon;
}

class Evaluator {
 public:
  Evaluator(const CalibrateOptions& o, samples::BackendRunner& b, SceneCache& c) : o_(o), backend_(b), cache_(c) {}

  // One point on every scene. timedRuns 0: one untimed run; otherwise bench::measure's median.
  Status evaluate(const std::string& stage, const Point& point, double radius, Extent size, int timedRuns,
                  Evaluated& out) {
    out = Evaluated{stage, radius, size, point, {}, 0, 0};
    const Settings s = settingsAt(point, radius);
    for (const std::string& name : o_.scenes) {
      std::fprintf(stderr, "\r\033[Kcalibrate: %s r %g %ux%u %s i %g k %g b %g e %g", stage.c_str(), radius,
                   size.width, size.height, name.c_str(), point.intensity, point.contrast, point.bias, point.epsilon);
      std::fflush(stderr);
      Prepared& p = cache_.prepare(name, size.width, size.height);
      const FloatImage& reference = nearFieldReference(p, radius, o_.rays);
      SceneResult r;
      FloatImage ao;
      if (timedRuns > 0) {
        Measurement m;
        if (Status st = measure(backend_, s, p.camera, runInputs(p, Extra::None), timedRuns, {}, m); !st) return st;
        r.totalMs = m.totalMs;
        ao = std::move(m.ao);
      } else {
        samples::RunOutputs run;
        if (Status st = backend_.run(s, p.camera, runInputs(p, Extra::None), false, false, run); !st) return st;
        ao = std::move(run.ao);
      }
      const samples::ReferenceComparison c = samples::compareToReference(ao, reference, p.mask);
      r.rmse = c.raw.rmse;
      r.scale = c.fittedIntensity;
      r.rmseFitted = c.fitted.rmse;
      r.meanBias = c.raw.meanBias;
      out.meanRmse += r.rmse / double(o_.scenes.size());
      // An undefined scale (no occlusion at all) can never be within the tolerance.
      out.maxScaleDeviation = std::max(out.maxScaleDeviation, std::isnan(r.scale) ? INFINITY : std::abs(r.scale - 1));
      out.scenes.push_back(r);
    }
    return Status::success();
  }

 private:
  const CalibrateOptions& o_;
  samples::BackendRunner& backend_;
  SceneCache& cache_;
};

// The least mean RMSE among the points whose every scale is within the tolerance; when none is,
// the point of least max |scale - 1| (met = false).
std::size_t pick(const std::vector<Evaluated>& points, bool& met) {
  std::size_t best = 0;
  met = false;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool ok = points[i].maxScaleDeviation <= kCalibrationScaleTolerance;
    if (ok && (!met || points[i].meanRmse < points[best].meanRmse)) best = i, met = true;
  }
  if (met) return best;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i].maxScaleDeviation < points[best].maxScaleDeviation) best = i;
  return best;
}

std::size_t leastRmse(const std::vector<Evaluated>& points) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i].meanRmse < points[best].meanRmse) best = i;
  return best;
}

// The least mean RMSE among the points with max |scale - 1| <= limit; points.size() when none.
std::size_t leastRmseWithin(const std::vector<Evaluated>& points, double limit) {
  std::size_t best = points.size();
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].maxScaleDeviation <= limit && (best == points.size() || points[i].meanRmse < points[best].meanRmse))
      best = i;
  return best;
}

std::string describe(const Point& p) {
  char s[128];
  std::snprintf(s, sizeof s, "intensity %g, contrast %g, bias %g, epsilon %g", p.intensity, p.contrast, p.bias,
                p.epsilon);
  return s;
}

void printPoint(const char* label, const std::vector<std::string>& scenes, const Evaluated& e) {
  std::printf("  %-22s %s (r %g m, %ux%u): mean RMSE vs (a) %.4f, max |scale - 1| %.3f\n", label,
              describe(e.point).c_str(), e.radius, e.size.width, e.size.height, e.meanRmse, e.maxScaleDeviation);
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const SceneResult& r = e.scenes[i];
    std::printf("    %-13s RMSE %.4f  scale %.3f  fitted RMSE %.4f  bias %+.4f", scenes[i].c_str(), r.rmse, r.scale,
                r.rmseFitted, r.meanBias);
    if (!std::isnan(r.totalMs)) std::printf("  %.3f ms", r.totalMs);
    std::printf("\n");
  }
}

Status writeCsv(const std::string& path, const std::vector<std::string>& scenes, const std::vector<Evaluated>& rows) {
  std::ofstream f(path);
  if (!f) return Status::error(StatusCode::IoError, "cannot write '" + path + "'");
  f << "stage,radius_m,width,height,intensity,contrast,bias,epsilon,scene,ao_rmse_raw,ao_fitted_scale,ao_rmse_fitted,"
       "ao_bias_raw,total_ms,mean_ao_rmse_raw,max_abs_scale_minus_1\n";
  for (const Evaluated& e : rows)
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      const SceneResult& r = e.scenes[i];
      char line[512];
      std::snprintf(line, sizeof line, "%s,%g,%u,%u,%g,%g,%g,%g,%s,%.6f,%.6f,%.6f,%.6f,", e.stage.c_str(), e.radius,
                    e.size.width, e.size.height, e.point.intensity, e.point.contrast, e.point.bias, e.point.epsilon,
                    scenes[i].c_str(), r.rmse, r.scale, r.rmseFitted, r.meanBias);
      f << line;
      if (!std::isnan(r.totalMs)) f << r.totalMs;
      std::snprintf(line, sizeof line, ",%.6f,%.6f\n", e.meanRmse, e.maxScaleDeviation);
      f << line;
    }
  f.close();
  if (!f) return Status::error(StatusCode::IoError, "cannot write '" + path + "'");
  return Status::success();
}

}  // namespace

Status calibrateSection(const CalibrateOptions& o, samples::BackendRunner& backend, SceneCache& cache) {
  if (o.scenes.empty()) return Status::error(StatusCode::InvalidInput, "calibrate: no scenes");
  const auto start = std::chrono::steady_clock::now();
  const double radius = presetSettings(Preset::Medium).radius;
  const std::vector<Point> grid = gridFor(o.quick).points();
  Evaluator ev(o, backend, cache);
  std::vector<Evaluated> rows;

  // The grid at the default radius.
  auto sweep = [&](const std::string& stage, double r, std::vector<Evaluated>& out) -> Status {
    for (const Point& p : grid)
      if (Status s = ev.evaluate(stage, p, r, o.searchSize, 0, out.emplace_back()); !s) return s;
    rows.insert(rows.end(), out.begin(), out.end());
    return Status::success();
  };
  std::vector<Evaluated> search;
  if (Status s = sweep("search", radius, search); !s) return s;
  bool met = false;
  const Evaluated winner = search[pick(search, met)];
  const auto before = std::find_if(search.begin(), search.end(), [](const Evaluated& e) {
    return samePoint(e.point, defaultPoint());
  });
  if (before == search.end()) return Status::error(StatusCode::InvalidInput, "calibrate: the grid lacks the defaults");
  const double searchSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Whether the fit holds at other radii: the same grid, each radius's own winner and the default
  // radius's winner there.
  struct RadiusCheck {
    double radius;
    Evaluated winnerThere, ownWinner, defaultsThere;
    bool met;
  };
  std::vector<RadiusCheck> checks;
  if (!o.quick)
    for (double r : {0.5, 2.0}) {
      std::vector<Evaluated> at;
      if (Status s = sweep("radius_check", r, at); !s) return s;
      RadiusCheck c{r, {}, {}, {}, false};
      c.ownWinner = at[pick(at, c.met)];
      for (const Evaluated& e : at) {
        if (samePoint(e.point, winner.point)) c.winnerThere = e;
        if (samePoint(e.point, defaultPoint())) c.defaultsThere = e;
      }
      checks.push_back(std::move(c));
    }

  // The defaults, the winner and (when it differs) the least mean RMSE again at the confirmation
  // size, timed.
  std::vector<Evaluated> confirm;
  const bool confirmed = !o.quick && !(o.confirmSize == o.searchSize);
  const Point leastRmsePoint = search[leastRmse(search)].point;
  std::vector<Point> confirmPoints = {defaultPoint(), winner.point};
  if (!samePoint(leastRmsePoint, winner.point) && !samePoint(leastRmsePoint, defaultPoint()))
    confirmPoints.push_back(leastRmsePoint);
  if (confirmed)
    for (const Point& p : confirmPoints)
      if (Status s = ev.evaluate("confirm", p, radius, o.confirmSize, o.runs, confirm.emplace_back()); !s) return s;
  rows.insert(rows.end(), confirm.begin(), confirm.end());
  std::fprintf(stderr, "\n");

  const std::string path = (std::filesystem::path(o.outDir) / "calibration.csv").string();
  if (Status s = writeCsv(path, o.scenes, rows); !s) return s;

  const Grid g = gridFor(o.quick);
  std::printf("calibrate: medium preset on %s, reference (a) at %u rays; grid of %zu points (%zu intensity x %zu "
              "contrast x %zu bias x %zu epsilon) x %zu scenes at %ux%u, %.0f s\n",
              std::string(backend.name()).c_str(), o.rays, grid.size(), g.intensity.size(), g.contrast.size(),
              g.bias.size(), g.epsilon.size(), o.scenes.size(), o.searchSize.width, o.searchSize.height, searchSeconds);
  if (met)
    std::printf("calibrate: winner (least mean RMSE vs (a) with every scale within 1 +- %g):\n",
                kCalibrationScaleTolerance);
  else
    std::printf("calibrate: NO grid point has every scale within 1 +- %g; the least max |scale - 1|:\n",
                kCalibrationScaleTolerance);
  printPoint("before (defaults)", o.scenes, *before);
  printPoint("after (winner)", o.scenes, winner);
  printPoint("least mean RMSE", o.scenes, search[leastRmse(search)]);
  // The trade between the two aims when the tolerance cannot be met.
  std::printf("calibrate: least mean RMSE vs (a) with max |scale - 1| at most:\n");
  for (double limit : {0.15, 0.2, 0.25, 0.3, 0.4, 0.5}) {
    const std::size_t i = leastRmseWithin(search, limit);
    if (i == search.size()) {
      std::printf("  %.2f: no point\n", limit);
      continue;
    }
    std::printf("  %.2f: %s, mean RMSE %.4f, max |scale - 1| %.3f, %s RMSE %.4f\n", limit,
                describe(search[i].point).c_str(), search[i].meanRmse, search[i].maxScaleDeviation,
                o.scenes[0].c_str(), search[i].scenes[0].rmse);
  }
  for (const RadiusCheck& c : checks) {
    std::printf("calibrate: radius %g m: the r %g winner %s the scale tolerance there%s\n", c.radius, radius,
                c.winnerThere.maxScaleDeviation <= kCalibrationScaleTolerance ? "meets" : "misses",
                c.met ? "" : " (and no grid point meets it at this radius)");
    printPoint("defaults", o.scenes, c.defaultsThere);
    printPoint("r 1 winner", o.scenes, c.winnerThere);
    printPoint(c.met ? "own winner" : "own least max dev", o.scenes, c.ownWinner);
  }
  if (confirmed) {
    std::printf("calibrate: confirmation at %ux%u (median of %d timed runs):\n", o.confirmSize.width,
                o.confirmSize.height, o.runs);
    printPoint("before (defaults)", o.scenes, confirm[0]);
    printPoint("after (winner)", o.scenes, confirm[1]);
    if (confirm.size() > 2) printPoint("least mean RMSE", o.scenes, confirm[2]);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("calibrate: %.0f s in all; wrote %s\n", seconds, std::filesystem::path(path).filename().c_str());
  return Status::success();
}

}  // namespace sao::bench
