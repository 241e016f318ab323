// View modes and the composite's parameter block.
#include <algorithm>
#include <cmath>

#include "viewer_types.h"

namespace sao::viewer {
namespace {

constexpr ViewModeInfo kModes[] = {
    {ViewMode::Ao, "ao", "AO only"},
    {ViewMode::Lit, "lit", "Lit with AO"},
    {ViewMode::LitNoAo, "lit-no-ao", "Lit without AO"},
    {ViewMode::Split, "split", "Split: without | with AO"},
    {ViewMode::RawAo, "raw-ao", "Raw AO (before blur)"},
    {ViewMode::ZMip, "z-mip", "z MIP level"},
    {ViewMode::Normals, "normals", "Reconstructed normals"},
    {ViewMode::Error, "error", "Error vs reference"},
    {ViewMode::SplitResolution, "split-resolution", "Split: full | reduced resolution"},
};

}  // namespace

std::span<const ViewModeInfo> viewModes() { return kModes; }

std::optional<ViewMode> findViewMode(std::string_view name) {
  for (const auto& m : kModes)
    if (m.name == name) return m.mode;
  return std::nullopt;
}

std::string viewModeNames() {
  std::string s;
  for (const auto& m : kModes) s += (s.empty() ? "" : ", ") + std::string(m.name);
  return s;
}

int reducedDivisor(const Settings& settings) {
  return settings.resolution_divisor > 1 ? settings.resolution_divisor : 2;
}

// The panel's settings at the other side's divisor: 1 when the panel asks for a reduced one,
// else 2 (a valid value of resolution_divisor's values=[1,2,4] either way).
Settings compareSettings(const Settings& settings) {
  Settings s = settings;
  s.resolution_divisor = settings.resolution_divisor > 1 ? 1 : 2;
  return s;
}

LegendRect errorLegend(int width, int height) {
  // 14 px wide, 40 % of the height (at most 240 px), 56 px from the right edge: room for the labels
  // on its left and the split labels' line below.
  LegendRect r;
  r.x1 = width - 56;
  r.x0 = r.x1 - 14;
  r.y0 = std::max(40, height / 10);
  r.y1 = r.y0 + std::min(240, height * 2 / 5);
  return r;
}

CompositeParams makeCompositeParams(const FrameDesc& f, bool topDown, bool rawAo, std::uint32_t cszLevels) {
  CompositeParams p{};
  const Camera& c = f.camera;
  DepthModel model;
  (void)analyze(c, model);  // the camera was built by the viewer and checked by the effect
  // Camera-space x of depth texel centre px: -z (ndc.x + P20) / P00 with ndc.x = 2 (px - g) / W - 1.
  const double w = c.width, h = c.height, g = c.guardBand;
  const auto& m = c.projection;
  const bool ortho = c.kind == ProjectionKind::Orthographic;
  if (ortho) {  // x = (ndc.x - P30) / P00, without z
    p.projInfo[0] = float(2.0 / (w * m[0]));
    p.projInfo[1] = float(-(1.0 + m[12] + 2.0 * g / w) / m[0]);
    p.projInfo[2] = float(2.0 / (h * m[5]));
    p.projInfo[3] = float(-(1.0 + m[13] + 2.0 * g / h) / m[5]);
  } else {
    p.projInfo[0] = float(-2.0 / (w * m[0]));
    p.projInfo[1] = float((1.0 - m[8] + 2.0 * g / w) / m[0]);
    p.projInfo[2] = float(-2.0 / (h * m[5]));
    p.projInfo[3] = float((1.0 - m[9] + 2.0 * g / h) / m[5]);
  }
  p.projection[0] = ortho ? 1 : 0;
  p.depthModel[0] = float(model.c0);
  p.depthModel[1] = float(model.c1);
  p.depthModel[2] = float(model.c2);
  p.depthModel[3] = float(model.depthAtFar);
  const glm::dvec4 up = f.view * glm::dvec4(0, 1, 0, 0);
  p.worldUp[0] = float(up.x);
  p.worldUp[1] = float(up.y);
  p.worldUp[2] = float(up.z);
  p.display[0] = float(f.zNear);
  p.display[1] = float(std::max(f.zFar, f.zNear * 1.01));
  p.display[2] = float(f.errorScale > 0 ? f.errorScale : 1.0);
  p.display[3] = float(std::floor(f.splitFraction * w));
  p.modes[0] = static_cast<std::int32_t>(f.mode);
  p.modes[1] = f.cszLevel;
  p.modes[2] = topDown ? 1 : 0;
  p.modes[3] = f.referenceValid ? 1 : 0;
  p.extra[0] = static_cast<std::int32_t>(c.guardBand);
  p.extra[1] = static_cast<std::int32_t>(c.height);
  p.extra[2] = rawAo ? 1 : 0;
  p.extra[3] = static_cast<std::int32_t>(cszLevels);
  const LegendRect legend = errorLegend(int(c.width), int(c.height));  // the window's size
  p.legend[0] = legend.x0;
  p.legend[1] = legend.y0;
  p.legend[2] = legend.x1;
  p.legend[3] = legend.y1;
  return p;
}

}  // namespace sao::viewer
