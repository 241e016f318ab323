// The command line of sao's programs (sao-render, sao-bench, sao-viewer, sao-gl-timing,
// sao-vk-timing) on CLI11: every value is checked where it is declared, every error is one line
// "TOOL: MESSAGE (see --help)" with exit status 2, and --help is generated from the declarations.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "sao/plan.h"

// CLI11 stays inside command_line.cpp: the header is heavy (tens of seconds per translation unit,
// more under the sanitizers), and callers only pass option handles through.
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace sao::cli {

// Refuses a value: `message` names the option and the value ("--runs expects a whole number in
// [1, 1000], got '0'"). Throws CLI::ValidationError; CommandLine::parse prints it as is.
[[noreturn]] void reject(const std::string& message);

// Checked conversions; on a bad value they reject() with a message naming `option`.
// A whole number in [lo, hi] (no sign for lo >= 0, no spaces, no overflow).
std::uint32_t parseWhole(std::string_view option, const std::string& text, std::uint32_t lo, std::uint32_t hi);
// A finite number.
double parseNumber(std::string_view option, const std::string& text);
// WxH, each side in [lo, hi]: "--size width expects a whole number in [1, 16384], got '0'".
Extent parseSize(std::string_view option, const std::string& text, std::uint32_t lo, std::uint32_t hi);

// "TOOL: MESSAGE (see --help)" on stderr, exit status 2.
[[noreturn]] void exitWithUsageError(std::string_view tool, const std::string& message);

class CommandLine {
 public:
  // `description`: the paragraph under "usage: TOOL [options]"; `footer`: the text after the options.
  CommandLine(std::string tool, std::string description, std::string footer = {});
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  // An option with a value. `apply` gets every value given, in order, after the empty-string
  // check; it assigns (the last one given counts) or appends (a repeatable option) and calls
  // reject() for a bad value. `valueName` is the placeholder in --help ("N", "WxH").
  CLI::Option* value(const std::string& name, const std::string& valueName, const std::string& help,
                     std::function<void(const std::string&)> apply);
  CLI::Option* text(const std::string& name, std::string& target, const std::string& valueName,
                    const std::string& help);
  CLI::Option* whole(const std::string& name, std::uint32_t& target, std::uint32_t lo, std::uint32_t hi,
                     const std::string& valueName, const std::string& help);
  CLI::Option* size(const std::string& name, Extent& target, std::uint32_t lo, std::uint32_t hi,
                    const std::string& help);
  CLI::Option* flag(const std::string& name, bool& target, const std::string& help);

  // One of a set of words: `parse` returns std::nullopt for an unknown one, refused as
  // "NAME expects EXPECTED, got 'VALUE'". `target` may be a T or a std::optional<T>.
  template <class Target, class Parse>
  CLI::Option* choice(const std::string& name, Target& target, Parse parse, std::string expected,
                      const std::string& valueName, const std::string& help) {
    return value(name, valueName, help, [name, &target, parse, expected](const std::string& v) {
      const auto parsed = parse(v);
      if (!parsed) reject(name + " expects " + expected + ", got '" + v + "'");
      target = *parsed;
    });
  }

  // A check across options, run by parse() after every option's own (in the order added): it
  // sees the final values and calls reject() to refuse them.
  void check(std::function<void()> check) { checks_.push_back(std::move(check)); }

  // Parses argv and runs every option's check. --help prints the help on stdout and exits 0; a
  // bad option prints one line on stderr and exits 2.
  void parse(int argc, char** argv);

  bool given(const std::string& name) const;
  std::set<std::string> givenNames() const;  // every option on the command line
  [[noreturn]] void fail(const std::string& message) const { exitWithUsageError(tool_, message); }

 private:
  std::string tool_;
  std::unique_ptr<CLI::App> app_;
  std::vector<std::function<void()>> checks_;
};

}  // namespace sao::cli
