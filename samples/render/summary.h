// The run's summary: what ran, how long each pass took, the plan's memory, and the error against
// the reference when one was computed.
#pragma once
#include <optional>
#include <string>

#include "sao/image.h"
#include "sao/plan.h"
#include "sao/settings.h"
#include "sao/timing.h"

namespace sao::samples {

struct ErrorMetrics {
  std::size_t pixels = 0;      // non-sky pixels compared
  double rmse = 0;
  double meanBias = 0;         // mean(ao - reference): negative = darker than the reference
  double fractionOver01 = 0;   // share of pixels off by more than 0.1
};

// Over pixels whose position w (4th channel of `positions`, guard-band offset g) is non-zero.
ErrorMetrics compareToReference(const FloatImage& ao, const FloatImage& reference, const FloatImage& positions,
                                std::uint32_t guardBand);

struct Summary {
  std::string backend, input;
  Extent size;
  std::uint32_t guard = 0;
  Settings settings;
  Plan plan;
  Timings timings;
  double prepareSeconds = 0;
  std::optional<ErrorMetrics> metrics;
  std::uint32_t referenceRays = 0;

  std::string text() const;
  std::string json() const;
};

}  // namespace sao::samples
