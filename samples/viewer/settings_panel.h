// The settings section of the panel, generated from the effect's metadata (gen::kSettings): one
// control per setting with its range and unit, its doc string as tooltip, a preset selector and
// "reset to defaults". Every edit goes through sao::setFromText, so the settings stay valid. A
// setting the others make inert (gen::kInertRules) is greyed out, the reason in its tooltip.
#pragma once
#include <string>

#include "sao/settings.h"

namespace sao::viewer {

struct SettingsPanelState {
  int preset = -1;          // index into sao::presets(), -1: custom / defaults
  std::string rejected;     // the last edit setFromText refused, shown under the controls
};

// Returns true when `settings` changed.
bool drawSettingsPanel(Settings& settings, SettingsPanelState& state);

// The label a setting gets: "name [unit]" or "name".
std::string settingLabel(const SettingInfo& info);
// Whether a float setting's slider is logarithmic: max/min > 100 (a zero minimum counts).
bool logarithmicSlider(const SettingInfo& info);

}  // namespace sao::viewer
