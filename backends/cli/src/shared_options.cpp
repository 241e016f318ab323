#include "sao/cli/shared_options.h"

#include <algorithm>
#include <cctype>
#include <memory>
#include <optional>

namespace sao::cli {
namespace {

// "low, medium, high, ultra, reference" (separator ", ") or "low | medium | ..." (" | ").
std::string presetNames(const std::string& separator) {
  std::string names;
  for (const PresetInfo& p : presets()) names += (names.empty() ? "" : separator) + std::string(p.name);
  return names;
}

Preset presetOrReject(const std::string& name) {
  const auto preset = findPreset(name);
  if (!preset) reject("unknown preset '" + name + "' (" + presetNames(", ") + ")");
  return *preset;
}

std::string range(std::uint32_t lo, std::uint32_t hi) { return std::to_string(lo) + ".." + std::to_string(hi); }

// "HELP, LO..HI (NOTE)"; `what` before the range ("each side ").
std::string described(const std::string& help, std::uint32_t lo, std::uint32_t hi, const std::string& note,
                      const std::string& what = "") {
  return help + ", " + what + range(lo, hi) + (note.empty() ? "" : " (" + note + ")");
}

}  // namespace

CLI::Option* addImageSize(CommandLine& cl, Extent& target, const std::string& help, const std::string& note) {
  return cl.size("--size", target, 1, kMaxImageSide, described(help, 1, kMaxImageSide, note, "each side "));
}

CLI::Option* addImageSizes(CommandLine& cl, std::vector<Extent>& target, const std::string& help,
                           const std::string& note) {
  return cl.value("--size", "WxH", described(help, 1, kMaxImageSide, "repeatable; " + note, "each side "),
                  [&target](const std::string& v) { target.push_back(parseSize("--size", v, 1, kMaxImageSide)); });
}

CLI::Option* addRuns(CommandLine& cl, std::uint32_t& target, std::uint32_t minRuns, const std::string& help,
                     const std::string& note) {
  return cl.whole("--runs", target, minRuns, kMaxRuns, "N", described(help, minRuns, kMaxRuns, note));
}

CLI::Option* addRays(CommandLine& cl, const std::string& name, std::uint32_t& target, const std::string& help,
                     const std::string& note) {
  return cl.whole(name, target, 1, kMaxRays, "N", described(help, 1, kMaxRays, note));
}

CLI::Option* addGuardBand(CommandLine& cl, std::uint32_t& target, const std::string& help, const std::string& note) {
  return cl.whole("--guard", target, 0, kMaxGuardBand, "N", described(help, 0, kMaxGuardBand, note));
}

CLI::Option* addViewNumber(CommandLine& cl, std::uint32_t& target) {
  return cl.whole("--view", target, 0, kMaxViewNumber, "N", "the scene's view number (default 0)");
}

void addSettings(CommandLine& cl, Settings& settings, const std::string& setHelp) {
  // CLI11 runs the checks in the order the options are declared: the preset before the --set
  // assignments, wherever they stand on the command line.
  cl.value("--preset", "NAME", presetNames(" | ") + " (default: the settings' defaults)",
           [&settings](const std::string& v) { settings = presetSettings(presetOrReject(v)); });
  // validate() checks each setting on its own, so a valid state after every assignment is a
  // valid final one.
  auto given = std::make_shared<std::vector<SettingId>>();  // the settings --set named, in order
  cl.value("--set", "NAME=VALUE", setHelp, [&settings, given](const std::string& v) {
    if (Status s = setFromAssignment(settings, v); !s) reject(s.message);
    if (Status s = validate(settings); !s) reject(s.message);
    given->push_back(*findSetting(v.substr(0, v.find('='))));
  });
  // A setting given that the final settings (the preset's and every --set, and what a program's
  // own options set after them) make inert is refused; a preset's values never are.
  cl.check([&settings, given] {
    if (Status s = checkRefusals(settings); !s) reject(s.message);
    for (SettingId id : *given)
      if (const gen::InertRule* rule = inertRule(settings, id)) reject("--set " + describeInert(*rule));
  });
}

CLI::Option* addPresetList(CommandLine& cl, std::vector<Preset>& target) {
  return cl.value("--preset", "NAME", presetNames(" | ") + ", or all (repeatable; default: all)",
                  [&target](const std::string& v) {
                    auto add = [&target](Preset p) {  // once each, in the order given
                      if (std::find(target.begin(), target.end(), p) == target.end()) target.push_back(p);
                    };
                    if (v != "all") return add(presetOrReject(v));
                    for (const PresetInfo& p : presets()) add(p.preset);
                  });
}

CLI::Option* addDepthFormat(CommandLine& cl, const std::string& name, DepthFormat& target, const std::string& help) {
  auto parse = [](std::string v) -> std::optional<DepthFormat> {
    std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return char(std::toupper(c)); });
    if (v == "D16") return DepthFormat::D16;
    if (v == "D24") return DepthFormat::D24;
    if (v == "D32F") return DepthFormat::D32F;
    return std::nullopt;
  };
  return cl.choice(name, target, parse, "D16, D24 or D32F", "F", help);
}

}  // namespace sao::cli
