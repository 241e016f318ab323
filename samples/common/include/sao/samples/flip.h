// FLIP (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom, Fairchild: "FLIP: A Difference
// Evaluator for Alternating Images", HPG 2020), the LDR version, for single-channel AO images:
// the per-pixel difference a viewer flipping between the two images would notice, in [0, 1].
//
// An AO value v is taken as a grey pixel (v, v, v) as ao.png stores it, i.e. read as sRGB, which
// is what FLIP's LDR input is. A grey has no chroma, so of FLIP's three opponent channels only the
// achromatic one is non-zero: the colour term is the Hunt-adjusted HyAB distance of the CSF-filtered
// images, which for greys is |L*_ref - L*_test|, and the feature term compares edges and points
// of the unfiltered luminance. Written from the paper; the constants are the paper's.
#pragma once
#include <cmath>
#include <vector>

#include "sao/image.h"

namespace sao::samples {

// Pixels per degree of visual angle: FLIP's default viewer, 0.7 m from a 0.7 m wide display of
// 3840 pixels (0.7 * 3840 / 0.7 * pi / 180).
inline constexpr double kFlipPixelsPerDegree = 67.0206;

// The FLIP error map of `test` against `reference` (1-channel images of one extent, values
// clamped to [0, 1]): one value in [0, 1] per pixel, row-major. Symmetric in its two images.
FloatImage flipErrorMap(const FloatImage& test, const FloatImage& reference, double ppd = kFlipPixelsPerDegree);

// Mean FLIP over the pixels where `mask` is non-zero, NaN over none. Pixels outside the mask are
// set to 1 (unoccluded) in both images first, so that sky, which has no AO, adds no difference
// through the filters' footprint.
double meanFlip(const FloatImage& test, const FloatImage& reference, const std::vector<unsigned char>& mask,
                double ppd = kFlipPixelsPerDegree);

// FLIP's colour-difference ceiling: the Hunt-adjusted HyAB distance between sRGB green and blue,
// raised to q_c = 0.7 (errors are remapped against it). Exposed for tests.
double flipMaxColorDistance();

}  // namespace sao::samples
