// User settings: the struct and its metadata are generated from the annotated effect; this
// header adds validation (no silent clamping), an explicit clamp for UIs, and text parsing.
#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "sao/status.h"
#include "sao_effect.h"

namespace sao {

using Settings = gen::Settings;
using SettingInfo = gen::SettingInfo;
using SettingId = gen::SettingId;

// Ok, or InvalidSetting naming the first offending setting, its value and the allowed range (or
// the allowed values, for a setting declared with values=[...]), or naming both settings of a
// broken rule between them (the distance fade: fade_start < fade_end when fade_end > 0). A
// float setting holding the float nearest a bound (0.01 is stored as 0.0099999998f) is in range.
Status validate(const Settings& settings);

// Every value pulled into its range, or to its nearest allowed value (NaN becomes the default);
// a fade_start at or beyond a non-zero fade_end becomes the largest float below fade_end.
// For sliders, never implicit.
Settings clamped(const Settings& settings);

// The setting called `name`, or nullopt.
std::optional<SettingId> findSetting(std::string_view name);

// Parses `value` for the named setting ("true"/"false"/"1"/"0" for bools) and stores it if it is
// valid (for fade_start / fade_end: also together with the other one); otherwise returns
// InvalidSetting and leaves `settings` unchanged. The number as written
// must lie in [min, max] exactly as the metadata (and every refusal) prints them: each bound is
// accepted, the next double beyond it is not.
Status setFromText(Settings& settings, std::string_view name, std::string_view value);

// "name=value" as the CLI's --set takes it.
Status setFromAssignment(Settings& settings, std::string_view assignment);

// The effect's refusals (`#pragma sao refuse` in effect/sao.glsl, gen::kRefusalRules): an error
// naming the first setting away from its default that the others rule out (bent_normals = true
// with a blur), what rules it out and what to change. plan() checks it after validate(); it is not
// part of validate(), which holds for each assignment on its own (a CLI's --set order is free).
Status checkRefusals(const Settings& settings);

// A setting that has no effect under `settings`: the effect's first rule (`#pragma sao inert` in
// effect/sao.glsl, gen::kInertRules) under which setting `id`'s value reaches no pass that runs,
// or null when it has an effect. Programs refuse a setting the user gave that has none.
const gen::InertRule* inertRule(const Settings& settings, SettingId id);

// "fade_start has no effect while fade_end = 0 (no distance fade: ...): also set fade_end > 0, or
// drop fade_start": the rule, its reason and the fix, for a setting the user gave.
std::string describeInert(const gen::InertRule& rule);

}  // namespace sao
