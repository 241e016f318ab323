// Error of an AO image against a reference, over the pixels that have geometry.
//
// A metric that is undefined for the images at hand is NaN (test with isDefined), never a
// plausible-looking number: every one of them over zero pixels; SSIM when no 8x8 window lies
// inside the mask, or when both images are constant over the mask (its structure term is then
// 0/0, and a score of 1 would only say that the two constants match); the best-fit occlusion
// scale when the AO shows no occlusion on any compared pixel (every scale fits equally). Printers
// write "n/a" for it, JSON writers null.
#pragma once
#include <cmath>
#include <cstddef>
#include <vector>

#include "sao/image.h"

namespace sao::samples {

struct ErrorMetrics {
  std::size_t pixels = 0;     // pixels compared (mask non-zero)
  double rmse = NAN;
  double meanBias = NAN;        // mean(ao - reference): negative = darker than the reference
  double ssim = NAN;            // mean SSIM over 8x8 windows fully inside the mask (data range 1)
  double fractionOver01 = NAN;  // share of pixels off by more than 0.1
  double flip = NAN;            // mean FLIP over the mask (flip.h: the perceptual difference, 0 = none)
  // Darkening where nothing occludes: over the pixels whose reference is exactly 1 (every ray of a
  // ray-traced reference escaped: open planes, convex edges and corners), how many there are, the
  // mean of 1 - ao, and the share darker than 0.9. Undefined (NaN) without such pixels.
  std::size_t openPixels = 0;
  double openDarkening = NAN;
  double openShareUnder09 = NAN;
};

struct ReferenceComparison {
  ErrorMetrics raw;
  double fittedIntensity = NAN;  // k minimising |(1 - k (1 - ao)) - reference|^2: occlusion scale
  ErrorMetrics fitted;           // the same metrics after applying k (k = 1 when k is undefined)
};

// Whether a metric above is defined (not NaN).
inline bool isDefined(double metric) { return !std::isnan(metric); }

// `mask[i]` non-zero selects pixel i (row-major, the AO extent). Both images are 1-channel.
ReferenceComparison compareToReference(const FloatImage& ao, const FloatImage& reference,
                                       const std::vector<unsigned char>& mask);

// The mask of pixels with geometry: position w (4th channel) != 0, guard band g cut off.
std::vector<unsigned char> geometryMask(const FloatImage& positions, std::uint32_t guardBand);

}  // namespace sao::samples
