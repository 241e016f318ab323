#include "sao/settings.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

namespace sao {
namespace {

// 9 significant digits, or 17 when 9 would print a different number (64.00000000000001 is not
// "64", which would make "is not a whole number" read as nonsense).
std::string describe(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  if (std::isfinite(v) && std::strtod(s.str().c_str(), nullptr) != v) {
    s.str("");
    s.precision(17);
    s << v;
  }
  return s.str();
}

std::string rangeText(const SettingInfo& info) {
  if (info.type == gen::SettingType::Bool) return "{false, true}";
  if (!info.allowedValues.empty()) {
    std::string t;
    for (double v : info.allowedValues) t += (t.empty() ? "" : ", ") + describe(v);
    return "{" + t + "}";
  }
  return "[" + describe(info.minValue) + ", " + describe(info.maxValue) + "]";
}

// exactBounds: `v` is what the user wrote (text), held to the bounds exactly as printed. Otherwise
// `v` is a value already stored in Settings: a float setting then also accepts the float nearest
// each bound (0.01 is stored as 0.0099999998f, 0.1 as 0.100000001f).
Status checkValue(const SettingInfo& info, double v, bool exactBounds) {
  // Built only for an error: a steady render() allocates nothing.
  auto where = [&] { return "setting '" + std::string(info.name) + "' "; };
  if (std::isnan(v)) return Status::error(StatusCode::InvalidSetting, where() + "is NaN; allowed range " + rangeText(info));
  if (std::isinf(v))
    return Status::error(StatusCode::InvalidSetting,
                         where() + "is " + (v > 0 ? "+inf" : "-inf") + "; allowed range " + rangeText(info));
  if (info.type != gen::SettingType::Float && v != std::floor(v))
    return Status::error(StatusCode::InvalidSetting, where() + "= " + describe(v) + " is not a whole number");
  // A setting with a list of values takes those alone (resolution_divisor: 3 is not a third size).
  if (!info.allowedValues.empty() &&
      std::find(info.allowedValues.begin(), info.allowedValues.end(), v) == info.allowedValues.end())
    return Status::error(StatusCode::InvalidSetting,
                         where() + "= " + describe(v) + " is not one of its allowed values " + rangeText(info));
  const bool widen = !exactBounds && info.type == gen::SettingType::Float;
  const double lo = widen ? std::fmin(info.minValue, double(float(info.minValue))) : info.minValue;
  const double hi = widen ? std::fmax(info.maxValue, double(float(info.maxValue))) : info.maxValue;
  if (v < lo || v > hi)
    return Status::error(StatusCode::InvalidSetting,
                         where() + "= " + describe(v) + " is outside its range " + rangeText(info) +
                             (info.unit.empty() ? "" : " " + std::string(info.unit)));
  return Status::success();
}

// Rules between settings, after each is in its range. The distance fade is on when fade_end > 0
// and then needs fade_start below it (fade_start is ignored while the fade is off).
Status checkTogether(const Settings& s) {
  if (s.fade_end > 0.0f && !(s.fade_start < s.fade_end))
    return Status::error(StatusCode::InvalidSetting,
                         "settings 'fade_start' = " + describe(s.fade_start) + " and 'fade_end' = " +
                             describe(s.fade_end) +
                             ": the distance fade needs fade_start < fade_end (or fade_end = 0 for no fade)");
  return Status::success();
}

}  // namespace

Status validate(const Settings& settings) {
  for (size_t i = 0; i < gen::kSettings.size(); ++i) {
    Status s = checkValue(gen::kSettings[i], gen::settingValue(settings, static_cast<SettingId>(i)), false);
    if (!s) return s;
  }
  return checkTogether(settings);
}

Settings clamped(const Settings& settings) {
  Settings out = settings;
  for (size_t i = 0; i < gen::kSettings.size(); ++i) {
    const auto id = static_cast<SettingId>(i);
    const SettingInfo& info = gen::kSettings[i];
    double v = gen::settingValue(settings, id);
    if (std::isnan(v)) v = info.defaultValue;
    v = std::fmin(std::fmax(v, info.minValue), info.maxValue);
    if (info.type != gen::SettingType::Float) v = std::round(v);
    // The nearest allowed value (the lower one on a tie).
    if (!info.allowedValues.empty()) {
      double best = info.allowedValues.front();
      for (double a : info.allowedValues)
        if (std::fabs(a - v) < std::fabs(best - v)) best = a;
      v = best;
    }
    gen::setSettingValue(out, id, v);
  }
  // fade_start at or beyond fade_end: the largest start below the end (a slider pushed past it stops).
  if (out.fade_end > 0.0f && !(out.fade_start < out.fade_end)) out.fade_start = std::nextafter(out.fade_end, 0.0f);
  return out;
}

std::optional<SettingId> findSetting(std::string_view name) {
  for (size_t i = 0; i < gen::kSettings.size(); ++i)
    if (gen::kSettings[i].name == name) return static_cast<SettingId>(i);
  return std::nullopt;
}

Status setFromText(Settings& settings, std::string_view name, std::string_view value) {
  const auto id = findSetting(name);
  if (!id) {
    std::string known;
    for (const auto& s : gen::kSettings) known += (known.empty() ? "" : ", ") + std::string(s.name);
    return Status::error(StatusCode::InvalidSetting,
                         "unknown setting '" + std::string(name) + "' (known: " + known + ")");
  }
  const SettingInfo& info = gen::kSettings[static_cast<size_t>(*id)];
  const std::string text(value);
  double v = 0;
  if (info.type == gen::SettingType::Bool) {
    if (text == "true" || text == "1") v = 1;
    else if (text == "false" || text == "0") v = 0;
    else
      return Status::error(StatusCode::InvalidSetting,
                           "setting '" + std::string(name) + "' is a bool: expected true or false, got '" + text + "'");
  } else {
    char* end = nullptr;
    v = text.empty() ? 0 : std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size())
      return Status::error(StatusCode::InvalidSetting,
                           "setting '" + std::string(name) + "': '" + text + "' is not a number");
  }
  if (Status s = checkValue(info, v, true); !s) return s;
  // An accepted fade value leaves valid settings: the rule between the two holds for the result.
  Settings next = settings;
  gen::setSettingValue(next, *id, v);
  if (*id == SettingId::fade_start || *id == SettingId::fade_end)
    if (Status s = checkTogether(next); !s) return s;
  settings = next;
  return Status::success();
}

Status setFromAssignment(Settings& settings, std::string_view assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    return Status::error(StatusCode::InvalidSetting,
                         "expected name=value, got '" + std::string(assignment) + "'");
  return setFromText(settings, assignment.substr(0, eq), assignment.substr(eq + 1));
}

Status checkRefusals(const Settings& settings) {
  for (const gen::InertRule& rule : gen::kRefusalRules) {
    const SettingInfo& info = gen::kSettings[static_cast<size_t>(rule.setting)];
    const double v = gen::settingValue(settings, rule.setting);
    if (v == info.defaultValue || !gen::holds(rule.when, settings)) continue;
    const std::string name(info.name);
    const std::string value = info.type == gen::SettingType::Bool ? (v != 0 ? "true" : "false") : describe(v);
    return Status::error(StatusCode::InvalidSetting,
                         "setting '" + name + "' = " + value + " is refused while " + std::string(rule.whenText) +
                             " (" + std::string(rule.reason) + "): also set " + std::string(rule.fixText) +
                             ", or drop " + name);
  }
  return Status::success();
}

const gen::InertRule* inertRule(const Settings& settings, SettingId id) {
  for (const gen::InertRule& rule : gen::kInertRules)
    if (rule.setting == id && gen::holds(rule.when, settings)) return &rule;
  return nullptr;
}

std::string describeInert(const gen::InertRule& rule) {
  const std::string name(gen::kSettings[static_cast<size_t>(rule.setting)].name);
  return name + " has no effect while " + std::string(rule.whenText) + " (" + std::string(rule.reason) +
         "): also set " + std::string(rule.fixText) + ", or drop " + name;
}

}  // namespace sao
