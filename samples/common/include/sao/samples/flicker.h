// Temporal stability of AO along a camera path: the flicker figure of issues 16 and 18, mean
// |A_t - A_{t-1}| on static geometry after reprojection. Each pixel of frame t with geometry is
// carried to world space and into frame t-1 (its camera and projection), and compared with the
// nearest pixel there when that pixel shows the same surface (its camera-space z within 1 % of the
// reprojected point's); the others are disoccluded or left the view and are not counted.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "sao/camera.h"
#include "sao/image.h"

namespace sao::samples {

// One frame: its AO (the viewport, 1 channel), its camera-space positions (4 channels, w = 0 where
// nothing is hit; the depth input's extent, guard band included) and its world -> camera matrix.
struct FlickerFrame {
  const FloatImage* ao = nullptr;
  const FloatImage* position = nullptr;
  glm::dmat4 worldToCamera{1.0};
};

struct Flicker {
  double meanAbsDifference = 0;  // mean |A_t - A_{t-1}| over the compared pixels
  std::uint64_t compared = 0;    // pixels reprojected onto the same surface
  std::uint64_t geometry = 0;    // pixels of frame t with geometry
};

// Both frames use `camera`'s projection, size and guard band (a camera path moves the view only).
Flicker reprojectedFlicker(const FlickerFrame& previous, const FlickerFrame& current, const Camera& camera);

// A path's flicker: each frame's figure added, the mean over the path weighted by the pixels each
// frame compared, and the share of geometry pixels compared.
struct FlickerTotal {
  double weightedSum = 0;  // sum of meanAbsDifference * compared
  std::uint64_t compared = 0, geometry = 0;
  void add(const Flicker& f) {
    weightedSum += f.meanAbsDifference * double(f.compared);
    compared += f.compared;
    geometry += f.geometry;
  }
  double mean() const { return compared ? weightedSum / double(compared) : 0.0; }
  double comparedFraction() const { return geometry ? double(compared) / double(geometry) : 0.0; }
};

}  // namespace sao::samples
