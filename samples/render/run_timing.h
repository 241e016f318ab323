// Per-pass times a user can quote: the median over N measured runs (after one warm-up run that is
// not counted), with the fastest and slowest run as the spread.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/timing.h"

namespace sao::render {

struct Spread {
  double median = 0, min = 0, max = 0;  // milliseconds
};

struct PassSpread {
  std::string pass;
  Spread ms;
};

struct RunTiming {
  TimingMethod method = TimingMethod::None;
  std::uint32_t runs = 0;  // measured runs (the warm-up excluded)
  std::vector<PassSpread> passes;
  Spread total;  // of each run's sum over its passes
};

// The runs must time the same passes; a pass missing from a run counts as missing, not as 0 ms.
RunTiming summarizeRuns(const std::vector<Timings>& runs);

}  // namespace sao::render
