// The run's summary: what ran, how long each pass took, the plan's memory, and the error against
// the reference when one was computed.
#pragma once
#include <optional>
#include <string>

#include "sao/image.h"
#include "sao/plan.h"
#include "sao/samples/metrics.h"
#include "sao/settings.h"
#include "sao/timing.h"

namespace sao::samples {

struct Summary {
  std::string backend, input;
  Extent size;
  std::uint32_t guard = 0;
  Settings settings;
  Plan plan;
  Timings timings;
  double prepareSeconds = 0;
  std::optional<ReferenceComparison> metrics;
  std::uint32_t referenceRays = 0;

  std::string text() const;
  std::string json() const;
};

}  // namespace sao::samples
