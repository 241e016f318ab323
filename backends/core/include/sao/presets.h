// Presets trade speed for accuracy. Their measured cost and error are published by sao-bench.
#pragma once
#include <optional>
#include <span>
#include <string_view>

#include "sao/settings.h"

namespace sao {

enum class Preset { Low, Medium, High, Ultra, Reference };

struct PresetInfo {
  Preset preset;
  std::string_view name;
  std::string_view summary;
};

std::span<const PresetInfo> presets();
std::optional<Preset> findPreset(std::string_view name);

// The defaults with the preset's sample count, blur taps and MIP use applied.
Settings presetSettings(Preset preset);

}  // namespace sao
