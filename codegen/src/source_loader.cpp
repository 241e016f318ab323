#include "source_loader.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace sao::codegen {
namespace {

namespace fs = std::filesystem;

class Loader {
 public:
  Loader(LoadedSource& out, Diagnostics& diags) : out_(out), diags_(diags) {}

  void load(const std::string& path, const SourceLoc& includedFrom) {
    const std::string key = fs::weakly_canonical(fs::path(path)).string();
    for (size_t i = 0; i < stack_.size(); ++i) {
      if (stack_[i].first != key) continue;
      std::string chain;
      for (size_t j = i; j < stack_.size(); ++j) chain += stack_[j].second + " -> ";
      diags_.error(includedFrom, "include cycle: " + chain + path);
      return;
    }
    std::error_code ec;
    const fs::file_type type = fs::status(path, ec).type();
    if (type == fs::file_type::directory) {
      diags_.error(includedFrom, "'" + path + "' is a directory, not a source file");
      return;
    }
    // A FIFO or a device (an include of "/dev/zero", "/dev/stdin") would block or never end.
    if (type != fs::file_type::regular && type != fs::file_type::not_found && type != fs::file_type::none) {
      diags_.error(includedFrom, "'" + path + "' is not a regular file");
      return;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      diags_.error(includedFrom, stack_.empty() ? "cannot open effect file '" + path + "'"
                                                : "cannot open include file '" + path + "'");
      return;
    }
    out_.files.push_back(path);
    stack_.emplace_back(key, path);
    std::string text;
    int lineNo = 0;
    static const std::regex includeRe(R"re(^\s*#\s*include\s*(.*)$)re");
    static const std::regex quotedRe(R"re(^"([^"]+)"\s*(//.*)?$)re");
    static const std::regex versionRe(R"(^\s*#\s*version\b.*$)");
    static const std::regex includeExtRe(R"(^\s*#\s*extension\s+GL_GOOGLE_include_directive\b.*$)");
    while (std::getline(in, text)) {
      ++lineNo;
      if (!text.empty() && text.back() == '\r') text.pop_back();
      const SourceLoc here{path, lineNo};
      std::smatch m;
      if (std::regex_match(text, m, includeRe)) {
        std::smatch q;
        const std::string rest = m[1].str();
        if (!std::regex_match(rest, q, quotedRe)) {
          diags_.error(here, "malformed #include: expected #include \"file\"");
          continue;
        }
        const fs::path target = fs::path(path).parent_path() / q[1].str();
        load(target.lexically_normal().string(), here);
        continue;
      }
      if (std::regex_match(text, versionRe) || std::regex_match(text, includeExtRe)) continue;
      out_.lines.push_back({text, here});
    }
    stack_.pop_back();
  }

 private:
  LoadedSource& out_;
  Diagnostics& diags_;
  std::vector<std::pair<std::string, std::string>> stack_;  // canonical key, display path
};

}  // namespace

LoadedSource loadSource(const std::string& entryPath, Diagnostics& diags) {
  LoadedSource out;
  Loader(out, diags).load(entryPath, SourceLoc{entryPath, 0});
  return out;
}

}  // namespace sao::codegen
