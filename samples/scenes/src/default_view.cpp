// The view a mesh file gets: the whole bounding box in sight.
#include "sao/scenes/default_view.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace sao::scenes {

namespace {

void bounds(const Mesh& mesh, glm::dvec3& lo, glm::dvec3& hi) {
  lo = glm::dvec3(std::numeric_limits<double>::max());
  hi = -lo;
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
}

}  // namespace

double defaultNearDistance(const Mesh& mesh) {
  glm::dvec3 lo, hi;
  bounds(mesh, lo, hi);
  return glm::length(hi - lo) / 100.0;
}

View defaultView(const Mesh& mesh) {
  glm::dvec3 lo, hi;
  bounds(mesh, lo, hi);
  const glm::dvec3 centre = (lo + hi) * 0.5;
  const double radius = glm::length(hi - lo) * 0.5;
  View v;
  v.name = "default";
  v.fovyRadians = std::numbers::pi / 3;
  // The bounding sphere fits the vertical field of view (and the horizontal one, for aspect >= 1).
  const double distance = radius / std::sin(v.fovyRadians / 2);
  v.target = centre;
  v.eye = centre + glm::normalize(glm::dvec3(1, 1, 1)) * distance;
  v.up = {0, 1, 0};
  v.nearDistance = glm::length(hi - lo) / 100.0;  // as defaultNearDistance
  return v;
}

}  // namespace sao::scenes
