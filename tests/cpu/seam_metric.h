// The seam metric of the reduced-resolution tests (CPU, OpenGL, Vulkan): the mean of every row and
// of every column of an image, and how far one mean lies from the average of its two neighbours.
// A line that differs from the lines on both sides (a centre-line or block-edge seam of an
// upsample, a last row or column left unwritten) stands out; a smooth gradient scores about 0.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "analytic_scenes.h"
#include "sao/image.h"

namespace sao::test {

struct SeamScore {
  double row = 0, column = 0;                   // largest |mean - average of the neighbours' means|
  std::uint32_t worstRow = 0, worstColumn = 0;  // where
};

// Lines within `margin` of an image edge are not scored: there the clamped taps of eq. 10 make A
// change fast at any resolution, and the last, partial block of an odd size samples the very edge.
inline SeamScore seamScore(const FloatImage& img, std::uint32_t margin, std::uint32_t channel = 0) {
  const std::uint32_t W = img.extent.width, H = img.extent.height;
  std::vector<double> rows(H, 0.0), cols(W, 0.0);
  for (std::uint32_t y = 0; y < H; ++y)
    for (std::uint32_t x = 0; x < W; ++x) {
      rows[y] += img.at(x, y, channel) / double(W);
      cols[x] += img.at(x, y, channel) / double(H);
    }
  SeamScore s;
  auto worst = [margin](const std::vector<double>& m, double& score, std::uint32_t& at) {
    for (std::size_t i = std::max<std::size_t>(margin, 1); i + std::max<std::size_t>(margin, 1) < m.size(); ++i) {
      const double d = std::fabs(m[i] - 0.5 * (m[i - 1] + m[i + 1]));
      if (d > score) score = d, at = static_cast<std::uint32_t>(i);
    }
  };
  worst(rows, s.row, s.worstRow);
  worst(cols, s.column, s.worstColumn);
  return s;
}

// The crease of creaseScene turned by 90 degrees: z = -distance + |y|, meeting along the screen's
// centre row. A then depends on the row alone, so column means are flat and a column seam (the
// centre column of an odd width among them) stands out; creaseScene does the same for rows.
inline Scene horizontalCreaseScene(double distance) {
  Scene s{"horizontal_crease", {}, {}, {}, {}};
  s.planes.push_back({{0, 0, -distance}, {0, 1, 1}, {{{0, 0, 0}, {0, 1, 0}}}});    // y <= 0
  s.planes.push_back({{0, 0, -distance}, {0, -1, 1}, {{{0, 0, 0}, {0, -1, 0}}}});  // y >= 0
  return s;
}

// The bound on a seam score: a line whose pixels are all off by delta moves its mean by delta,
// so this catches any row or column off by half an 8-bit step on average. At full resolution the
// same scenes score under 0.3/255 (estimator noise the blur leaves).
inline constexpr double kSeamBound = 0.5 / 255.0;

}  // namespace sao::test
