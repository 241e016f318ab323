// Writes all outputs or none: files are staged in a temporary folder and moved into place only
// when every one was written.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace sao::codegen {

class OutputSet {
 public:
  void add(std::string name, std::string content) { files_.emplace_back(std::move(name), std::move(content)); }
  // Returns an error message, or empty on success.
  std::string commit(const std::string& dir) const;

 private:
  std::vector<std::pair<std::string, std::string>> files_;
};

// Make-style depfile: "<target>: <deps...>" with spaces escaped.
std::string makeDepfile(const std::string& target, const std::vector<std::string>& deps);

}  // namespace sao::codegen
