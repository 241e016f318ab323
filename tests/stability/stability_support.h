// The numerical-stability suite's shared machinery: every case runs on every backend the samples'
// runner knows ("cpu-double", "cpu", "gl", "vulkan"), skipping the ones this build leaves out or
// SAO_STABILITY_BACKENDS excludes (one that fails to start is a test failure), with the same
// checks everywhere (finite, in [0, 1], the AO extent, sky = 1) and a GL-vs-Vulkan agreement
// check (<= 1/255) whenever both ran. Also: the depth a GPU writes, modelled operation by
// operation in float (docs/STABILITY.md, "The GPU depth model"), scene helpers built on the
// sao_test_scenes library, and the "[stability]" report lines that docs/STABILITY.md quotes.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analytic_scenes.h"
#include "sao/camera.h"
#include "sao/constants.h"
#include "sao/image.h"
#include "sao/samples/backend_runner.h"
#include "sao/settings.h"

namespace sao::stability {

// The backends every case loops over, in this order (the references first, so that a GPU result
// can be compared with them).
// The settings' defaults at full resolution. The suite's cases were written for full-resolution
// output (ao_raw at the output's size, per-pixel statistics, false occlusion judged before the
// blur); since the tuned defaults (issue 16) run at half resolution, every case asks for full
// resolution explicitly. The reduced-resolution path has its own agreement, seam and precision
// tests (tests/*/reduced_resolution_test.cpp).
inline Settings fullResolution() {
  Settings s;
  s.resolution_divisor = 1;
  return s;
}

inline constexpr std::array<std::string_view, 4> kBackendNames = {"cpu-double", "cpu", "gl", "vulkan"};

// The one agreement bound between the GPU backends (design-notes §6: "aim at <= 1/255").
inline constexpr double kGpuAgreement = 1.0 / 255.0;

// A started runner for `name`, created once per process and kept, or nullptr. A backend excluded
// by SAO_STABILITY_BACKENDS or not built into this program is a logged skip. One that is built
// but fails to start fails every test that asks for it (once per test), unless
// SAO_STABILITY_ALLOW_MISSING_BACKENDS=1, which turns that into a logged skip too.
samples::BackendRunner* backend(std::string_view name);

enum class BackendState { Started, Excluded, NotBuilt, FailedAllowed, Failed };
// What backend(name) found (starting it if not tried yet); `reason` gets the runner's
// description or why it did not start.
BackendState backendState(std::string_view name, std::string* reason = nullptr);

// ---- Running one case on every backend

struct CaseOptions {
  bool dumpPasses = false;  // ask the runners for their intermediates (csz levels, ao_raw, ...)
  // Restrict the case to these backends (empty: all of kBackendNames). Used only where the
  // issue allows it (8K on the CPU reference).
  std::vector<std::string_view> only;
  // AO pixels (AO extent, row 0 first) that are sky in the input: A must be exactly 1 there.
  const std::vector<bool>* skyMask = nullptr;
  // Skip the GL-vs-Vulkan check (never used by a case of the issue; for diagnostics only).
  bool compareGpus = true;
  // GPU backends whose API cannot hold the input (a GL depth texture clamps what is uploaded to
  // it, so the runner reports InvalidInput): logged and skipped instead of failed.
  bool gpuMayRejectInput = false;
  // Left out of the end-of-run summary of cross-backend differences (cases outside the range the
  // suite claims, e.g. the units sweep beyond 1e-9).
  bool excludeFromSummary = false;
};

struct BackendRun {
  std::string name;
  samples::RunOutputs out;
  // An intermediate by name ("csz_level0", "ao_raw", ...), or nullptr when the runner gave none.
  const FloatImage* intermediate(std::string_view passName) const;
};

struct CaseRuns {
  std::string label;
  std::vector<BackendRun> runs;  // only the backends that were available, in kBackendNames order
  const BackendRun* find(std::string_view name) const;
};

// Runs the case on each available backend. Every run must succeed and its AO must have the
// camera's extent, be finite and lie in [0, 1] (and be exactly 1 on skyMask); when both GL and
// Vulkan ran, their AO must agree to kGpuAgreement. Failures are reported with `label`.
CaseRuns runCase(const std::string& label, const Settings& settings, const Camera& camera,
                 const samples::RunInputs& inputs, const CaseOptions& options = {});

// Runs the case on each available backend and expects it to be rejected with `code`; returns the
// message of the first rejection (empty if none ran).
// With gpuUploadMayFailFirst, a GPU runner may fail earlier, in its own texture upload, with any
// error code (logged).
std::string expectRejected(const std::string& label, const Settings& settings, const Camera& camera,
                           const samples::RunInputs& inputs, StatusCode code, bool gpuUploadMayFailFirst = false);

// ---- Image statistics

struct Range {
  double min = 0, max = 0, mean = 0;
  std::size_t count = 0;
};
// Over the pixels where mask (if given) is true.
Range range(const FloatImage& img, const std::vector<bool>* mask = nullptr, std::uint32_t channel = 0);
double maxAbsDiff(const FloatImage& a, const FloatImage& b, const std::vector<bool>* mask = nullptr);
bool allFinite(const FloatImage& img);

// ---- The depth a GPU writes (docs/STABILITY.md, "The GPU depth model")

// The window depth a GPU computes for a vertex at camera-space z (a float): the projection built
// in double and cast to float, clip = P·(x, y, z, 1) in float, the perspective divide in float,
// then the viewport transform d = 0.5·ndc + 0.5 in float for GL's [-1, 1] clip range (d = ndc for
// [0, 1]), clamped to [0, 1] as the depth range clamp does. Built with -ffp-contract=off.
float gpuWindowDepth(const Camera& camera, float z);

// A first-order bound on |gpuWindowDepth(z) - d(z)|, d(z) the exact window depth of the double
// projection: the float casts of P22, P23 and every rounding of the transform (u = 2^-24).
double gpuWindowDepthBound(const Camera& camera, double z);

// The stored texel of window depth d as the depth write quantises it (round to nearest for
// D16 / D24; the float itself for D32F); LinearZ stores z.
std::uint32_t storeDepth(DepthFormat format, float d);

// The depth image a GPU would hold for the scene: the analytic camera-space z of each texel
// (sao::test::renderZ, double), rounded to a float vertex z, then gpuWindowDepth and storeDepth.
// Texels without a surface hold the clear value (LinearZ: +0.0).
DepthImage renderGpuDepth(const test::Scene& scene, const Camera& camera, DepthFormat format);

// AO-extent mask of the pixels whose depth texel (p + guard) holds no surface of the scene.
std::vector<bool> skyMaskOf(const test::Scene& scene, const Camera& camera);
// The analytic camera-space z of every AO pixel (0 = sky), row 0 first.
std::vector<double> aoPixelZ(const test::Scene& scene, const Camera& camera);

// ---- Scenes (extending sao_test_scenes)

// Every surface scaled about the eye by k (units change, geometry does not).
test::Scene scaledScene(const test::Scene& scene, double k);
// A plane through (0, 0, -distance) whose normal is turned `degrees` away from the view axis
// about the vertical axis (0: facing the camera, 89: seen at grazing incidence on the screen's
// centre column).
test::Scene turnedWall(double distance, double degrees);
// A camera-facing rectangle |x|, |y| <= half at z = -cardDistance in front of a wall at
// z = -wallDistance: a depth discontinuity along the card's four edges.
test::Scene cardOverWall(double cardDistance, double wallDistance, double half);

// ---- Cameras

// 60-degree vertical field of view, width x height, the given near / far / conventions.
Camera camera(std::uint32_t width, std::uint32_t height, double nearDistance, double farDistance, ClipDepth clip,
              bool reversedZ, std::uint32_t guard = 0);
// An orthographic camera of the given half height in view units (default tan 30°: the extent
// camera() has at distance 1).
Camera orthoCamera(std::uint32_t width, std::uint32_t height, double nearDistance, double farDistance,
                   ClipDepth clip, bool reversedZ, std::uint32_t guard = 0, double halfHeight = 0.57735026918962573);

std::string describe(const Camera& camera);  // "persp n=0.1 f=inf [0,1] reversed"

// ---- Reporting

// One line "[stability] <case> | <bound> | <measured>" on stdout (docs/STABILITY.md quotes them),
// also recorded as a test property.
void report(const std::string& caseName, const std::string& bound, const std::string& measured);
std::string fmt(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace sao::stability
