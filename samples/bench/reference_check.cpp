#include "reference_check.h"

#include <fstream>
#include <iomanip>

namespace sao::bench {

Status checkReference(std::vector<raytrace::SphereCheck>& out) {
  out.clear();
  for (double theta : {0.0, 45.0, 60.0}) {
    raytrace::SphereCheck c;
    if (Status st = raytrace::traceAnalyticSphere({theta, 1.0, 3.0}, 40000, 7, c); !st) return st;
    out.push_back(c);
  }
  return Status::success();
}

void writeReferenceCheck(const std::string& path, const std::vector<raytrace::SphereCheck>& checks) {
  std::ofstream f(path);
  f << "theta_deg,R,D,analytic,traced,abs_error\n" << std::setprecision(6);
  for (const auto& c : checks)
    f << c.sphere.thetaDegrees << "," << c.sphere.radius << "," << c.sphere.distance << "," << c.analytic << ","
      << c.traced << "," << c.absError() << "\n";
}

}  // namespace sao::bench
