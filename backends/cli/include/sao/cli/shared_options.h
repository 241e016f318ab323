// The options two or more of sao's programs share, each declared once with its limits, so that
// sao-render, sao-bench, sao-viewer and the timing tools check them alike.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/cli/command_line.h"
#include "sao/image.h"
#include "sao/presets.h"
#include "sao/settings.h"

namespace sao::cli {

inline constexpr std::uint32_t kMaxRuns = 1000;         // --runs
inline constexpr std::uint32_t kMaxRays = 65536;        // rays per pixel of a ray-traced reference
inline constexpr std::uint32_t kMaxGuardBand = 4096;    // --guard, pixels on each side
inline constexpr std::uint32_t kMaxViewNumber = 1000;   // --view

// --size WxH: each side 1..kMaxImageSide (sao/plan.h, the largest image the plan accepts).
// `help` says what the size is of; the range and `note` (a default) follow it.
CLI::Option* addImageSize(CommandLine& cl, Extent& target, const std::string& help, const std::string& note);
// --size WxH, repeatable: a list of sizes, each checked as above.
CLI::Option* addImageSizes(CommandLine& cl, std::vector<Extent>& target, const std::string& help,
                           const std::string& note);

// The next three: `help` says what the number is, the range and `note` (a default) follow it.
// --runs N: measured runs, minRuns..kMaxRuns.
CLI::Option* addRuns(CommandLine& cl, std::uint32_t& target, std::uint32_t minRuns, const std::string& help,
                     const std::string& note);
// `name` N: rays per pixel of a ray-traced reference, 1..kMaxRays.
CLI::Option* addRays(CommandLine& cl, const std::string& name, std::uint32_t& target, const std::string& help,
                     const std::string& note);
// --guard N: a guard band of 0..kMaxGuardBand pixels on each side.
CLI::Option* addGuardBand(CommandLine& cl, std::uint32_t& target, const std::string& help, const std::string& note);

// --view N: a scene's view number, 0..kMaxViewNumber (the scene says later whether it has it).
CLI::Option* addViewNumber(CommandLine& cl, std::uint32_t& target);

// --preset NAME and --set NAME=VALUE (repeatable) into `settings`: the preset first, then each
// assignment in order, each checked against its range (sao::setFromAssignment), then the whole
// validated. `setHelp` describes --set.
void addSettings(CommandLine& cl, Settings& settings, const std::string& setHelp);

// --preset NAME|all, repeatable: a list of presets (all of them for "all").
CLI::Option* addPresetList(CommandLine& cl, std::vector<Preset>& target);

// `name` F: a depth format D16 | D24 | D32F (any case).
CLI::Option* addDepthFormat(CommandLine& cl, const std::string& name, DepthFormat& target, const std::string& help);

}  // namespace sao::cli
