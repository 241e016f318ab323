// For the tests that set every setting to an end of its range: the settings the effect's refusal
// rules (`#pragma sao refuse`, gen::kRefusalRules) rule out under the others, back at their
// defaults. bent_normals = true needs the visibility estimator, the direct path and an rgba output
// (refused otherwise: tests/vulkan/bent_normal_test.cpp checks that and its own agreement).
#pragma once
#include "sao/settings.h"

namespace sao::test {

inline Settings withoutRefusedSettings(Settings s) {
  for (const gen::InertRule& rule : gen::kRefusalRules)
    if (gen::holds(rule.when, s))
      gen::setSettingValue(s, rule.setting, gen::kSettings[static_cast<std::size_t>(rule.setting)].defaultValue);
  return s;
}

// Whether a refusal rule rules `s` out (plan() would fail with its message).
inline bool refused(const Settings& s) { return !checkRefusals(s).ok(); }

}  // namespace sao::test
