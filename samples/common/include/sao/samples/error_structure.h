// Where an AO image's error lies, beyond one RMSE: the low-frequency blotches a blur cannot remove,
// the high-frequency remainder, the halos at depth discontinuities, and the signed error itself as
// a false-colour PNG. Metrics follow metrics.h: NaN (undefined) over zero pixels.
#pragma once
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "sao/image.h"
#include "sao/status.h"

namespace sao::samples {

inline constexpr double kBlotchSigmaPx = 8.0;         // the low-pass that separates blotches from noise
inline constexpr int kSilhouetteBandPx = 3;           // "near a discontinuity": within this distance
inline constexpr double kDiscontinuityRelativeJump = 0.1;  // |z1 - z2| > 0.1 min(|z1|, |z2|)
inline constexpr double kErrorMapScale = 0.1;         // error of full colour in the PNG maps

struct ErrorStructure {
  double blotchRmse = NAN;         // RMSE over the mask of the error low-passed (Gaussian, kBlotchSigmaPx)
  double highFrequencyRmse = NAN;  // RMSE over the mask of the error minus that low-pass
  std::size_t silhouettePixels = 0;
  double silhouetteRmse = NAN;     // RMSE over the mask pixels of the silhouette band
};

// The pixels (AO viewport, row-major) within kSilhouetteBandPx (Euclidean) of a depth
// discontinuity: a pair of 4-neighbours of the depth input (viewport + guard band, so edges at the
// viewport border count) where one is sky and the other geometry (position w == 0 / != 0), or
// both are geometry and their camera-space z differ by more than kDiscontinuityRelativeJump times
// the nearer one's |z|. Both pixels of such a pair are on the discontinuity.
std::vector<unsigned char> silhouetteBand(const FloatImage& positions, std::uint32_t guardBand);

// The error e = ao - reference over `mask`. The low-pass is a normalised convolution over the mask
// only, sum(G e m) / sum(G m) with a Gaussian G of sigma kBlotchSigmaPx truncated at 3 sigma, so
// sky and the image border do not pull it towards 0. `band` (silhouetteBand) selects the
// silhouette pixels among the mask's.
ErrorStructure errorStructure(const FloatImage& ao, const FloatImage& reference, const std::vector<unsigned char>& mask,
                              const std::vector<unsigned char>& band);

// The signed error ao - reference as an 8-bit RGB PNG, top row first: white at 0, towards blue
// where ao is darker (negative), towards red where it is lighter (positive), full colour at
// +-kErrorMapScale and beyond; pixels outside the mask mid grey. IoError if it cannot be written.
Status writeErrorMapPng(const std::string& path, const FloatImage& ao, const FloatImage& reference,
                        const std::vector<unsigned char>& mask);

}  // namespace sao::samples
