// Every fallible call returns a Status: a code to branch on and a message that names the problem.
#pragma once
#include <string>
#include <utility>

namespace sao {

enum class StatusCode {
  Ok,
  InvalidSetting,     // a setting out of range, NaN or infinite
  InvalidCamera,      // a projection that contradicts its declared convention
  InvalidExtent,      // zero or too large image sizes
  InvalidInput,       // bad handles, missing inputs, inputs that contradict the plan
  UnsupportedFormat,  // a texture or file format the effect cannot read
  IoError,            // files that cannot be read or written, malformed files
  DriverError,        // the graphics API failed or is missing
  VersionMismatch,    // header and library versions differ
};

struct [[nodiscard]] Status {
  StatusCode code = StatusCode::Ok;
  std::string message;

  bool ok() const { return code == StatusCode::Ok; }
  explicit operator bool() const { return ok(); }
  static Status success() { return {}; }
  static Status error(StatusCode code, std::string message) { return {code, std::move(message)}; }
};

const char* toString(StatusCode code);

}  // namespace sao
