// Resolutions from 1x1 to 8K, the largest-side limit, repeated runs on one runner, and which
// backends the suite runs on.
// 8K (7680x4320) runs on the float CPU reference only, at reduced work (8 taps, no blur), and
// checks that the per-pixel rotation (eq. 8, an integer hash turned into 2^-32 turns) keeps full
// precision out to the far corner: no banding, the same statistics as near the origin, and the
// same A as a pixel near the origin whose rotation is the same.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

#include "stability_support.h"

extern char** environ;

namespace sao::stability {
namespace {

constexpr double kInf = INFINITY;
constexpr double k255 = 1.0 / 255.0;

TEST(Resolution, TinyAndOddSizesRun) {
  std::string measured;
  for (const auto& [w, h] : {std::pair{1u, 1u}, std::pair{2u, 2u}, std::pair{1u, 7u}, std::pair{3u, 2u}, std::pair{641u, 479u}})
    for (std::uint32_t g : {0u, 3u})
      for (bool reversed : {false, true}) {
        const Camera cam = reversed ? camera(w, h, 0.1, kInf, ClipDepth::ZeroToOne, true, g)
                                    : camera(w, h, 0.1, 1e4, ClipDepth::NegativeOneToOne, false, g);
        const test::Scene scene = test::sphereOnPlaneScene();
        const DepthImage depth = renderGpuDepth(scene, cam, reversed ? DepthFormat::D32F : DepthFormat::D24);
        const std::vector<bool> sky = skyMaskOf(scene, cam);
        CaseOptions o;
        o.skyMask = &sky;
        const CaseRuns r = runCase(fmt("%ux%u guard %u %s", w, h, g, describe(cam).c_str()), fullResolution(), cam,
                                   {&depth, nullptr, nullptr}, o);
        if (g == 0 && reversed && !r.runs.empty()) {
          const Range a = range(r.runs.front().out.ao);
          measured += fmt("%s%ux%u: A in [%.3f, %.3f]", measured.empty() ? "" : "; ", w, h, a.min, a.max);
        }
      }
  report("resolutions 1x1, 2x2, 1x7, 3x2, 641x479 (guard 0 and 3, D24 standard and D32F reversed, every backend)",
         "runs; A finite in [0,1]; sky = 1", measured);
}

TEST(Resolution, LargestSideIsEnforcedWithAClearError) {
  DepthImage depth;
  depth.format = DepthFormat::D32F;
  Camera cam = camera(16385, 1, 0.1, kInf, ClipDepth::ZeroToOne, true);
  depth.extent = {16385, 1};
  depth.texels.assign(16385, std::bit_cast<std::uint32_t>(0.5f));
  // The GL runner uploads before the effect validates: the texture upload fails first (finding F6).
  const std::string m1 = expectRejected("16385x1", fullResolution(), cam, {&depth, nullptr, nullptr}, StatusCode::InvalidExtent,
                                        /*gpuUploadMayFailFirst=*/true);
  cam = camera(16, 16, 0.1, kInf, ClipDepth::ZeroToOne, true, 0x80000000u);  // guard band 2^31: 64-bit sum
  depth.extent = {16, 16};
  depth.texels.assign(256, std::bit_cast<std::uint32_t>(0.5f));
  const std::string m2 = expectRejected("guard 2^31", fullResolution(), cam, {&depth, nullptr, nullptr}, StatusCode::InvalidExtent);
  report("largest side 16384: a 16385-wide viewport; a 2^31 guard band", "rejected with InvalidExtent",
         "'" + m1 + "'; '" + m2 + "'");
}

// ---- 8K

// Eq. 8 as docs/effect-math.md §5.4 specifies it: the phase of AO pixel (x, y) in 2^-32 turns.
std::uint32_t specPhase(std::uint32_t x, std::uint32_t y) {
  const std::uint32_t h = (3u * x) ^ (y + x * y);
  return (h * std::uint32_t(gen::SAO_PHASE_MUL)) << 1u;
}

// The same with the hash rounded to float first (what a naive float implementation computes).
std::uint32_t floatHashPhase(std::uint32_t x, std::uint32_t y) {
  const std::uint32_t h = std::uint32_t(float((3u * x) ^ (y + x * y)));
  return (h * std::uint32_t(gen::SAO_PHASE_MUL)) << 1u;
}

TEST(Resolution, EightKRotationKeepsFullPrecision) {
  // Orthographic view of a plane 1 m away with a checkerboard of 2 mm bumps (R32F linear z), 1 mm
  // pixels, radius 12 mm (r' = 12 px, all taps on csz level 0), bias 0, sigma*r = 0.05 m, no 2x2
  // averaging, no blur:
  // every pixel sees the same geometry up to the checkerboard parity, so A(p) is a function of the
  // parity and the rotation phi(p) alone. On "cpu" only (the issue allows the CPU reference here).
  const std::uint32_t W = 7680, H = 4320;
  Camera cam = orthoCamera(W, H, 0.1, 10.0, ClipDepth::ZeroToOne, false, 0, 0.5 * H * 1e-3);
  DepthImage depth;
  depth.extent = {W, H};
  depth.format = DepthFormat::LinearZ;
  depth.texels.resize(std::size_t(W) * H);
  const std::uint32_t lo = std::bit_cast<std::uint32_t>(-1.0f), hi = std::bit_cast<std::uint32_t>(-1.0f + 0.002f);
  for (std::uint32_t y = 0; y < H; ++y)
    for (std::uint32_t x = 0; x < W; ++x) depth.texels[std::size_t(y) * W + x] = ((x + y) & 1) ? hi : lo;
  Settings s = fullResolution();
  s.radius = 0.012f;
  s.bias = 0.0f;
  s.intensity = 0.05f / 0.012f;  // sigma*r = 0.05 m, the block's value from before sigma became unitless
  s.samples = 8;
  s.blur_radius = 0;
  s.quad_edge_threshold = 0.0f;
  CaseOptions o;
  o.only = {"cpu"};
  const auto t0 = std::chrono::steady_clock::now();
  const CaseRuns runs = runCase("8K checkerboard, orthographic", s, cam, {&depth, nullptr, nullptr}, o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(runs.runs.size(), 1u);
  const FloatImage& ao = runs.runs.front().out.ao;
  ASSERT_EQ(ao.extent, (Extent{W, H}));

  // (1) No bands. Row and column means, in standard errors of an independent-pixel mean. The
  // eq. 8 hash itself gives a few scattered rows and columns with resonant phase sequences (the
  // same at any resolution); banding from lost precision would instead (a) correlate neighbouring
  // rows or columns and (b) grow toward the far corner. So: lag-1 to lag-4 autocorrelations of the
  // row and column means stay small, and the far half's rms deviation is like the near half's.
  double sum = 0, sum2 = 0;
  for (float a : ao.data) sum += a, sum2 += double(a) * a;
  const double n = double(ao.data.size()), mean = sum / n, sd = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  ASSERT_GT(sd, 0.01) << "the test scene must make A depend on the rotation (mean " << mean << ")";
  std::vector<double> rowDev(H, 0.0), colDev(W, 0.0);
  for (std::uint32_t y = 0; y < H; ++y)
    for (std::uint32_t x = 0; x < W; ++x) {
      const double a = ao.data[std::size_t(y) * W + x];
      rowDev[y] += a;
      colDev[x] += a;
    }
  for (double& r : rowDev) r = (r / W - mean) / (sd / std::sqrt(double(W)));
  for (double& c : colDev) c = (c / H - mean) / (sd / std::sqrt(double(H)));
  auto autocorr = [](const std::vector<double>& v) {
    double worst = 0, var = 0;
    for (double x : v) var += x * x;
    for (std::size_t lag = 1; lag <= 4; ++lag) {
      double c = 0;
      for (std::size_t i = 0; i + lag < v.size(); ++i) c += v[i] * v[i + lag];
      worst = std::max(worst, std::fabs(c / var));
    }
    return worst;
  };
  auto rms = [](const std::vector<double>& v, std::size_t b, std::size_t e) {
    double s = 0;
    for (std::size_t i = b; i < e; ++i) s += v[i] * v[i];
    return std::sqrt(s / double(e - b));
  };
  const double acRow = autocorr(rowDev), acCol = autocorr(colDev);
  const double rowNear = rms(rowDev, 0, H / 2), rowFar = rms(rowDev, H / 2, H);
  const double colNear = rms(colDev, 0, W / 2), colFar = rms(colDev, W / 2, W);
  double worstRow = 0, worstCol = 0;
  for (double r : rowDev) worstRow = std::max(worstRow, std::fabs(r));
  for (double c : colDev) worstCol = std::max(worstCol, std::fabs(c));

  // (2) The far corner looks like the origin: mean, spread and histogram of a 256x256 block.
  auto blockStats = [&](std::uint32_t x0, std::uint32_t y0, std::vector<double>& hist) {
    hist.assign(64, 0.0);
    double m = 0, m2 = 0;
    for (std::uint32_t y = y0; y < y0 + 256; ++y)
      for (std::uint32_t x = x0; x < x0 + 256; ++x) {
        const double a = ao.data[std::size_t(y) * W + x];
        m += a, m2 += a * a;
        hist[std::min<std::size_t>(63, std::size_t(a * 64))] += 1.0 / 65536;
      }
    m /= 65536;
    return std::pair{m, std::sqrt(std::max(0.0, m2 / 65536 - m * m))};
  };
  std::vector<double> hO, hC;
  const auto [meanO, sdO] = blockStats(1, 1, hO);
  const auto [meanC, sdC] = blockStats(W - 256, H - 256, hC);
  double ks = 0, cO = 0, cC = 0;
  for (int i = 0; i < 64; ++i) cO += hO[i], cC += hC[i], ks = std::max(ks, std::fabs(cO - cC));

  // (3) Same rotation, same A: predict each far-corner pixel from the origin-block pixel of the same
  // parity whose specified phase is nearest, and compare with a block next to the origin
  // predicted the same way (the baseline of the method: phases never match exactly).
  struct Entry {
    std::uint32_t phase;
    float a;
  };
  std::vector<Entry> table[2];
  for (std::uint32_t y = 1; y < 257; ++y)
    for (std::uint32_t x = 1; x < 257; ++x) table[(x + y) & 1].push_back({specPhase(x, y), ao.at(x, y)});
  for (auto& t : table) std::sort(t.begin(), t.end(), [](const Entry& a, const Entry& b) { return a.phase < b.phase; });
  auto mismatch = [&](std::uint32_t x0, std::uint32_t y0, std::uint32_t (*phaseOf)(std::uint32_t, std::uint32_t)) {
    std::size_t bad = 0, total = 0;
    for (std::uint32_t y = y0; y < y0 + 256; ++y)
      for (std::uint32_t x = x0; x < x0 + 256; ++x) {
        const auto& t = table[(x + y) & 1];
        const std::uint32_t ph = phaseOf(x, y);
        auto it = std::lower_bound(t.begin(), t.end(), ph, [](const Entry& e, std::uint32_t p) { return e.phase < p; });
        const Entry& a = it == t.end() ? t.front() : *it;                 // wraps around
        const Entry& b = it == t.begin() ? t.back() : *(it - 1);
        const Entry& best = std::uint32_t(a.phase - ph) < std::uint32_t(ph - b.phase) ? a : b;
        bad += std::fabs(double(best.a) - ao.at(x, y)) > k255;
        ++total;
      }
    return double(bad) / double(total);
  };
  const double missNear = mismatch(300, 300, specPhase), missCorner = mismatch(W - 256, H - 256, specPhase);
  // The check's power: had the effect turned the hash into a float first (the Stride PR #1168
  // mistake), its corner pixels would follow floatHashPhase, and predicting them with the exact
  // phase would miss about as often as this does.
  const double missFloatHash = mismatch(W - 256, H - 256, floatHashPhase);
  EXPECT_GE(missFloatHash, 3 * missCorner) << "the phase check would not notice a float hash";

  EXPECT_LE(acRow, 0.1) << "neighbouring row means are correlated: bands";
  EXPECT_LE(acCol, 0.1) << "neighbouring column means are correlated: bands";
  EXPECT_LE(rowFar, 1.5 * rowNear + 0.5) << "row means scatter more in the far half";
  EXPECT_LE(colFar, 1.5 * colNear + 0.5) << "column means scatter more in the far half";
  EXPECT_LE(std::fabs(meanC - meanO), 0.01);
  EXPECT_LE(std::fabs(sdC - sdO), 0.01);
  EXPECT_LE(ks, 0.03);
  EXPECT_LE(missCorner, missNear * 1.5 + 0.01) << "the far corner's A does not follow the specified rotation";
  report("8K (7680x4320, cpu, orthographic checkerboard, 8 taps, no blur): per-pixel rotation",
         "row/column means: lag 1-4 autocorrelation <= 0.1, far-half rms <= 1.5x near-half + 0.5 (in standard errors); "
         "corner vs origin block: |dmean|, |dsd| <= 0.01, KS <= 0.03; nearest-phase prediction misses at the corner "
         "<= 1.5x those near the origin + 1%",
         fmt("A mean %.4f sd %.4f; row means: autocorr %.3f, rms near/far %.2f/%.2f (worst %.1f); column means: autocorr "
             "%.3f, rms near/far %.2f/%.2f (worst %.1f); origin block mean %.4f sd %.4f, corner %.4f / %.4f, KS %.4f; "
             "phase-prediction misses %.2f%% near the origin, %.2f%% at the corner (%.1f%% against a float-hash phase); "
             "run %.1f s",
             mean, sd, acRow, rowNear, rowFar, worstRow, acCol, colNear, colFar, worstCol, meanO, sdO, meanC, sdC, ks,
             100 * missNear, 100 * missCorner, 100 * missFloatHash, seconds));
}

// ---- The backends the suite runs on

TEST(Backends, EveryBuiltBackendStartsUnlessExcluded) {
  // A built backend that cannot start fails the suite (here and in every test that asks for it):
  // otherwise a broken GL or Vulkan would pass on the CPU alone, and the GL = Vulkan check would
  // never run. Only SAO_STABILITY_BACKENDS or SAO_STABILITY_ALLOW_MISSING_BACKENDS=1 skip it.
  if (const char* only = std::getenv("SAO_STABILITY_BACKENDS")) {
    // A misspelt name would exclude the backend it was meant to name.
    std::string list = only;
    for (std::size_t start = 0; start <= list.size();) {
      const std::size_t end = std::min(list.find(',', start), list.size());
      const std::string item = list.substr(start, end - start);
      EXPECT_NE(std::find(kBackendNames.begin(), kBackendNames.end(), item), kBackendNames.end())
          << "SAO_STABILITY_BACKENDS names an unknown backend '" << item << "' (expected cpu-double, cpu, gl, vulkan)";
      start = end + 1;
    }
  }
  std::string measured;
  std::size_t started = 0;
  for (std::string_view name : kBackendNames) {
    std::string reason;
    const BackendState st = backendState(name, &reason);  // a Failed backend has added its failure
    started += st == BackendState::Started;
    const char* what = st == BackendState::Started         ? "started"
                       : st == BackendState::Excluded      ? "excluded"
                       : st == BackendState::NotBuilt      ? "not built"
                       : st == BackendState::FailedAllowed ? "failed to start, allowed"
                                                           : "FAILED to start";
    measured += fmt("%s%.*s: %s (%s)", measured.empty() ? "" : "; ", int(name.size()), name.data(), what, reason.c_str());
  }
  EXPECT_GT(started, 0u) << "no backend ran: every case would pass vacuously";
  report("backends", "every built backend starts unless excluded (SAO_STABILITY_BACKENDS) or allowed to be missing",
         measured);
}

// A runner of its own for `name`; Vulkan's under the validation layers (SAO_VK_VALIDATION=1 while
// it is created), so that a message fails the run.
std::unique_ptr<samples::BackendRunner> validatedRunner(std::string_view name) {
  const char* before = std::getenv("SAO_VK_VALIDATION");
  const std::string saved = before ? before : "";
  setenv("SAO_VK_VALIDATION", "1", 1);
  std::unique_ptr<samples::BackendRunner> runner;
  const Status s = samples::createBackend(name, runner);
  if (before) setenv("SAO_VK_VALIDATION", saved.c_str(), 1);
  else unsetenv("SAO_VK_VALIDATION");
  EXPECT_TRUE(s.ok()) << name << ": " << s.message;
  return s.ok() ? std::move(runner) : nullptr;
}

// ---- A runner's inputs changed in place between runs
// The GL runner keeps its input textures across runs while the images stay the same (so that a
// run's timers do not hold the upload): an image changed in place, at the same address, must
// still be uploaded again. Depth and supplied normals, on every backend: the run after a change
// equals a fresh runner's run of the changed inputs, and changing them back gives the first output.
TEST(Backends, InputsChangedInPlaceAreSeen) {
  const Camera cam = camera(64, 48, 0.1, kInf, ClipDepth::ZeroToOne, true);
  const DepthImage sphere = renderGpuDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
  const DepthImage plane = renderGpuDepth(test::planeScene(2.0), cam, DepthFormat::D32F);
  FloatImage up(sphere.extent, 4), tilted(sphere.extent, 4);
  for (std::size_t i = 0; i < up.data.size(); i += 4) {
    up.data[i + 2] = 1.0f;                                   // (0, 0, 1): facing the camera
    tilted.data[i + 1] = 0.6f, tilted.data[i + 2] = 0.8f;  // tilted up
  }
  std::string measured;
  for (std::string_view name : kBackendNames) {
    if (!backend(name)) continue;
    std::unique_ptr<samples::BackendRunner> runner = validatedRunner(name), fresh = validatedRunner(name);
    ASSERT_TRUE(runner && fresh) << name;
    DepthImage depth = sphere;
    FloatImage normals = up;
    auto run = [&](samples::BackendRunner& r, bool withNormals) {
      samples::RunOutputs out;
      const Status s = r.run(fullResolution(), cam, {&depth, withNormals ? &normals : nullptr, nullptr}, false, false, out);
      EXPECT_TRUE(s.ok()) << name << ": " << s.message;
      return out.ao;
    };
    const FloatImage first = run(*runner, true);
    depth = plane;  // in place: the same object the runner was given
    const FloatImage changedDepth = run(*runner, true), freshDepth = run(*fresh, true);
    normals = tilted;
    const FloatImage changedNormals = run(*runner, true), freshNormals = run(*fresh, true);
    depth = sphere, normals = up;
    const FloatImage back = run(*runner, true);
    EXPECT_GT(maxAbsDiff(first, changedDepth), 0.05) << name << ": the new depth changed nothing";
    EXPECT_EQ(maxAbsDiff(changedDepth, freshDepth), 0.0) << name << ": a depth changed in place was not seen";
    EXPECT_GT(maxAbsDiff(changedDepth, changedNormals), 0.05) << name << ": the new normals changed nothing";
    EXPECT_EQ(maxAbsDiff(changedNormals, freshNormals), 0.0) << name << ": normals changed in place were not seen";
    EXPECT_EQ(maxAbsDiff(first, back), 0.0) << name << ": the first inputs again gave another result";
    measured += fmt("%s%.*s: depth change %.3f, normals change %.3f", measured.empty() ? "" : "; ", int(name.size()),
                    name.data(), maxAbsDiff(first, changedDepth), maxAbsDiff(changedDepth, changedNormals));
  }
  report("inputs changed in place between runs (depth, normals; every backend)",
         "seen: equal to a fresh runner's run, and the first inputs again give the first output", measured);
}

// ---- keepBusy (sao-bench --warmup-ms): renders without read-back between two runs
// It must leave the runner as it found it: the run after it gives the run before it's output, on
// every backend (the Vulkan one under the validation layers), with and
// without timing, and with normals, which the GL runner keeps.
TEST(Backends, KeepBusyLeavesTheNextRunAlike) {
  const Camera cam = camera(64, 48, 0.1, kInf, ClipDepth::ZeroToOne, true);
  const DepthImage depth = renderGpuDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
  FloatImage normals(depth.extent, 4);
  for (std::size_t i = 0; i < normals.data.size(); i += 4) normals.data[i + 2] = 1.0f;
  std::string measured;
  for (std::string_view name : kBackendNames) {
    if (!backend(name)) continue;
    std::unique_ptr<samples::BackendRunner> runner = validatedRunner(name);
    ASSERT_TRUE(runner) << name;
    for (const samples::RunInputs& in : {samples::RunInputs{&depth, nullptr, nullptr}, samples::RunInputs{&depth, &normals, nullptr}})
      for (bool timed : {false, true}) {
        samples::RunOutputs before, after;
        ASSERT_TRUE(runner->run(fullResolution(), cam, in, timed, false, before).ok()) << name;
        const auto start = std::chrono::steady_clock::now();
        const Status busy = runner->keepBusy(fullResolution(), cam, in, 30.0);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        ASSERT_TRUE(busy.ok()) << name << ": " << busy.message;
        ASSERT_TRUE(runner->run(fullResolution(), cam, in, timed, false, after).ok()) << name;
        EXPECT_EQ(maxAbsDiff(before.ao, after.ao), 0.0) << name << (in.normals ? " with normals" : "") << (timed ? ", timed" : "");
        if (name == "gl" || name == "vulkan") { EXPECT_GE(ms, 30.0) << name << ": keepBusy returned before its time"; }
        if (!in.normals && !timed) measured += fmt("%s%.*s: %.0f ms", measured.empty() ? "" : "; ", int(name.size()), name.data(), ms);
      }
  }
  report("keepBusy between two runs (every backend; timed or not, normals or not)",
         "the next run's output equals the previous one's; the GPU backends render for the time asked", measured);
}

// ---- Repeated runs on one runner (finding F5, fixed upstream in 6f366b2)

TEST(Backends, RepeatedRunsReuseOneRunner) {
  // Six runs of the same case on one runner (the way an application renders frame after frame,
  // re-creating its depth image in between). At c3d23cd the Vulkan backend crashed on the third
  // (descriptor sets cached per ring slot by VkImageView handle value, and lavapipe reuses the
  // handle of the destroyed view); 6f366b2 rewrites the sets on every record. Each backend runs in a child process of its own, so
  // that a crash is reported as a failure of this test instead of taking the suite down.
  if (const char* child = std::getenv("SAO_STABILITY_CHILD_BACKEND")) {
    std::unique_ptr<samples::BackendRunner> runner;
    if (!samples::createBackend(child, runner).ok()) std::_Exit(4);  // the parent started it: this is a failure
    // The configuration that first showed the crash: a plane, GL standard depth, far 1e4.
    const Camera cam = camera(40, 30, 0.1, 1e4, ClipDepth::NegativeOneToOne, false, 2);
    DepthImage depth = renderGpuDepth(test::planeScene(2.0), cam, DepthFormat::D32F);
    for (auto& t : depth.texels) t = std::bit_cast<std::uint32_t>(0.5f);
    FloatImage first;
    for (int i = 0; i < 6; ++i) {
      samples::RunOutputs out;
      if (!runner->run(fullResolution(), cam, {&depth, nullptr, nullptr}, false, false, out).ok()) std::_Exit(2);
      if (i == 0) first = out.ao;
      else if (maxAbsDiff(first, out.ao) != 0.0) std::_Exit(3);
    }
    std::_Exit(0);
  }
  std::string measured;
  for (std::string_view name : kBackendNames) {
    if (!backend(name)) continue;
    const std::string var = "SAO_STABILITY_CHILD_BACKEND=" + std::string(name);
    std::vector<char*> env;
    for (char** e = environ; *e; ++e) env.push_back(*e);
    env.push_back(const_cast<char*>(var.c_str()));
    env.push_back(nullptr);
    std::string filter = "--gtest_filter=Backends.RepeatedRunsReuseOneRunner";
    char exe[] = "/proc/self/exe";
    char* argv[] = {exe, filter.data(), nullptr};
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, exe, nullptr, nullptr, argv, env.data()), 0);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    std::string outcome;
    if (WIFEXITED(status)) {
      const int rc = WEXITSTATUS(status);
      outcome = rc == 0   ? "6 identical runs"
                : rc == 2 ? "a run failed"
                : rc == 3 ? "runs differ"
                : rc == 4 ? "did not start in the child"
                          : fmt("exit %d", rc);
      EXPECT_EQ(rc, 0) << name << ": " << outcome;
    } else {
      outcome = fmt("killed by signal %d", WIFSIGNALED(status) ? WTERMSIG(status) : -1);
      ADD_FAILURE() << name << ": " << outcome << " (see finding F5 in docs/STABILITY.md)";
    }
    measured += fmt("%s%.*s: %s", measured.empty() ? "" : "; ", int(name.size()), name.data(), outcome.c_str());
  }
  report("six runs on one runner (depth image re-created per run)", "no crash; identical AO", measured);
}

}  // namespace
}  // namespace sao::stability
