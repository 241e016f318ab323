// Diagnostics as values: every error names a place in the annotated source.
#pragma once
#include <string>
#include <vector>

namespace sao::codegen {

struct SourceLoc {
  std::string file;  // as the user named it (entry) or joined from the including file
  int line = 0;      // 1-based; 0 = the file as a whole
};

struct Diagnostic {
  SourceLoc loc;
  std::string severity;  // "error" or "warning"
  std::string message;
  std::string format() const;  // "path:line: error: message"
};

class Diagnostics {
 public:
  void error(const SourceLoc& loc, std::string message);
  void warning(const SourceLoc& loc, std::string message);
  bool hasErrors() const { return errorCount_ > 0; }
  const std::vector<Diagnostic>& all() const { return items_; }
  void append(const Diagnostics& other) {  // other's diagnostics after these (repeats dropped)
    for (const Diagnostic& d : other.items_) add(d);
  }

 private:
  void add(Diagnostic d);
  std::vector<Diagnostic> items_;
  int errorCount_ = 0;
};

}  // namespace sao::codegen
