#include "settings_panel.h"

#include <imgui.h>

#include <cstdio>
#include <string>

#include "sao/presets.h"

namespace sao::viewer {
namespace {

std::string formatValue(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// `inert`: the effect's rule under which the setting has no effect now (greyed out), or null.
void tooltip(const SettingInfo& info, const gen::InertRule* inert) {
  if (!ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) return;
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
  if (inert)
    ImGui::Text("No effect while %.*s (%.*s): set %.*s to change it.", int(inert->whenText.size()),
                inert->whenText.data(), int(inert->reason.size()), inert->reason.data(), int(inert->fixText.size()),
                inert->fixText.data());
  ImGui::TextUnformatted(info.doc.data(), info.doc.data() + info.doc.size());
  ImGui::TextDisabled("range [%g, %g]%s%.*s, default %g", info.minValue, info.maxValue, info.unit.empty() ? "" : " ",
                      int(info.unit.size()), info.unit.data(), info.defaultValue);
  ImGui::PopTextWrapPos();
  ImGui::EndTooltip();
}

// One control; returns the value the user asked for, or nothing when untouched.
bool control(const SettingInfo& info, double current, const gen::InertRule* inert, double& wanted) {
  const std::string label = settingLabel(info);
  bool edited = false;
  ImGui::BeginDisabled(inert != nullptr);
  switch (info.type) {
    case gen::SettingType::Float: {
      float v = static_cast<float>(current);
      ImGuiSliderFlags flags = ImGuiSliderFlags_NoRoundToFormat;
      if (logarithmicSlider(info)) flags |= ImGuiSliderFlags_Logarithmic;
      edited = ImGui::SliderFloat(label.c_str(), &v, float(info.minValue), float(info.maxValue), "%.4g", flags);
      wanted = v;
      break;
    }
    case gen::SettingType::Int: {
      int v = static_cast<int>(current);
      if (!info.allowedValues.empty()) {  // values=[...]: a slider would offer values it refuses
        if (ImGui::BeginCombo(label.c_str(), std::to_string(v).c_str())) {
          for (double allowed : info.allowedValues) {
            const int a = static_cast<int>(allowed);
            if (ImGui::Selectable(std::to_string(a).c_str(), a == v)) v = a, edited = true;
          }
          ImGui::EndCombo();
        }
      } else {
        edited = ImGui::SliderInt(label.c_str(), &v, int(info.minValue), int(info.maxValue));
      }
      wanted = v;
      break;
    }
    case gen::SettingType::Bool: {
      bool v = current != 0;
      edited = ImGui::Checkbox(label.c_str(), &v);
      wanted = v ? 1 : 0;
      break;
    }
  }
  ImGui::EndDisabled();
  tooltip(info, inert);
  return edited;
}

}  // namespace

std::string settingLabel(const SettingInfo& info) {
  std::string label(info.name);
  if (!info.unit.empty()) label += " [" + std::string(info.unit) + "]";
  return label;
}

bool logarithmicSlider(const SettingInfo& info) {
  return info.type == gen::SettingType::Float && (info.minValue <= 0 || info.maxValue / info.minValue > 100);
}

bool drawSettingsPanel(Settings& settings, SettingsPanelState& state) {
  bool changed = false;
  const auto all = presets();
  const std::string current =
      state.preset >= 0 ? std::string(all[state.preset].name) : settings == Settings{} ? "(defaults)" : "(custom)";
  if (ImGui::BeginCombo("preset", current.c_str())) {
    for (int i = 0; i < int(all.size()); ++i) {
      const std::string name(all[i].name);
      if (ImGui::Selectable(name.c_str(), i == state.preset)) {
        settings = presetSettings(all[i].preset);
        state.preset = i;
        state.rejected.clear();
        changed = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%.*s", int(all[i].summary.size()), all[i].summary.data());
    }
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  if (ImGui::Button("Reset to defaults")) {
    settings = Settings{};
    state.preset = -1;
    state.rejected.clear();
    changed = true;
  }
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
    const SettingInfo& info = gen::kSettings[i];
    const auto id = static_cast<SettingId>(i);
    double wanted = 0;
    // A setting the others make inert (gen::kInertRules) is shown greyed out, with the reason.
    if (!control(info, gen::settingValue(settings, id), inertRule(settings, id), wanted)) continue;
    // Ctrl+click lets the user type any number: setFromText refuses what is out of range.
    if (Status s = setFromText(settings, info.name, formatValue(wanted)); !s) {
      state.rejected = s.message;
    } else {
      state.rejected.clear();
      state.preset = -1;
      changed = true;
    }
  }
  if (!state.rejected.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "rejected: %s", state.rejected.c_str());
    ImGui::PopTextWrapPos();
  }
  return changed;
}

}  // namespace sao::viewer
