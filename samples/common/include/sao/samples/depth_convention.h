// Whether a depth buffer's values fit the conventions it is read with: a buffer read with the wrong
// convention (reversed-Z as standard, standard as reversed-Z, linear depth as perspective depth,
// positive distances as LinearZ) or holding no geometry at all gives an AO that is plain wrong, or
// 1 everywhere, without any error. The programs say so, naming the likely cause and the flag.
#pragma once
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/settings.h"

namespace sao::samples {

// One line each (without a program prefix), judged from the values of `depth` over the camera's
// viewport (the whole image when its extent does not match the camera), for the cases:
//   - no geometry: every texel is sky (all at the clear value, the near plane beyond the scene...;
//     LinearZ: positive, 0, NaN or infinite values), so the AO is 1 everywhere;
//   - LinearZ whose texels are mostly positive (sky): positive distances, not camera-space z;
//   - perspective hardware depth whose geometry the declared convention puts within twice the near
//     distance (the median of 1 - d, or of d for reversed-Z, above 1/2) while the other one does
//     not, and whose sky is not the declared clear value: the other convention (--reversed-z);
//   - orthographic hardware depth whose sky is the other convention's clear value;
//   - perspective hardware depth whose values vary like a distance (1/d affine on flat surfaces)
//     rather than like window depth (d affine), judged on texels 1/64 of the image apart: linear
//     depth normalised to [0, 1].
// Not told: the Z convention of orthographic depth without sky, linear [0, 1] depth read with an
// orthographic camera (it is orthographic window depth for other near/far), and perspective depth
// read with the wrong convention whose geometry lies mostly within twice the near distance.
// Empty when nothing looks wrong, or when the camera or settings are ones the effect would refuse.
// checkScale (scale_warnings.h) puts these lines first in its own list and, when there are any,
// leaves out its units/radius warnings, whose figures a wrong convention explains.
std::vector<std::string> depthConventionWarnings(const DepthImage& depth, const Camera& camera,
                                                 const Settings& settings);

}  // namespace sao::samples
