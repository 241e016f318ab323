#include "stability_support.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>

namespace sao::stability {
namespace {

struct Slot {
  std::unique_ptr<samples::BackendRunner> runner;
  bool tried = false;
  BackendState state = BackendState::Started;
  std::string reason;          // why it did not start (or its description when it did)
  std::string lastFailedTest;  // a backend that failed to start fails each test that asks for it once
};

std::map<std::string, Slot, std::less<>>& slots() {
  static std::map<std::string, Slot, std::less<>> s;
  return s;
}

bool wanted(const CaseOptions& o, std::string_view name) {
  return o.only.empty() || std::find(o.only.begin(), o.only.end(), name) != o.only.end();
}

double P(const Camera& c, int row, int col) { return c.projection[std::size_t(col) * 4 + std::size_t(row)]; }

constexpr double kU = 0x1p-24;  // unit roundoff of binary32

// The largest cross-backend differences seen by runCase in this process, printed at exit.
struct Worst {
  double value = -1;
  std::string where;
  void note(double v, const std::string& label) {
    if (v > value) value = v, where = label;
  }
};
Worst worstGlVk, worstGpuCpu, worstCpuDouble;
std::size_t caseCount = 0;

class Summary : public ::testing::Environment {
 public:
  void TearDown() override {
    if (!caseCount) return;
    auto line = [](const char* what, const Worst& w) {
      if (w.value < 0)
        std::printf("[stability] summary: %s: not run\n", what);
      else
        std::printf("[stability] summary: %s: max %.3g (%s)\n", what, w.value, w.where.c_str());
    };
    std::printf("[stability] summary: %zu cases through runCase\n", caseCount);
    line("|gl - vulkan| (bound 1/255)", worstGlVk);
    line("|gpu - cpu|", worstGpuCpu);
    line("|cpu - cpu-double| (the float path's own error, all cases)", worstCpuDouble);
  }
};
const bool kSummaryRegistered = (::testing::AddGlobalTestEnvironment(new Summary), true);

bool allowMissingBackends() {
  const char* v = std::getenv("SAO_STABILITY_ALLOW_MISSING_BACKENDS");
  return v && std::string_view(v) == "1";
}

}  // namespace

samples::BackendRunner* backend(std::string_view name) {
  Slot& slot = slots()[std::string(name)];
  const std::string shown(name);
  if (!slot.tried) {
    slot.tried = true;
    // SAO_STABILITY_BACKENDS=cpu,gl restricts the suite to those backends (for diagnosis).
    if (const char* only = std::getenv("SAO_STABILITY_BACKENDS")) {
      const std::string list = std::string(",") + only + ",";
      if (list.find("," + shown + ",") == std::string::npos) {
        slot.state = BackendState::Excluded;
        slot.reason = "not in SAO_STABILITY_BACKENDS";
        std::printf("[stability] backend '%s' skipped: %s\n", shown.c_str(), slot.reason.c_str());
        return nullptr;
      }
    }
    // A backend this build left out (SAO_BUILD_GL / SAO_BUILD_VULKAN off) is not a failure.
    if (!samples::isBackendBuiltIn(name)) {
      slot.state = BackendState::NotBuilt;
      slot.reason = "not built into this program";
      std::printf("[stability] backend '%s' skipped: %s\n", shown.c_str(), slot.reason.c_str());
      return nullptr;
    }
    const Status st = samples::createBackend(name, slot.runner);
    if (!st) {
      slot.runner.reset();
      slot.reason = st.message + " (" + toString(st.code) + ")";
      slot.state = allowMissingBackends() ? BackendState::FailedAllowed : BackendState::Failed;
      std::printf("[stability] backend '%s' failed to start: %s%s\n", shown.c_str(), slot.reason.c_str(),
                  slot.state == BackendState::FailedAllowed ? "; skipped (SAO_STABILITY_ALLOW_MISSING_BACKENDS=1)" : "");
    } else {
      slot.state = BackendState::Started;
      slot.reason = slot.runner->description();
      std::printf("[stability] backend '%s': %s\n", shown.c_str(), slot.reason.c_str());
    }
  }
  // Otherwise a broken GL or Vulkan would leave the suite passing on the CPU alone.
  if (slot.state == BackendState::Failed) {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string test = info ? std::string(info->test_suite_name()) + "." + info->name() : std::string();
    if (test.empty() || test != slot.lastFailedTest) {
      slot.lastFailedTest = test;
      ADD_FAILURE() << "backend '" << shown << "' failed to start: " << slot.reason
                    << ". Exclude it with SAO_STABILITY_BACKENDS or set SAO_STABILITY_ALLOW_MISSING_BACKENDS=1 to skip it.";
    }
  }
  return slot.runner.get();
}

BackendState backendState(std::string_view name, std::string* reason) {
  backend(name);
  const Slot& slot = slots().find(name)->second;
  if (reason) *reason = slot.reason;
  return slot.state;
}

const FloatImage* BackendRun::intermediate(std::string_view passName) const {
  for (const auto& [n, img] : out.intermediates)
    if (n == passName) return &img;
  return nullptr;
}

const BackendRun* CaseRuns::find(std::string_view name) const {
  for (const BackendRun& r : runs)
    if (r.name == name) return &r;
  return nullptr;
}

bool allFinite(const FloatImage& img) {
  for (float v : img.data)
    if (!std::isfinite(v)) return false;
  return true;
}

Range range(const FloatImage& img, const std::vector<bool>* mask, std::uint32_t channel) {
  Range r;
  r.min = INFINITY;
  r.max = -INFINITY;
  double sum = 0;
  const std::size_t n = std::size_t(img.extent.width) * img.extent.height;
  for (std::size_t i = 0; i < n; ++i) {
    if (mask && !(*mask)[i]) continue;
    const double v = img.data[i * img.channels + channel];
    r.min = std::min(r.min, v);
    r.max = std::max(r.max, v);
    sum += v;
    ++r.count;
  }
  r.mean = r.count ? sum / double(r.count) : 0.0;
  if (!r.count) r.min = r.max = 0;
  return r;
}

double maxAbsDiff(const FloatImage& a, const FloatImage& b, const std::vector<bool>* mask) {
  if (a.extent != b.extent || a.channels != b.channels) return INFINITY;
  double worst = 0;
  const std::size_t n = std::size_t(a.extent.width) * a.extent.height;
  for (std::size_t i = 0; i < n; ++i) {
    if (mask && !(*mask)[i]) continue;
    for (std::uint32_t c = 0; c < a.channels; ++c) {
      const double d = std::fabs(double(a.data[i * a.channels + c]) - double(b.data[i * a.channels + c]));
      if (!(d <= worst)) worst = d;  // NaN propagates as "worse"
    }
  }
  return worst;
}

CaseRuns runCase(const std::string& label, const Settings& settings, const Camera& cam,
                 const samples::RunInputs& inputs, const CaseOptions& options) {
  CaseRuns result;
  result.label = label;
  for (std::string_view name : kBackendNames) {
    if (!wanted(options, name)) continue;
    samples::BackendRunner* runner = backend(name);
    if (!runner) continue;  // logged skip (printed once in backend())
    BackendRun run;
    run.name = std::string(name);
    const Status st = runner->run(settings, cam, inputs, false, options.dumpPasses, run.out);
    if (!st && options.gpuMayRejectInput && (name == "gl" || name == "vulkan") && st.code == StatusCode::InvalidInput) {
      static int printed = 0;
      if (printed++ < 8)
        std::printf("[stability] %s: %.*s cannot hold this input (%s): skipped there%s\n", label.c_str(), int(name.size()),
                    name.data(), st.message.c_str(), printed == 8 ? " (further such skips not printed)" : "");
      continue;
    }
    EXPECT_TRUE(st.ok()) << label << " on " << name << ": " << st.message;
    if (!st) continue;
    const FloatImage& ao = run.out.ao;
    EXPECT_EQ(ao.extent, (Extent{cam.width, cam.height})) << label << " on " << name;
    EXPECT_EQ(ao.channels, 1u) << label << " on " << name;
    EXPECT_TRUE(allFinite(ao)) << label << " on " << name << ": the AO holds NaN or Inf";
    const Range r = range(ao);
    EXPECT_GE(r.min, 0.0) << label << " on " << name;
    EXPECT_LE(r.max, 1.0) << label << " on " << name;
    if (options.skyMask && options.skyMask->size() == ao.data.size()) {
      std::size_t bad = 0, first = 0;
      for (std::size_t i = 0; i < ao.data.size(); ++i)
        if ((*options.skyMask)[i] && ao.data[i] != 1.0f && bad++ == 0) first = i;
      EXPECT_EQ(bad, 0u) << label << " on " << name << ": sky pixels with A != 1, first at " << first % ao.extent.width
                         << "," << first / ao.extent.width << " A = " << ao.data[first];
    }
    result.runs.push_back(std::move(run));
  }
  // Cross-backend: GL and Vulkan must agree to the Vulkan bound; GPU vs the float reference is
  // printed (it is the number the backend tests hold to bits).
  const BackendRun* gl = result.find("gl");
  const BackendRun* vk = result.find("vulkan");
  ++caseCount;
  const bool summarise = !options.excludeFromSummary;
  if (options.compareGpus && gl && vk) {
    const double d = maxAbsDiff(gl->out.ao, vk->out.ao);
    EXPECT_LE(d, kGpuAgreement) << label << ": GL and Vulkan AO differ by " << d;
    if (summarise) worstGlVk.note(d, label);
    if (d > 0) std::printf("[stability] %s: |gl - vulkan| = %.3g\n", label.c_str(), d);
  }
  if (const BackendRun* cpu = result.find("cpu")) {
    for (const BackendRun* gpu : {gl, vk})
      if (gpu) {
        const double d = maxAbsDiff(gpu->out.ao, cpu->out.ao);
        if (summarise) worstGpuCpu.note(d, gpu->name + ": " + label);
        if (d > 0) std::printf("[stability] %s: |%s - cpu| = %.3g\n", label.c_str(), gpu->name.c_str(), d);
      }
    if (const BackendRun* dbl = result.find("cpu-double"); dbl && summarise)
      worstCpuDouble.note(maxAbsDiff(cpu->out.ao, dbl->out.ao), label);
  }
  return result;
}

std::string expectRejected(const std::string& label, const Settings& settings, const Camera& cam,
                           const samples::RunInputs& inputs, StatusCode code, bool gpuUploadMayFailFirst) {
  std::string message;
  for (std::string_view name : kBackendNames) {
    samples::BackendRunner* runner = backend(name);
    if (!runner) continue;
    samples::RunOutputs out;
    const Status st = runner->run(settings, cam, inputs, false, false, out);
    if (gpuUploadMayFailFirst && (name == "gl" || name == "vulkan") && !st.ok() && st.code != code) {
      std::printf("[stability] %s on %.*s: rejected by the upload first: %s '%s'\n", label.c_str(), int(name.size()),
                  name.data(), toString(st.code), st.message.c_str());
      continue;
    }
    EXPECT_EQ(st.code, code) << label << " on " << name << ": expected " << toString(code) << ", got "
                             << toString(st.code) << " '" << st.message << "'";
    EXPECT_FALSE(st.message.empty()) << label << " on " << name;
    if (message.empty()) message = st.message;
  }
  return message;
}

// ---- The GPU depth model

float gpuWindowDepth(const Camera& c, float z) {
  // mvp built in double, cast to float (the view matrix is the identity here).
  const float p22 = float(P(c, 2, 2)), p23 = float(P(c, 2, 3)), p32 = float(P(c, 3, 2)), p33 = float(P(c, 3, 3));
  // clip = P·(x, y, z, 1): the x and y columns of rows 2 and 3 are zero, so only these terms.
  const float clipZ = p22 * z + p23;
  const float clipW = p32 * z + p33;
  const float ndc = clipZ / clipW;
  float d = c.clipDepth == ClipDepth::ZeroToOne ? ndc : 0.5f * ndc + 0.5f;
  return std::clamp(d, 0.0f, 1.0f);
}

double gpuWindowDepthBound(const Camera& c, double z) {
  const double p22 = P(c, 2, 2), p23 = P(c, 2, 3);
  const double a = std::fabs(p22 * z), clipZ = p22 * z + p23;
  // casts of P22 and P23, the product, the sum.
  const double dClip = kU * (2.0 * a + std::fabs(p23) + std::fabs(clipZ));
  double dNdc, ndc;
  if (c.kind == ProjectionKind::Perspective) {
    ndc = clipZ / (-z);
    dNdc = dClip / std::fabs(z) + kU * std::fabs(ndc);  // w = -z exactly; the division
  } else {
    ndc = clipZ;
    dNdc = dClip;  // w = 1
  }
  if (c.clipDepth == ClipDepth::ZeroToOne) return dNdc * (1 + 4 * kU);
  const double d = 0.5 * ndc + 0.5;
  return (0.5 * dNdc + kU * std::fabs(d)) * (1 + 4 * kU);  // 0.5·ndc is exact; the sum rounds
}

std::uint32_t storeDepth(DepthFormat format, float d) { return encodeDepth(format, double(d)); }

DepthImage renderGpuDepth(const test::Scene& scene, const Camera& cam, DepthFormat format) {
  DepthImage img;
  img.extent = test::inputExtent(cam);
  img.format = format;
  const std::vector<double> z = test::renderZ(scene, cam);
  img.texels.resize(z.size());
  const float clear = float(test::clearDepth(cam));
  for (std::size_t i = 0; i < z.size(); ++i) {
    const bool sky = z[i] == 0.0;
    if (format == DepthFormat::LinearZ)
      img.texels[i] = std::bit_cast<std::uint32_t>(sky ? 0.0f : float(z[i]));
    else
      img.texels[i] = storeDepth(format, sky ? clear : gpuWindowDepth(cam, float(z[i])));
  }
  return img;
}

std::vector<double> aoPixelZ(const test::Scene& scene, const Camera& cam) {
  const std::vector<double> z = test::renderZ(scene, cam);
  const Extent e = test::inputExtent(cam);
  std::vector<double> out(std::size_t(cam.width) * cam.height);
  for (std::uint32_t y = 0; y < cam.height; ++y)
    for (std::uint32_t x = 0; x < cam.width; ++x)
      out[std::size_t(y) * cam.width + x] = z[std::size_t(y + cam.guardBand) * e.width + x + cam.guardBand];
  return out;
}

std::vector<bool> skyMaskOf(const test::Scene& scene, const Camera& cam) {
  const std::vector<double> z = aoPixelZ(scene, cam);
  std::vector<bool> m(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) m[i] = z[i] == 0.0;
  return m;
}

// ---- Scenes

test::Scene scaledScene(const test::Scene& s, double k) {
  test::Scene out = s;
  auto sc = [k](test::Vec3 v) { return test::Vec3{v.x * k, v.y * k, v.z * k}; };
  for (auto& p : out.planes) {
    p.point = sc(p.point);
    for (auto& h : p.keep) h.point = sc(h.point);
  }
  for (auto& sp : out.spheres) sp.centre = sc(sp.centre), sp.radius *= k;
  for (auto& b : out.boxes) b.lo = sc(b.lo), b.hi = sc(b.hi);
  for (auto& r : out.rods) r.x *= k, r.z *= k, r.radius *= k, r.yMin *= k, r.yMax *= k;
  out.name += "_x" + fmt("%g", k);
  return out;
}

test::Scene turnedWall(double distance, double degrees) {
  const double a = degrees * 3.14159265358979323846 / 180.0;
  test::Scene s{"wall_" + fmt("%g", degrees) + "deg", {}, {}, {}, {}};
  s.planes.push_back({{0, 0, -distance}, {std::sin(a), 0, std::cos(a)}, {}});
  return s;
}

test::Scene cardOverWall(double cardDistance, double wallDistance, double half) {
  test::Scene s{"card_over_wall", {}, {}, {}, {}};
  s.planes.push_back({{0, 0, -wallDistance}, {0, 0, 1}, {}});
  s.planes.push_back({{0, 0, -cardDistance},
                      {0, 0, 1},
                      {{{half, 0, 0}, {1, 0, 0}}, {{-half, 0, 0}, {-1, 0, 0}}, {{0, half, 0}, {0, 1, 0}},
                       {{0, -half, 0}, {0, -1, 0}}}});
  return s;
}

// ---- Cameras

constexpr std::array<double, 16> kIdentityView{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Camera camera(std::uint32_t width, std::uint32_t height, double n, double f, ClipDepth clip, bool reversedZ,
              std::uint32_t guard) {
  Camera c = perspectiveCamera(3.14159265358979323846 / 3.0, width, height, n, f, clip, reversedZ);
  c.guardBand = guard;
  c.view = kIdentityView;  // a pose, so that every setting (temporal too) runs
  return c;
}

Camera orthoCamera(std::uint32_t width, std::uint32_t height, double n, double f, ClipDepth clip, bool reversedZ,
                   std::uint32_t guard, double halfHeight) {
  Camera c = orthographicCamera(halfHeight, width, height, n, f, clip, reversedZ);
  c.guardBand = guard;
  c.view = kIdentityView;
  return c;
}

std::string describe(const Camera& c) {
  DepthModel m;
  const bool ok = analyze(c, m).ok();
  std::string s = c.kind == ProjectionKind::Perspective ? "persp" : "ortho";
  s += fmt(" %ux%u", c.width, c.height);
  if (c.guardBand) s += fmt("+g%u", c.guardBand);
  if (ok) s += fmt(" n=%g f=%g", m.nearDistance, m.farDistance);
  s += c.clipDepth == ClipDepth::ZeroToOne ? " [0,1]" : " [-1,1]";
  s += c.reversedZ ? " reversed" : " standard";
  if (c.metersToViewUnits != 1.0) s += fmt(" u=%g", c.metersToViewUnits);
  return s;
}

// ---- Reporting

std::string fmt(const char* format, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, format);
  std::vsnprintf(buf, sizeof buf, format, ap);
  va_end(ap);
  return buf;
}

void report(const std::string& caseName, const std::string& bound, const std::string& measured) {
  static int counter = 0;
  std::printf("[stability] %s | %s | %s\n", caseName.c_str(), bound.c_str(), measured.c_str());
  std::fflush(stdout);
  ::testing::Test::RecordProperty("stability_" + std::to_string(++counter), caseName + " | " + bound + " | " + measured);
}

}  // namespace sao::stability
