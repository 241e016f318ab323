#include "sao/status.h"
#include "sao/timing.h"
#include "sao/version.h"

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

const char* toString(TimingMethod method) {
  switch (method) {
    case TimingMethod::None: return "none";
    case TimingMethod::GpuTimestamps: return "GPU timestamps";
    case TimingMethod::FinishAndClock: return "finish + steady clock";
    case TimingMethod::CpuClock: return "CPU steady clock";
  }
  return "?";
}

int libraryVersion() { return SAO_VERSION; }

}  // namespace sao
