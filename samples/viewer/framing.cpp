#include "framing.h"

#include <algorithm>

namespace sao::viewer {

Strip freeStrip(bool panelShown, double panelX0, double panelX1) {
  if (!panelShown) return {};
  const double left = std::clamp(panelX0, 0.0, 1.0), right = std::clamp(panelX1, 0.0, 1.0);
  const Strip beside = left >= 1.0 - right ? Strip{0.0, left} : Strip{right, 1.0};
  if (beside.x1 - beside.x0 < 0.25) return {};
  return beside;
}

void frameInStrip(Camera& camera, Strip strip) {
  if (strip == Strip{}) return;
  // ndc' = s * ndc + (c, 0): in clip space row 0' = s * row 0 + c * row 3 (row 3 gives w: -z for a
  // perspective camera, 1 for an orthographic one), row 1' = s * row 1.
  const double s = strip.x1 - strip.x0, c = strip.x0 + strip.x1 - 1.0;
  auto& m = camera.projection;  // column-major: element (row r, column k) is m[k * 4 + r]
  for (int k = 0; k < 4; ++k) {
    m[std::size_t(k * 4 + 0)] = s * m[std::size_t(k * 4 + 0)] + c * m[std::size_t(k * 4 + 3)];
    m[std::size_t(k * 4 + 1)] = s * m[std::size_t(k * 4 + 1)];
  }
}

}  // namespace sao::viewer
