// One bench measurement: run a backend several times on prepared inputs and keep the median of
// each pass, plus the error against each ray-traced reference that is given.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "sao/samples/backend_runner.h"
#include "sao/samples/error_structure.h"
#include "sao/samples/metrics.h"

namespace sao::bench {

// The truths a measurement is compared with, over the pixels where `mask` is non-zero. Any
// reference may be absent (no error is computed for it); without a mask none is.
struct References {
  const FloatImage* nearFieldAo = nullptr;  // (a) raytrace::referenceAmbientOcclusion at the run's radius
  const FloatImage* obscurance = nullptr;   // (b) raytrace::referenceObscurance with the run's settings
  const FloatImage* converged = nullptr;    // (c) raytrace::convergedEstimator with the run's settings and inputs
  const FloatImage* screen = nullptr;       // (d) raytrace::screenVisibility with the run's radius and inputs,
  const std::vector<unsigned char>* screenMask = nullptr;  // compared over this mask (its stride's pixels)
  const std::vector<unsigned char>* mask = nullptr;
  const std::vector<unsigned char>* silhouette = nullptr;  // samples::silhouetteBand, for (c)'s structure
};

struct Measurement {
  std::vector<PassTiming> passes;  // median per pass over the runs
  double totalMs = 0;              // median of the per-run totals
  TimingMethod method = TimingMethod::None;
  int runs = 0;
  std::uint64_t planBytes = 0;
  std::uint32_t cszLevels = 0;
  // Wall-clock time (seconds since the Unix epoch) of the first timed run's start and the last's end:
  // a GPU's clock log (ci/gpu-bench.sh's gpu-clocks.csv) lines up with the rows by them.
  double startedUnixSeconds = 0, endedUnixSeconds = 0;
  std::string shaderVariant;  // the ao_sample variant the plan chose, e.g. "NORMALS_SUPPLIED=1 TWO_LAYER=0 Z_HIERARCHY=0"
  std::optional<samples::ReferenceComparison> aoError;          // against (a)
  std::optional<samples::ReferenceComparison> obscuranceError;  // against (b)
  std::optional<samples::ReferenceComparison> convergedError;   // against (c)
  std::optional<samples::ReferenceComparison> screenError;      // against (d)
  std::optional<samples::ErrorStructure> convergedStructure;    // blotch, high-frequency, silhouette vs (c)
  FloatImage ao;
};

// `inputs` select the variant as the backends do: normals -> NORMALS_SUPPLIED, depth2 -> TWO_LAYER;
// settings.use_z_hierarchy -> Z_HIERARCHY.
// warmupMs > 0: after the warm-up run, the backend renders back to back for that long
// (BackendRunner::keepBusy: a GPU's clocks up) before the timed runs; not with the temporal setting,
// whose history it would advance.
// averagedFrames > 1: the AO compared with the references (and kept in `ao`) is the mean of that many
// untimed runs at Inputs::frameIndex 0, 1, ... (each frame its own taps: what a static camera's
// frames converge to, the estimator's own converged value, without its sampling noise); the times
// are the timed runs' as before. Not with the temporal setting (InvalidInput), which blends frames
// itself.
Status measure(samples::BackendRunner& backend, const Settings& settings, const Camera& camera,
               const samples::RunInputs& inputs, int runs, const References& references, Measurement& out,
               double warmupMs = 0, std::uint32_t averagedFrames = 1);

}  // namespace sao::bench
