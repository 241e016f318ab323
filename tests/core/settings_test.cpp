// Every setting rejects below-min, above-max, NaN and infinite values with a message that names
// the setting, the value and the range; --set parsing; presets are valid and ordered by cost.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "sao/constants.h"
#include "sao/presets.h"
#include "sao/spiral.h"
#include "sao/settings.h"

namespace {

using sao::StatusCode;

TEST(Settings, DefaultsAreValid) { EXPECT_TRUE(sao::validate(sao::Settings{}).ok()); }

// The allowed range as the messages print it: "[min, max]" (9 significant digits), "{false, true}"
// or, for a setting declared with values=[...], the list "{1, 2, 4}".
std::string rangeOf(const sao::gen::SettingInfo& info) {
  if (info.type == sao::gen::SettingType::Bool) return "{false, true}";
  if (!info.allowedValues.empty()) {
    std::ostringstream v;
    for (std::size_t k = 0; k < info.allowedValues.size(); ++k) v << (k ? ", " : "{") << info.allowedValues[k];
    return v.str() + "}";
  }
  std::ostringstream r;
  r.precision(9);
  r << "[" << info.minValue << ", " << info.maxValue << "]";
  return r.str();
}

TEST(Settings, EverySettingRejectsOutOfRangeAndNonFinite) {
  for (std::size_t i = 0; i < sao::gen::kSettings.size(); ++i) {
    const auto& info = sao::gen::kSettings[i];
    const auto id = static_cast<sao::SettingId>(i);
    const std::string name(info.name);
    struct Case {
      double value;
      const char* shown;
    };
    std::vector<Case> cases = {{std::numeric_limits<double>::quiet_NaN(), "NaN"},
                               {std::numeric_limits<double>::infinity(), "+inf"},
                               {-std::numeric_limits<double>::infinity(), "-inf"}};
    if (info.type == sao::gen::SettingType::Bool) {
      // A bool cannot hold anything but true/false: every bad value arrives as text (--set).
      for (const char* text : {"nan", "inf", "-inf", "-1", "2", "yes"}) {
        sao::Settings s;
        const sao::Settings untouched = s;
        const sao::Status st = sao::setFromText(s, name, text);
        EXPECT_EQ(st.code, StatusCode::InvalidSetting) << name << " = " << text;
        EXPECT_TRUE(s == untouched) << name << ": a rejected text must change nothing";
        EXPECT_NE(st.message.find("'" + name + "'"), std::string::npos) << st.message;
        EXPECT_NE(st.message.find(std::string("'") + text + "'"), std::string::npos) << st.message;
        EXPECT_NE(st.message.find("true or false"), std::string::npos) << st.message;
      }
      continue;
    }
    const double step = info.type == sao::gen::SettingType::Int ? 1.0 : std::max(1e-3, (info.maxValue - info.minValue) * 1e-3);
    const char* outside = info.allowedValues.empty() ? "outside its range" : "is not one of its allowed values";
    cases.push_back({info.minValue - step, outside});
    cases.push_back({info.maxValue + step, outside});
    for (const auto& c : cases) {
      sao::Settings s;
      const sao::Settings untouched = s;
      sao::Status st;
      if (info.type == sao::gen::SettingType::Int && !std::isfinite(c.value)) {
        // An int cannot hold NaN/inf: those arrive as text (the CLI's --set).
        st = sao::setFromText(s, name, std::isnan(c.value) ? "nan" : (c.value > 0 ? "inf" : "-inf"));
        EXPECT_TRUE(s == untouched) << name << ": a rejected text must change nothing";
      } else {
        sao::gen::setSettingValue(s, id, c.value);
        st = sao::validate(s);
      }
      EXPECT_EQ(st.code, StatusCode::InvalidSetting) << name << " = " << c.value;
      // Every message names the setting, what is wrong with the value and the allowed range.
      EXPECT_NE(st.message.find("'" + name + "'"), std::string::npos) << st.message;
      EXPECT_NE(st.message.find(c.shown), std::string::npos) << st.message;
      EXPECT_NE(st.message.find(rangeOf(info)), std::string::npos) << "range missing: " << st.message;
    }
  }
}

// The bounds as a user reads them in a refusal, e.g. "[1e-06, 0.01]".
std::pair<std::string, std::string> printedBounds(const std::string& name) {
  sao::Settings s;
  const sao::Status st = sao::setFromText(s, name, "1e300");
  const auto open = st.message.find('['), comma = st.message.find(", ", open), close = st.message.find(']', comma);
  if (open == std::string::npos || comma == std::string::npos || close == std::string::npos) return {};
  return {st.message.substr(open + 1, comma - open - 1), st.message.substr(comma + 2, close - comma - 2)};
}

std::string printed(double v, int digits) {
  std::ostringstream t;
  t.precision(digits);
  t << v;
  return t.str();
}

// Each bound typed exactly as a refusal prints it is accepted (and stored as the nearest float for
// float settings); the next double beyond it, the next float beyond the stored bound and, for ints,
// the next whole number are refused naming the range.
TEST(Settings, EveryBoundAcceptedAsPrintedAndJustBeyondRefused) {
  for (std::size_t i = 0; i < sao::gen::kSettings.size(); ++i) {
    const auto& info = sao::gen::kSettings[i];
    // A list of values has no range to be just beyond (AllowedValuesAloneAreAccepted).
    if (info.type == sao::gen::SettingType::Bool || !info.allowedValues.empty()) continue;
    const auto id = static_cast<sao::SettingId>(i);
    const std::string name(info.name);
    const auto [loText, hiText] = printedBounds(name);
    ASSERT_FALSE(loText.empty()) << name << ": the refusal of 1e300 names no range";
    const std::vector<std::tuple<std::string, double, double>> bounds = {{loText, info.minValue, -1.0},
                                                                         {hiText, info.maxValue, 1.0}};
    for (const auto& [text, bound, outward] : bounds) {
      sao::Settings s;
      const sao::Status st = sao::setFromText(s, name, text);
      EXPECT_TRUE(st.ok()) << name << " = " << text << ": " << st.message;
      const double expected = info.type == sao::gen::SettingType::Float ? double(float(bound)) : bound;
      EXPECT_EQ(sao::gen::settingValue(s, id), expected) << name << " = " << text;
      EXPECT_TRUE(sao::validate(s).ok()) << name << " = " << text << ": " << sao::validate(s).message;

      std::vector<std::string> beyond = {printed(std::nextafter(std::strtod(text.c_str(), nullptr), outward * INFINITY), 17)};
      if (info.type == sao::gen::SettingType::Float)
        beyond.push_back(printed(std::nextafter(float(bound), float(outward * INFINITY)), 9));
      else
        beyond.push_back(printed(bound + outward, 17));
      for (const std::string& out : beyond) {
        sao::Settings t;
        const sao::Settings untouched = t;
        const sao::Status refused = sao::setFromText(t, name, out);
        EXPECT_EQ(refused.code, StatusCode::InvalidSetting) << name << " = " << out << " must be refused";
        // The next double beyond a whole bound is no whole number: that is the reason given.
        const bool whole = std::strtod(out.c_str(), nullptr) == std::floor(std::strtod(out.c_str(), nullptr));
        const std::string reason = info.type == sao::gen::SettingType::Int && !whole
                                       ? std::string("is not a whole number")
                                       : "is outside its range [" + loText + ", " + hiText + "]";
        EXPECT_NE(refused.message.find(reason), std::string::npos) << refused.message;
        EXPECT_TRUE(t == untouched) << name << " = " << out;
      }
    }
  }
}

// The two values of the report: the upper bound of epsilon and the lower bound of contrast.
TEST(Settings, EpsilonAndContrastAtTheirPrintedBounds) {
  sao::Settings s;
  EXPECT_TRUE(sao::setFromAssignment(s, "epsilon=0.01").ok());
  EXPECT_EQ(s.epsilon, 0.01f);
  EXPECT_TRUE(sao::setFromAssignment(s, "contrast=0.1").ok());
  EXPECT_EQ(s.contrast, 0.1f);
  EXPECT_TRUE(sao::validate(s).ok());
  EXPECT_EQ(sao::setFromAssignment(s, "epsilon=0.0100001").message,
            "setting 'epsilon' = 0.0100001 is outside its range [1e-06, 0.01] m^2");
}

TEST(Settings, MessageNamesValueAndRange) {
  sao::Settings s;
  s.radius = 500.0f;
  const sao::Status st = sao::validate(s);
  EXPECT_EQ(st.message, "setting 'radius' = 500 is outside its range [0.01, 100] m");
}

TEST(Settings, ClampedIsExplicitAndTotal) {
  sao::Settings s;
  s.radius = std::numeric_limits<float>::quiet_NaN();
  s.samples = 1000;
  s.bias = -3.0f;
  const sao::Settings c = sao::clamped(s);
  EXPECT_TRUE(sao::validate(c).ok());
  EXPECT_EQ(c.radius, sao::Settings{}.radius) << "NaN becomes the default";
  EXPECT_EQ(c.samples, 64);
  EXPECT_EQ(c.bias, 0.0f);
  EXPECT_FALSE(sao::validate(s).ok()) << "the original is untouched";
}

TEST(Settings, SetFromAssignment) {
  sao::Settings s;
  EXPECT_TRUE(sao::setFromAssignment(s, "radius=2.5").ok());
  EXPECT_FLOAT_EQ(s.radius, 2.5f);
  EXPECT_TRUE(sao::setFromAssignment(s, "use_z_hierarchy=false").ok());
  EXPECT_FALSE(s.use_z_hierarchy);
  EXPECT_TRUE(sao::setFromAssignment(s, "samples=16").ok());
  EXPECT_EQ(s.samples, 16);

  const sao::Settings before = s;
  EXPECT_EQ(sao::setFromAssignment(s, "samples=16.5").message, "setting 'samples' = 16.5 is not a whole number");
  EXPECT_EQ(sao::setFromAssignment(s, "samples=abc").message, "setting 'samples': 'abc' is not a number");
  EXPECT_EQ(sao::setFromAssignment(s, "radius").code, StatusCode::InvalidSetting);
  EXPECT_NE(sao::setFromAssignment(s, "radiuss=1").message.find("unknown setting 'radiuss'"), std::string::npos);
  EXPECT_EQ(sao::setFromAssignment(s, "samples=65").message, "setting 'samples' = 65 is outside its range [1, 64]");
  EXPECT_EQ(s, before) << "failed assignments leave the settings unchanged";
}

TEST(Presets, AllValidNamedAndOnTheHierarchy) {
  for (const auto& p : sao::presets()) {
    const sao::Settings s = sao::presetSettings(p.preset);
    EXPECT_TRUE(sao::validate(s).ok()) << p.name;
    EXPECT_EQ(sao::findPreset(p.name), p.preset);
    // The tuner's grid keeps the z hierarchy (samples/bench/tune_grid.h): it is what keeps the
    // cost flat in the radius on a GPU.
    EXPECT_TRUE(s.use_z_hierarchy) << p.name;
  }
  EXPECT_FALSE(sao::findPreset("extreme").has_value());
}

// What a user gets without choosing is the high preset (the tuned point at the untuned defaults'
// cost, docs/BENCHMARKS.md "Tuning"): the settings' defaults in effect/sao.glsl must say the same.
TEST(Presets, DefaultsAreTheHighPreset) {
  EXPECT_EQ(sao::Settings{}, sao::presetSettings(sao::Preset::High));
}

// The ladder runs from quarter to full resolution and from few to many taps.
TEST(Presets, SpanResolutionAndTaps) {
  const sao::Settings low = sao::presetSettings(sao::Preset::Low);
  const sao::Settings reference = sao::presetSettings(sao::Preset::Reference);
  EXPECT_EQ(low.resolution_divisor, 4);
  EXPECT_EQ(reference.resolution_divisor, 1);
  EXPECT_LT(low.samples, reference.samples);
}

}  // namespace

// resolution_divisor takes 1, 2 or 4 and nothing between: 3 is refused (no silent clamping) with a
// message naming the setting and the values; clamped() pulls to the nearest value for sliders.
TEST(Settings, AllowedValuesAloneAreAccepted) {
  const auto id = sao::SettingId::resolution_divisor;
  const auto& info = sao::gen::kSettings[static_cast<std::size_t>(id)];
  ASSERT_EQ(info.allowedValues.size(), 3u);
  for (const char* ok : {"1", "2", "4"}) {
    sao::Settings s;
    EXPECT_TRUE(sao::setFromText(s, "resolution_divisor", ok).ok()) << ok;
    EXPECT_TRUE(sao::validate(s).ok()) << ok;
  }
  for (const char* bad : {"3", "0", "5", "8", "-2"}) {
    sao::Settings s;
    const sao::Status st = sao::setFromText(s, "resolution_divisor", bad);
    EXPECT_EQ(st.code, StatusCode::InvalidSetting) << bad;
    EXPECT_EQ(s.resolution_divisor, sao::Settings{}.resolution_divisor) << bad << ": a refused value changes nothing";
    EXPECT_EQ(st.message, "setting 'resolution_divisor' = " + std::string(bad) +
                              " is not one of its allowed values {1, 2, 4}");
  }
  sao::Settings three;
  three.resolution_divisor = 3;
  const sao::Status st = sao::validate(three);
  EXPECT_EQ(st.code, StatusCode::InvalidSetting);
  EXPECT_EQ(st.message, "setting 'resolution_divisor' = 3 is not one of its allowed values {1, 2, 4}");
  EXPECT_EQ(sao::clamped(three).resolution_divisor, 2) << "a tie goes to the lower value";
  three.resolution_divisor = 100;
  EXPECT_EQ(sao::clamped(three).resolution_divisor, 4);
  three.resolution_divisor = -7;
  EXPECT_EQ(sao::clamped(three).resolution_divisor, 1);
}

// The distance fade is on when fade_end > 0 and then needs fade_start < fade_end; a refusal names
// both settings and their values, through validate() and --set alike, and changes nothing.
TEST(Settings, FadeStartMustLieBelowFadeEnd) {
  const std::string expected = "settings 'fade_start' = 6 and 'fade_end' = 4: the distance fade needs "
                               "fade_start < fade_end (or fade_end = 0 for no fade)";
  sao::Settings s;
  EXPECT_EQ(s.fade_end, 0.0f) << "no fade by default";
  s.fade_start = 6.0f;
  s.fade_end = 4.0f;
  sao::Status st = sao::validate(s);
  EXPECT_EQ(st.code, StatusCode::InvalidSetting);
  EXPECT_EQ(st.message, expected);
  s.fade_end = 6.0f;
  EXPECT_EQ(sao::validate(s).code, StatusCode::InvalidSetting) << "equal ends are no range";
  s.fade_end = 0.0f;
  EXPECT_TRUE(sao::validate(s).ok()) << "fade_start alone is ignored while the fade is off";
  s.fade_end = 6.5f;
  EXPECT_TRUE(sao::validate(s).ok());

  // --set in either order: the second assignment is checked against the first.
  sao::Settings t;
  ASSERT_TRUE(sao::setFromAssignment(t, "fade_end=4").ok());
  const sao::Settings before = t;
  st = sao::setFromAssignment(t, "fade_start=6");
  EXPECT_EQ(st.message, expected);
  EXPECT_EQ(t, before) << "a refused assignment changes nothing";
  sao::Settings u;
  ASSERT_TRUE(sao::setFromAssignment(u, "fade_start=6").ok());
  EXPECT_EQ(sao::setFromAssignment(u, "fade_end=4").message, expected);
  EXPECT_EQ(u.fade_end, 0.0f);
  EXPECT_TRUE(sao::setFromAssignment(u, "fade_end=8").ok());
  EXPECT_TRUE(sao::setFromAssignment(u, "fade_end=0").ok()) << "turning the fade off is always allowed";

  // computeConstants refuses as well (every backend fills its block through it).
  sao::Settings bad;
  bad.fade_start = 6.0f;
  bad.fade_end = 4.0f;
  sao::ParamBlock p;
  const sao::Camera cam =
      sao::perspectiveCamera(1.0, 64, 32, 0.1, 100.0, sao::ClipDepth::NegativeOneToOne, false);
  EXPECT_EQ(sao::computeConstants(bad, cam, sao::DepthEncoding::Hardware, p).message, expected);
  // clamped() stops fade_start just below fade_end.
  const sao::Settings c = sao::clamped(bad);
  EXPECT_TRUE(sao::validate(c).ok());
  EXPECT_EQ(c.fade_end, 4.0f);
  EXPECT_EQ(c.fade_start, std::nextafter(4.0f, 0.0f));
}
