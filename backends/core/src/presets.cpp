#include "sao/presets.h"

namespace sao {
namespace {

constexpr PresetInfo kPresets[] = {
    {Preset::Low, "low", "6 taps, 2x2 + 5-tap blur, z hierarchy with an early MIP switch (q' = 4 px)"},
    {Preset::Medium, "medium", "11 taps, 2x2 + 7-tap blur, z hierarchy (q' = 8 px)"},
    {Preset::High, "high", "16 taps, 2x2 + 9-tap blur, z hierarchy (q' = 8 px)"},
    {Preset::Ultra, "ultra", "32 taps, 2x2 + 13-tap blur, z hierarchy with a later MIP switch (q' = 16 px)"},
    {Preset::Reference, "reference", "64 taps at full resolution (no z hierarchy), light blur"},
};

}  // namespace

std::span<const PresetInfo> presets() { return kPresets; }

std::optional<Preset> findPreset(std::string_view name) {
  for (const auto& p : kPresets)
    if (p.name == name) return p.preset;
  return std::nullopt;
}

Settings presetSettings(Preset preset) {
  Settings s;
  switch (preset) {
    case Preset::Low:
      s.samples = 6;
      s.blur_radius = 2;
      s.blur_stride = 2;
      s.use_z_hierarchy = true;
      s.mip_switch_log2 = 2;  // coarser levels from 4 px on: fewer cache misses, less z detail
      break;
    case Preset::Medium:
      s.samples = 11;
      s.blur_radius = 3;
      s.blur_stride = 2;
      s.use_z_hierarchy = true;
      s.mip_switch_log2 = 3;  // the paper's q' = 8
      break;
    case Preset::High:
      s.samples = 16;
      s.blur_radius = 4;
      s.blur_stride = 2;
      s.use_z_hierarchy = true;
      s.mip_switch_log2 = 3;
      break;
    case Preset::Ultra:
      s.samples = 32;
      s.blur_radius = 6;
      s.blur_stride = 1;
      s.use_z_hierarchy = true;
      s.mip_switch_log2 = 4;
      break;
    case Preset::Reference:
      s.samples = 64;
      s.blur_radius = 2;
      s.blur_stride = 1;
      s.use_z_hierarchy = false;
      break;
  }
  return s;
}

}  // namespace sao
