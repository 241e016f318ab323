#include "diagnostics.h"

#include <algorithm>

namespace sao::codegen {

std::string Diagnostic::format() const {
  std::string out = loc.file;
  if (loc.line > 0) out += ":" + std::to_string(loc.line);
  out += ": " + severity + ": " + message;
  return out;
}

void Diagnostics::error(const SourceLoc& loc, std::string message) {
  add({loc, "error", std::move(message)});
}

void Diagnostics::warning(const SourceLoc& loc, std::string message) {
  add({loc, "warning", std::move(message)});
}

void Diagnostics::add(Diagnostic d) {
  while (!d.message.empty() && (d.message.back() == ' ' || d.message.back() == '\t')) d.message.pop_back();
  // The same GLSL error shows up once per pass and variant; report it once.
  const std::string text = d.format();
  if (std::any_of(items_.begin(), items_.end(), [&](const Diagnostic& x) { return x.format() == text; }))
    return;
  if (d.severity == "error") ++errorCount_;
  items_.push_back(std::move(d));
}

}  // namespace sao::codegen
