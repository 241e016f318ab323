// The analytic case the near-field reference is checked against (tests and every sao-bench run):
// a sphere of radius R whose centre is at distance D from a point on a plane, at angle theta from
// the plane's normal and fully above the horizon, occludes cos(theta) (R/D)^2 of the
// cosine-weighted hemisphere (unbounded ray length).
#pragma once
#include <cstdint>

#include "sao/status.h"

namespace sao::raytrace {

struct SphereCase {
  double thetaDegrees = 0;
  double radius = 1.0;    // R
  double distance = 3.0;  // D, centre to the point
};

struct SphereCheck {
  SphereCase sphere;
  double analytic = 0;  // cos(theta) (R/D)^2
  double traced = 0;    // 1 - visibilityAt with an unbounded radius
  double absError() const;
};

// Traces `rays` cosine-weighted rays (seed `seed`) from the point against a finely tessellated
// sphere. InvalidInput when the sphere is not fully above the horizon (theta + asin(R/D) > 90
// degrees) or R, D are not finite with 0 < R < D.
Status traceAnalyticSphere(const SphereCase& sphere, std::uint32_t rays, std::uint64_t seed, SphereCheck& out);

}  // namespace sao::raytrace
