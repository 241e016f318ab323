// The settings' defaults before the presets were tuned (issue 16, 2026-12-03): full resolution, 11
// taps, a 9-tap blur (radius 4, stride 2) whose depth edge is against the centre's z, q' = 8 px,
// rg32f (A, key) images. Tests whose figures were derived by hand for a full-resolution plan with a
// blur (plan bytes, dispatch lists, MIP counts, reconstruction keys, seam bounds) use these instead
// of Settings{}, whose defaults are now the high preset (half resolution).
#pragma once
#include <string>
#include <vector>

#include "sao/presets.h"
#include "sao/settings.h"

namespace sao::test {

inline Settings untunedDefaults() {
  Settings s;
  s.samples = 11;
  s.mip_switch_log2 = 3;
  s.blur_radius = 4;
  s.blur_stride = 2;
  s.resolution_divisor = 1;
  s.half_intermediates = false;  // rg32f (A, key) images, as before half_intermediates became the default
  s.blur_edge_slope = false;      // the blur's depth edge against the centre's z, as before 2026-12-08
  return s;
}

// The medium preset before tuning: the same with a 7-tap blur (radius 3, stride 2).
inline Settings untunedMedium() {
  Settings s = untunedDefaults();
  s.blur_radius = 3;
  return s;
}

// The settings the backends' agreement matrices run: every preset, plus what no preset covers since
// the tuning: the z hierarchy off (the Z_HIERARCHY=0 variant, the AlchemyAO-style baseline's) and
// the untuned defaults (full resolution with a 9-tap strided blur).
struct NamedSettings {
  std::string name;
  Settings settings;
};
inline std::vector<NamedSettings> agreementSettings() {
  std::vector<NamedSettings> out;
  for (const PresetInfo& p : presets()) out.push_back({std::string(p.name), presetSettings(p.preset)});
  Settings flat = untunedMedium();
  flat.use_z_hierarchy = false;
  out.push_back({"no_hierarchy", flat});
  out.push_back({"untuned_defaults", untunedDefaults()});
  return out;
}

}  // namespace sao::test
