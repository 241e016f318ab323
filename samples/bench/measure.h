// One bench measurement: run a backend several times on prepared inputs and keep the median of
// each pass, plus the error against the ray-traced reference when one is given.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "sao/samples/backend_runner.h"
#include "sao/samples/metrics.h"

namespace sao::bench {

struct Measurement {
  std::vector<PassTiming> passes;  // median per pass over the runs
  double totalMs = 0;              // median of the per-run totals
  TimingMethod method = TimingMethod::None;
  int runs = 0;
  std::uint64_t planBytes = 0;
  std::uint32_t cszLevels = 0;
  std::optional<samples::ReferenceComparison> error;
  FloatImage ao;
};

Status measure(samples::BackendRunner& backend, const Settings& settings, const Camera& camera,
               const DepthImage& depth, int runs, const FloatImage* reference,
               const std::vector<unsigned char>* mask, Measurement& out);

}  // namespace sao::bench
