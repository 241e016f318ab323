// Presets trade speed for accuracy. They are declared in the effect (`#pragma sao preset`, values
// and summaries) and generated; their measured cost and error are published by sao-bench.
#pragma once
#include <optional>
#include <span>
#include <string_view>

#include "sao/settings.h"

namespace sao {

// Low, Medium, High, Ultra, Reference: the effect's presets in declaration order.
using Preset = gen::Preset;
// preset, name (as --preset takes it), summary, and the setting values it applies.
using PresetInfo = gen::PresetInfo;

std::span<const PresetInfo> presets();
std::optional<Preset> findPreset(std::string_view name);

// The defaults with the preset's values applied (settings it does not list keep their defaults).
Settings presetSettings(Preset preset);

}  // namespace sao
