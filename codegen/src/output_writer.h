// Writes all outputs or none: files are staged in a temporary folder and moved into place only
// when every one was written. The project's rule for every writer (docs/ROBUSTNESS.md, "Files of
// the user's") holds here too: a file sao-shaderc did not write is replaced only with --overwrite
// (what it wrote is listed in the folder's sao-shaderc-outputs.txt), and an input never.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace sao::codegen {

// The list of what sao-shaderc wrote into a folder, one name a line.
inline constexpr const char* kOutputsManifest = "sao-shaderc-outputs.txt";

struct WriteRules {
  bool overwrite = false;           // --overwrite: replace files of the same names it did not write
  std::vector<std::string> inputs;  // the effect and its includes: never written onto
};

class OutputSet {
 public:
  void add(std::string name, std::string content) { files_.emplace_back(std::move(name), std::move(content)); }
  // Returns an error message, or empty on success; on error nothing in `dir` has changed.
  std::string commit(const std::string& dir, const WriteRules& rules) const;

 private:
  std::vector<std::pair<std::string, std::string>> files_;
};

// Make-style depfile: "<target>: <deps...>" with spaces escaped.
std::string makeDepfile(const std::string& target, const std::vector<std::string>& deps);

}  // namespace sao::codegen
