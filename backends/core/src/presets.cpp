#include "sao/presets.h"

namespace sao {

// presetSettings() indexes the table by the enumerator's value.
static_assert([] {
  for (std::size_t i = 0; i < gen::kPresets.size(); ++i)
    if (static_cast<std::size_t>(gen::kPresets[i].preset) != i) return false;
  return true;
}());

std::span<const PresetInfo> presets() { return gen::kPresets; }

std::optional<Preset> findPreset(std::string_view name) {
  for (const auto& p : gen::kPresets)
    if (p.name == name) return p.preset;
  return std::nullopt;
}

Settings presetSettings(Preset preset) {
  Settings s;
  const auto index = static_cast<std::size_t>(preset);
  if (index >= gen::kPresets.size()) return s;  // not a declared preset: the defaults
  for (const auto& v : gen::kPresets[index].values) gen::setSettingValue(s, v.setting, v.value);
  return s;
}

}  // namespace sao
