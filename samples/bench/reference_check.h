// The check every sao-bench run makes before measuring: the near-field reference (a) against the
// analytic sphere case (raytrace::traceAnalyticSphere) at a few angles, as reference_check.csv.
#pragma once
#include <string>
#include <vector>

#include "sao/raytrace/analytic.h"

namespace sao::bench {

// The largest |traced - analytic| the reference may show (bench_smoke.sh and the gtest hold it).
inline constexpr double kReferenceTolerance = 0.01;

// theta 0, 45, 60 degrees, R = 1, D = 3, 40,000 rays each; fails the Status if Embree fails.
Status checkReference(std::vector<raytrace::SphereCheck>& out);

// theta_deg,R,D,analytic,traced,abs_error, one row per case.
void writeReferenceCheck(const std::string& path, const std::vector<raytrace::SphereCheck>& checks);

}  // namespace sao::bench
