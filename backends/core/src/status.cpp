#include "sao/status.h"

namespace sao {

const char* toString(StatusCode code) {
  switch (code) {
    case StatusCode::Ok: return "ok";
    case StatusCode::InvalidSetting: return "invalid setting";
    case StatusCode::InvalidCamera: return "invalid camera";
    case StatusCode::InvalidExtent: return "invalid extent";
    case StatusCode::InvalidInput: return "invalid input";
    case StatusCode::UnsupportedFormat: return "unsupported format";
    case StatusCode::IoError: return "I/O error";
    case StatusCode::DriverError: return "driver error";
    case StatusCode::VersionMismatch: return "version mismatch";
  }
  return "unknown status";
}

}  // namespace sao
