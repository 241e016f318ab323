// Pieces of the precision measurement (precision.h) that live in their own files.
#pragma once
#include <array>
#include <vector>

#include "sao/constants.h"
#include "sao/image.h"
#include "sao/prepass/precision.h"

namespace sao::prepass::detail {

// The face normal ao_sample reconstructs at csz level-0 texel (cx, cy) from the csz image
// (docs/effect-math.md 5.2, NORMALS_SUPPLIED = 0), in the shader's float arithmetic and order.
std::array<float, 3> reconstructNormal(const FloatImage& csz0, int cx, int cy, const ParamBlock& params);

// What the measurement compares against, per texel of the depth image (row 0 at ndc y = -1).
struct Truth {
  Extent extent;
  std::vector<double> z;           // camera-space z, view units (0 where nothing is hit)
  std::vector<glm::dvec3> normal;  // unit, facing the camera
  std::vector<unsigned char> inside;  // 1: the texel and its 4 neighbours lie on one face
};

// Analytic truth for the panels of precisionScene seen through `camera` from `view`.
Truth panelTruth(const std::vector<PrecisionPanel>& panels, const scenes::View& view, const Camera& camera);

}  // namespace sao::prepass::detail
