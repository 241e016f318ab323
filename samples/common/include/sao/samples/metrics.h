// Error of an AO image against a reference, over the pixels that have geometry.
#pragma once
#include <cstddef>
#include <vector>

#include "sao/image.h"

namespace sao::samples {

struct ErrorMetrics {
  std::size_t pixels = 0;     // pixels compared (mask non-zero)
  double rmse = 0;
  double meanBias = 0;        // mean(ao - reference): negative = darker than the reference
  double ssim = 0;            // mean SSIM over 8x8 windows fully inside the mask (data range 1)
  double fractionOver01 = 0;  // share of pixels off by more than 0.1
};

struct ReferenceComparison {
  ErrorMetrics raw;
  double fittedIntensity = 1;  // k minimising |(1 - k (1 - ao)) - reference|^2: occlusion scale
  ErrorMetrics fitted;         // the same metrics after applying k
};

// `mask[i]` non-zero selects pixel i (row-major, the AO extent). Both images are 1-channel.
ReferenceComparison compareToReference(const FloatImage& ao, const FloatImage& reference,
                                       const std::vector<unsigned char>& mask);

// The mask of pixels with geometry: position w (4th channel) != 0, guard band g cut off.
std::vector<unsigned char> geometryMask(const FloatImage& positions, std::uint32_t guardBand);

}  // namespace sao::samples
