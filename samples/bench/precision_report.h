// The precision section's outputs: precision.csv (one row per backend x format x far plane x
// convention x distance bin) and precision.txt (the same as fixed-width tables, one per backend).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "sao/prepass/precision.h"

namespace sao::bench {

using PrecisionByBackend = std::vector<std::pair<std::string, std::vector<prepass::PrecisionRow>>>;

void writePrecision(const std::string& dir, const PrecisionByBackend& results);

}  // namespace sao::bench
