// Whether the effect's radius suits the scene's scale, judged from a finished run: a scene in other
// units than the settings assume (Camera::metersToViewUnits) gives an all-white AO without any
// error, so the programs say so.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/settings.h"
#include "sao/status.h"

namespace sao::samples {

struct ScaleCheck {
  std::size_t geometryPixels = 0;  // AO pixels whose depth is geometry (finite camera-space z < 0)
  double radiusPxMedian = 0;       // projected radius r' (eq. 5, before the effect's clamp) over them
  double fractionBelowOnePx = 0;   // share of them with r' < 1 px
  double fractionAboveImage = 0;   // share with r' > the image's larger side
  double aoMin = 1, aoMean = 1;    // the AO over them
  std::vector<std::string> warnings;  // one line each, without a program prefix
};

// The warnings: first depthConventionWarnings(depth, camera, settings) (depth_convention.h: no
// geometry at all, a buffer that looks read with the wrong convention), and only when there are
// none, since a wrong convention explains the figures, each of these when it holds on geometry
// pixels:
//   - r' below 1 px on more than half of them (the effect then returns 1: nothing to see);
//   - r' above the image's larger side on more than half of them;
//   - the AO exactly 1.0 on every one of them.
// `depth` is the run's depth input (AO size plus the guard band) and `ao` its output (1 channel,
// the camera's viewport). InvalidInput for images that do not match the camera, or a camera or
// settings the effect would refuse.
Status checkScale(const Settings& settings, const Camera& camera, const DepthImage& depth, const FloatImage& ao,
                  ScaleCheck& out);

}  // namespace sao::samples
