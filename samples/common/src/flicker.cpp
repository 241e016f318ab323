#include "sao/samples/flicker.h"

#include <cmath>

namespace sao::samples {

Flicker reprojectedFlicker(const FlickerFrame& previous, const FlickerFrame& current, const Camera& camera) {
  Flicker out;
  const glm::dmat4 currentToPrevious = previous.worldToCamera * glm::inverse(current.worldToCamera);
  const auto& P = camera.projection;  // column-major: element (row r, column c) is P[c * 4 + r]
  const std::int64_t w = camera.width, h = camera.height, g = camera.guardBand;
  double sum = 0;
  for (std::int64_t y = 0; y < h; ++y)
    for (std::int64_t x = 0; x < w; ++x) {
      const auto px = std::uint32_t(x + g), py = std::uint32_t(y + g);
      if (current.position->at(px, py, 3) == 0.0f) continue;
      ++out.geometry;
      const glm::dvec4 p(current.position->at(px, py, 0), current.position->at(px, py, 1),
                         current.position->at(px, py, 2), 1.0);
      const glm::dvec4 q = currentToPrevious * p;  // the same world point in the previous camera
      double clip[4];
      for (int r = 0; r < 4; ++r) clip[r] = P[r] * q.x + P[4 + r] * q.y + P[8 + r] * q.z + P[12 + r] * q.w;
      if (!(clip[3] > 0)) continue;
      const double ndcX = clip[0] / clip[3], ndcY = (camera.flipY ? -1.0 : 1.0) * clip[1] / clip[3];
      // Row 0 at ndc y = -1 (sao::Camera's convention without flipY).
      const auto qx = std::int64_t(std::floor((ndcX + 1.0) * 0.5 * double(w)));
      const auto qy = std::int64_t(std::floor((ndcY + 1.0) * 0.5 * double(h)));
      if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
      const auto sx = std::uint32_t(qx + g), sy = std::uint32_t(qy + g);
      if (previous.position->at(sx, sy, 3) == 0.0f) continue;
      const double zThere = previous.position->at(sx, sy, 2);
      if (std::abs(zThere - q.z) > 0.01 * std::abs(q.z)) continue;  // another surface: disoccluded
      sum += std::abs(double(current.ao->at(std::uint32_t(x), std::uint32_t(y))) -
                      double(previous.ao->at(std::uint32_t(qx), std::uint32_t(qy))));
      ++out.compared;
    }
  out.meanAbsDifference = out.compared ? sum / double(out.compared) : 0.0;
  return out;
}

}  // namespace sao::samples
