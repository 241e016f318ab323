#include "per_tap_section.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "sao/constants.h"
#include "sao/presets.h"

#ifdef SAO_BENCH_HAVE_GL
#include "per_tap_ladder.h"
#endif

namespace sao::bench {

#ifdef SAO_BENCH_HAVE_GL
namespace {

// One variant at one sample count.
struct Point {
  double median = NAN, min = NAN, max = NAN;  // ms
  double meanA = NAN;                         // over the geometry
};

struct Series {
  std::string variant, label;
  std::map<int, Point> at{};            // by sample count
  std::map<int, Point> atGpu{};         // the ladder's GL_TIME_ELAPSED times, where the query saw the work
  double slope = NAN, intercept = NAN;  // ms per tap, ms
  TimingMethod method = TimingMethod::None;  // how its times were taken
};

Point summarize(std::vector<double> ms) {
  Point p;
  if (ms.empty()) return p;
  std::sort(ms.begin(), ms.end());
  const std::size_t n = ms.size();
  p.median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  p.min = ms.front();
  p.max = ms.back();
  return p;
}

// Least squares of the median time against s.
void fit(Series& s) {
  double n = 0, ms = 0, mt = 0;
  for (const auto& [samples, p] : s.at) n += 1, ms += samples, mt += p.median;
  if (n < 2) return;
  ms /= n, mt /= n;
  double sst = 0, ss = 0;
  for (const auto& [samples, p] : s.at) sst += (samples - ms) * (p.median - mt), ss += (samples - ms) * (samples - ms);
  s.slope = sst / ss;
  s.intercept = mt - s.slope * ms;
}

// What a rung's output says about its shader over the geometry (csz level-0 z < 0 at p + guard).
struct Check {
  double meanA = NAN;
  bool nan = false, allZero = true, allOne = true;
  std::size_t pixels = 0;
};

Check check(const FloatImage& ao, const FloatImage& csz0, gen::Int2 guard) {
  Check c;
  double sum = 0;
  for (std::uint32_t y = 0; y < ao.extent.height; ++y)
    for (std::uint32_t x = 0; x < ao.extent.width; ++x) {
      const float a = ao.at(x, y);
      if (std::isnan(a)) c.nan = true;
      if (!(csz0.at(x + std::uint32_t(guard.x), y + std::uint32_t(guard.y)) < 0.0f)) continue;
      c.allZero = c.allZero && a == 0.0f;
      c.allOne = c.allOne && a == 1.0f;
      sum += a;
      ++c.pixels;
    }
  c.meanA = c.pixels ? sum / double(c.pixels) : NAN;
  return c;
}

void progress(int s, const std::string& what) {
  std::fprintf(stderr, "\r\033[Kper_tap: s=%d %s", s, what.c_str());
  std::fflush(stderr);
}

Status writeCsv(const std::string& path, const std::vector<Series>& series, Extent size, int runs) {
  std::ofstream csv(path);
  if (!csv) return Status::error(StatusCode::IoError, "cannot write " + path);
  csv << "variant,samples,width,height,runs,median_ms,min_ms,max_ms,mean_a,label,timing_method\n";
  for (const Series& s : series)
    for (const auto& [samples, p] : s.at)
      csv << s.variant << ',' << samples << ',' << size.width << ',' << size.height << ',' << runs << ',' << p.median
          << ',' << p.min << ',' << p.max << ',' << p.meanA << ",\"" << s.label << "\","  // labels hold commas
          << toString(s.method) << "\n";
  if (!csv.flush()) return Status::error(StatusCode::IoError, "cannot write " + path);
  return Status::success();
}

void printSummary(const std::vector<Series>& series, const PerTapOptions& o, const std::string& machine) {
  const double pixels = double(o.size.width) * o.size.height;
  auto find = [&](const std::string& variant) -> const Series& {
    for (const Series& s : series)
      if (s.variant == variant) return s;
    return series.front();
  };
  const Series &a = find("a_fragment"), &b = find("b_compute"), &e = find("e_compute_rebuilt_n");
  std::printf(
      "per_tap: time per tap of ao_sample and of minimal passes, %s at %ux%u, median of %d runs (per_tap.csv)\n"
      "  on %s\n",
      o.scene.c_str(), o.size.width, o.size.height, o.runs, machine.c_str());
  std::printf("  %-46s %10s %9s %8s", "variant", "ns/px/tap", "fixed ms", "x (a)");
  for (int s : o.sampleCounts) std::printf(" %9s", ("s=" + std::to_string(s) + " ms").c_str());
  std::printf("\n");
  for (const Series& s : series) {
    std::printf("  %-46s %10.3f %9.2f %7.2fx", s.label.c_str(), s.slope * 1e6 / pixels, s.intercept, s.slope / a.slope);
    for (int n : o.sampleCounts) std::printf(" %9.2f", s.at.count(n) ? s.at.at(n).median : NAN);
    std::printf("\n");
  }
  const Series &read = find("ours_normals"), &rebuilt = find("ours_rebuilt");
  std::printf(
      "  ao_sample's time per tap: normals read %.2fx (a), %.2fx (b); normals rebuilt %.2fx (a), %.2fx (b), "
      "%.2fx (e)\n",
      read.slope / a.slope, read.slope / b.slope, rebuilt.slope / a.slope, rebuilt.slope / b.slope,
      rebuilt.slope / e.slope);
  const int first = o.sampleCounts.front();
  auto at = [first](const Series& s) { return s.at.count(first) ? s.at.at(first).median : NAN; };
  std::printf(
      "  ao_sample at s=%d over (a) at s=%d (the issue's 2.2-3.3x): normals read %.2fx, normals rebuilt %.2fx\n", first,
      first, at(read) / at(a), at(rebuilt) / at(a));
  std::printf("  mean A over the geometry (plausibility, not bit-exact):\n  %6s %14s %14s %8s %8s %8s\n", "s",
              "ao_sample read", "ao_sample rebuilt", "(b)", "(c)", "(e)");
  const Series& c = find("c_compute_2x2");
  for (int n : o.sampleCounts) {
    auto mean = [n](const Series& s) { return s.at.count(n) ? s.at.at(n).meanA : NAN; };
    std::printf("  %6d %14.4f %17.4f %8.4f %8.4f %8.4f\n", n, mean(read), mean(rebuilt), mean(b), mean(c), mean(e));
  }
}

}  // namespace
#endif

Status perTapSection(const PerTapOptions& o, samples::BackendRunner* gl, SceneCache& cache) {
#ifndef SAO_BENCH_HAVE_GL
  (void)o, (void)gl, (void)cache;
  std::printf("per_tap: skipped: the gl backend is not built into this sao-bench (SAO_BUILD_GL=OFF)\n");
  return Status::success();
#else
  std::unique_ptr<samples::BackendRunner> own;
  if (!gl) {
    if (!samples::isBackendBuiltIn("gl")) {
      std::printf("per_tap: skipped: the gl backend is not built into this sao-bench\n");
      return Status::success();
    }
    if (Status s = samples::createBackend("gl", own); !s) {
      std::printf("per_tap: skipped: the gl backend does not start: %s\n", s.message.c_str());
      return Status::success();
    }
    gl = own.get();
  }
  if (o.sampleCounts.size() < 2) return Status::error(StatusCode::InvalidInput, "needs at least two sample counts");
  Prepared& p = cache.prepare(o.scene, o.size.width, o.size.height);
  Settings base = presetSettings(Preset::Medium);
  base.blur_radius = 0;  // the sampling alone matters: no blur, full resolution, so the one pass after
  base.resolution_divisor = 1;  // linear_z is ao_sample_output (ao_sample storing A into the output)

  // The effect's own csz chain, so that the rungs read exactly its z.
  samples::RunOutputs dump;
  if (Status s = gl->run(base, p.camera, runInputs(p, Extra::None), false, true, dump); !s) return s;
  std::vector<FloatImage> csz;
  for (std::uint32_t m = 0;; ++m) {
    auto it = std::find_if(dump.intermediates.begin(), dump.intermediates.end(),
                           [m](const auto& i) { return i.first == "csz_level" + std::to_string(m); });
    if (it == dump.intermediates.end()) break;
    csz.push_back(std::move(it->second));
  }
  if (csz.empty()) return Status::error(StatusCode::DriverError, "the gl backend dumped no csz_level0");
  std::unique_ptr<PerTapLadder> ladder;
  if (Status s = PerTapLadder::create(csz, p.primary.normal, o.size, ladder); !s) return s;

  std::vector<Series> series;
  for (const LadderStep& step : ladderSteps()) series.push_back({step.name, step.label, {}});
  series.push_back({"ours_normals", "ao_sample, normals read (medium, no blur)", {}});
  series.push_back({"ours_rebuilt", "ao_sample, normals rebuilt (medium, no blur)", {}});
  std::vector<std::string> broken;
  TimingMethod method = TimingMethod::None;
  bool ladderGpuSees = true;  // every rung's GL_TIME_ELAPSED saw its work, at every s
  // Every variant at one s before the next s: the ratios come from the same minute of a noisy machine.
  for (int s : o.sampleCounts) {
    Settings set = base;
    set.samples = s;
    ParamBlock block;
    if (Status st = computeConstants(set, p.camera, DepthEncoding::Hardware, block); !st) return st;
    if (block.ortho)
      return Status::error(StatusCode::InvalidCamera, "the minimal passes take a perspective camera (drop --ortho)");
    block.max_mip = std::min(block.max_mip, std::int32_t(csz.size()) - 1);
    for (std::size_t k = 0; k < ladderSteps().size(); ++k) {
      const LadderStep& step = ladderSteps()[k];
      progress(s, step.label);
      std::vector<double> ms, gpuMs;
      FloatImage ao;
      if (Status st = ladder->measure(step, block, o.runs, ms, gpuMs, ao); !st) return st;
      ladderGpuSees = ladderGpuSees && !gpuMs.empty();
      const Check c = check(ao, csz[0], block.guard);
      if (c.nan || (c.pixels && (c.allZero || c.allOne)))
        broken.push_back(std::string(step.name) + " at s=" + std::to_string(s) +
                         (c.nan       ? ": NaN"
                          : c.allZero ? ": all 0"
                                      : ": all 1"));
      series[k].at[s] = summarize(ms);
      series[k].at[s].meanA = c.meanA;
      if (!gpuMs.empty()) series[k].atGpu[s] = summarize(gpuMs);
    }
    for (const Extra extra : {Extra::Normals, Extra::None}) {
      Series& out = series[ladderSteps().size() + (extra == Extra::None ? 1 : 0)];
      progress(s, out.label);
      std::vector<double> ms;
      for (int r = -1; r < o.runs; ++r) {  // one warm-up
        samples::RunOutputs run;
        if (Status st = gl->run(set, p.camera, runInputs(p, extra), true, false, run); !st) return st;
        method = out.method = run.timings.method;
        const auto pass = std::find_if(run.timings.passes.begin(), run.timings.passes.end(),
                                       [](const PassTiming& t) { return t.pass == "ao_sample_output"; });
        if (pass == run.timings.passes.end())
          return Status::error(StatusCode::DriverError, "the gl backend timed no ao_sample_output");
        if (r < 0) continue;
        ms.push_back(pass->milliseconds);
        if (r == o.runs - 1) out.at[s].meanA = check(run.ao, csz[0], block.guard).meanA;
      }
      const double meanA = out.at[s].meanA;
      out.at[s] = summarize(ms);
      out.at[s].meanA = meanA;
    }
  }
  std::fprintf(stderr, "\n");
  // One method for the whole ladder, as the effect's timer decides for all its passes: the queries
  // where every rung's saw its work (a GPU, where glFinish and a clock time the synchronisation
  // more than the pass), else the clock (llvmpipe's query sees compute work as 1 ns, and a draw as
  // its binning only).
  for (std::size_t k = 0; k < ladderSteps().size(); ++k) {
    Series& ladderSeries = series[k];
    ladderSeries.method = ladderGpuSees ? TimingMethod::GpuTimestamps : TimingMethod::FinishAndClock;
    if (ladderGpuSees)
      for (auto& [count, point] : ladderSeries.at) {
        const double meanA = point.meanA;
        point = ladderSeries.atGpu.at(count);
        point.meanA = meanA;
      }
  }
  for (Series& s : series) fit(s);

  const std::string path = (std::filesystem::path(o.outDir) / "per_tap.csv").string();
  if (Status st = writeCsv(path, series, o.size, o.runs); !st) return st;
  printSummary(series, o,
               gl->description() + "; ao_sample timed by " + toString(method) + ", the rungs by glFinish + clock");
  if (!broken.empty()) {
    std::string list;
    for (const std::string& b : broken) list += (list.empty() ? "" : "; ") + b;
    return Status::error(StatusCode::DriverError,
                         "a minimal pass gave an implausible output (a broken shader): " + list);
  }
  return Status::success();
#endif
}

}  // namespace sao::bench
