// Fuzz target: the settings parser behind `--set NAME=VALUE` (sao::setFromAssignment /
// setFromText) and the explicit clamp for UIs (sao::clamped).
//
// Input: lines of text. Each line is applied with setFromAssignment to one Settings object.
// Invariants: a rejected assignment returns InvalidSetting with a message and leaves the settings
// bit for bit unchanged; an accepted one leaves them valid (validate() is Ok). Then the bytes are
// read again as raw setting values (float and int bits, any NaN / Inf / extreme included):
// clamped() of anything is valid, and clamped() of valid settings changes nothing.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "sao/settings.h"

namespace {

using sao::gen::kSettings;
using sao::gen::SettingType;

bool sameSettings(const sao::Settings& a, const sao::Settings& b) {
  for (std::size_t i = 0; i < kSettings.size(); ++i) {
    const auto id = static_cast<sao::SettingId>(i);
    const double x = sao::gen::settingValue(a, id), y = sao::gen::settingValue(b, id);
    if (std::memcmp(&x, &y, sizeof x) != 0) return false;
  }
  return true;
}

void checkAssignments(std::string_view text) {
  sao::Settings s;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    const sao::Settings before = s;
    const sao::Status st = sao::setFromAssignment(s, line);
    if (st) {
      const sao::Status v = sao::validate(s);
      SAO_FUZZ_CHECK(v.ok(), "'%.*s' was accepted but left invalid settings: %s", int(line.size()), line.data(),
                     v.message.c_str());
    } else {
      SAO_FUZZ_CHECK(st.code == sao::StatusCode::InvalidSetting, "code %s", sao::toString(st.code));
      SAO_FUZZ_CHECK(!st.message.empty());
      SAO_FUZZ_CHECK(sameSettings(s, before), "'%.*s' was rejected (%s) but changed the settings", int(line.size()),
                     line.data(), st.message.c_str());
    }
  }
  SAO_FUZZ_CHECK(sao::validate(s).ok());
}

// Raw values: 4 bytes per setting (float bits, int32, or the low bit for a bool), cycled.
void checkClamped(const std::uint8_t* data, std::size_t size) {
  if (size < 4) return;
  sao::Settings s;
  for (std::size_t i = 0; i < kSettings.size(); ++i) {
    std::uint8_t b[4];
    for (std::size_t k = 0; k < 4; ++k) b[k] = data[(i * 4 + k) % size];
    const auto id = static_cast<sao::SettingId>(i);
    double v = 0;
    switch (kSettings[i].type) {
      case SettingType::Float: {
        float f;
        std::memcpy(&f, b, 4);
        v = f;  // exact; stored back as the same float
        break;
      }
      case SettingType::Int: {
        std::int32_t n;
        std::memcpy(&n, b, 4);
        v = n;
        break;
      }
      default: v = b[0] & 1; break;
    }
    sao::gen::setSettingValue(s, id, v);
  }
  const sao::Settings c = sao::clamped(s);
  const sao::Status v = sao::validate(c);
  SAO_FUZZ_CHECK(v.ok(), "clamped() gave invalid settings: %s", v.message.c_str());
  if (sao::validate(s).ok())  // by value: -0 may come back as +0
    for (std::size_t i = 0; i < kSettings.size(); ++i) {
      const auto id = static_cast<sao::SettingId>(i);
      SAO_FUZZ_CHECK(sao::gen::settingValue(s, id) == sao::gen::settingValue(c, id), "clamped() changed valid %s",
                     std::string(kSettings[i].name).c_str());
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  checkAssignments(std::string_view(reinterpret_cast<const char*>(data), size));
  checkClamped(data, size);
  return 0;
}
