#include "sao/cli/command_line.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <CLI/CLI.hpp>

namespace sao::cli {
namespace {

constexpr std::size_t kHelpWidth = 100;  // columns of --help
constexpr std::size_t kNameWidth = 24;   // the option names' column

// `text` wrapped at `width` columns; its own line breaks are kept.
std::string wrapped(const std::string& text, std::size_t width) {
  std::string out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line;
    std::size_t word = start;
    while (word < end) {
      std::size_t space = text.find(' ', word);
      if (space == std::string::npos || space > end) space = end;
      const std::string w = text.substr(word, space - word);
      if (!line.empty() && line.size() + 1 + w.size() > width) out += line + "\n", line.clear();
      line += (line.empty() ? "" : " ") + w;
      word = space + 1;
    }
    out += line;
    if (end < text.size()) out += "\n";
    start = end + 1;
  }
  return out;
}

// "usage: TOOL [options]", the description, the options (names and placeholders in 24 columns,
// descriptions wrapped at 100) and the footer.
class Formatter : public CLI::Formatter {
 public:
  Formatter() { column_width(kNameWidth); }
  std::string make_option_desc(const CLI::Option* option) const override {
    return wrapped(option->get_description(), kHelpWidth - kNameWidth);
  }
  std::string make_usage(const CLI::App*, std::string name) const override { return "usage: " + name + " [options]\n"; }
  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override {
    std::string help = make_usage(app, name) + app->get_description() + "\n" + make_groups(app, mode);
    const std::string footer = app->get_footer();
    return footer.empty() ? help : help + "\n" + footer;
  }
};

std::string quoted(const std::string& text) { return "'" + text + "'"; }

// CLI11's own errors in the words of ours (our checks throw their messages ready). With every
// value option taking a string, CLI11 itself refuses only a missing value ("NAME: 1 required
// TYPE missing") and a flag given a value it cannot read ("Could not convert: NAME = VALUE").
std::string explained(const CLI::ParseError& e) {
  const std::string what = e.what();
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
    const auto colon = what.find(": ");
    if (colon != std::string::npos && what.find(" required ", colon) != std::string::npos)
      return what.substr(0, colon) + " needs a value";
  }
  if (dynamic_cast<const CLI::ConversionError*>(&e)) {
    const std::string prefix = "Could not convert: ";
    const auto equals = what.find(" = ");
    if (what.starts_with(prefix) && equals != std::string::npos)
      return what.substr(prefix.size(), equals - prefix.size()) + " takes no value (or true or false), got " +
             quoted(what.substr(equals + 3));
  }
  return what;
}

}  // namespace

void reject(const std::string& message) { throw CLI::ValidationError(message); }

void exitWithUsageError(std::string_view tool, const std::string& message) {
  std::fprintf(stderr, "%.*s: %s (see --help)\n", int(tool.size()), tool.data(), message.c_str());
  std::exit(2);
}

std::uint32_t parseWhole(std::string_view option, const std::string& text, std::uint32_t lo, std::uint32_t hi) {
  long long n = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, n);
  if (text.empty() || ec != std::errc() || ptr != end || n < lo || n > hi)
    reject(std::string(option) + " expects a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
           "], got " + quoted(text));
  return std::uint32_t(n);
}

double parseNumber(std::string_view option, const std::string& text) {
  double d = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, d);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(d))
    reject(std::string(option) + " expects a finite number, got " + quoted(text));
  return d;
}

Extent parseSize(std::string_view option, const std::string& text, std::uint32_t lo, std::uint32_t hi) {
  const auto x = text.find('x');
  if (x == std::string::npos) reject(std::string(option) + " expects WxH, got " + quoted(text));
  return {parseWhole(std::string(option) + " width", text.substr(0, x), lo, hi),
          parseWhole(std::string(option) + " height", text.substr(x + 1), lo, hi)};
}

CommandLine::~CommandLine() = default;

bool CommandLine::given(const std::string& name) const { return app_->count(name) > 0; }

CommandLine::CommandLine(std::string tool, std::string description, std::string footer)
    : tool_(std::move(tool)), app_(std::make_unique<CLI::App>(std::move(description), tool_)) {
  app_->formatter(std::make_shared<Formatter>());
  app_->footer(std::move(footer));
  app_->option_defaults()->group("options");
  app_->allow_extras();  // reported by parse() in the tool's own words
  app_->set_help_flag();  // added last, in parse(), to be listed last
}

CLI::Option* CommandLine::value(const std::string& name, const std::string& valueName, const std::string& help,
                                std::function<void(const std::string&)> apply) {
  CLI::Option* option = app_->add_option(
      name,
      [name, apply = std::move(apply)](const CLI::results_t& values) {
        for (const std::string& v : values) {
          if (v.empty()) reject(name + " needs a value, got an empty string");
          apply(v);
        }
        return true;
      },
      help);
  // Every value reaches `apply`, so each is checked even when a later one replaces it.
  option->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->option_text(valueName);
  return option;
}

CLI::Option* CommandLine::text(const std::string& name, std::string& target, const std::string& valueName,
                               const std::string& help) {
  return value(name, valueName, help, [&target](const std::string& v) { target = v; });
}

CLI::Option* CommandLine::whole(const std::string& name, std::uint32_t& target, std::uint32_t lo, std::uint32_t hi,
                                const std::string& valueName, const std::string& help) {
  return value(name, valueName, help,
               [name, &target, lo, hi](const std::string& v) { target = parseWhole(name, v, lo, hi); });
}

CLI::Option* CommandLine::size(const std::string& name, Extent& target, std::uint32_t lo, std::uint32_t hi,
                               const std::string& help) {
  return value(name, "WxH", help,
               [name, &target, lo, hi](const std::string& v) { target = parseSize(name, v, lo, hi); });
}

CLI::Option* CommandLine::flag(const std::string& name, bool& target, const std::string& help) {
  return app_->add_flag(name, target, help);
}

void CommandLine::parse(int argc, char** argv) {
  app_->set_help_flag("-h,--help", "this text");
  try {
    app_->parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app_->help().c_str(), stdout);
    std::exit(std::fflush(stdout) == 0 && !std::ferror(stdout) ? 0 : 1);
  } catch (const CLI::ParseError& e) {
    fail(explained(e));
  }
  const std::vector<std::string> extra = app_->remaining();
  if (!extra.empty())
    fail(extra.front().starts_with("-") ? "unknown option " + quoted(extra.front())
                                        : "unexpected argument " + quoted(extra.front()) + " (options start with --)");
  try {
    for (const auto& check : checks_) check();
  } catch (const CLI::ParseError& e) {
    fail(e.what());
  }
}

std::set<std::string> CommandLine::givenNames() const {
  std::set<std::string> names;
  for (const CLI::Option* option : app_->get_options())
    if (option->count() > 0) names.insert(option->get_name());
  return names;
}

}  // namespace sao::cli
