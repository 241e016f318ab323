// The names and rules of a depth EXR; see depth_exr_format.h.
#include "depth_exr_format.h"

namespace sao::io::detail {

const char* formatName(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return "D16";
    case DepthFormat::D24: return "D24";
    case DepthFormat::D32F: return "D32F";
    case DepthFormat::LinearZ: return "LinearZ";
  }
  return nullptr;
}

std::optional<DepthFormat> parseFormat(const std::string& s) {
  for (DepthFormat f : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ})
    if (s == formatName(f)) return f;
  return std::nullopt;
}

const char* kindName(ProjectionKind k) {
  switch (k) {
    case ProjectionKind::Perspective: return "perspective";
    case ProjectionKind::Orthographic: return "orthographic";
  }
  return nullptr;
}

const char* clipName(ClipDepth c) {
  switch (c) {
    case ClipDepth::NegativeOneToOne: return "negativeOneToOne";
    case ClipDepth::ZeroToOne: return "zeroToOne";
  }
  return nullptr;
}

std::uint32_t integerMax(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16: return 0xffffu;
    case DepthFormat::D24: return 0xffffffu;
    default: return 0;
  }
}

bool extentMatches(Extent e, std::uint64_t width, std::uint64_t height, std::uint64_t guard) {
  return std::uint64_t(e.width) == width + 2 * guard && std::uint64_t(e.height) == height + 2 * guard;
}

std::string extentMismatch(Extent e, std::uint64_t width, std::uint64_t height, std::uint64_t guard) {
  return "depth image is " + std::to_string(e.width) + "x" + std::to_string(e.height) + ", but the camera's " +
         std::to_string(width) + "x" + std::to_string(height) + " viewport with a guard band of " +
         std::to_string(guard) + " needs " + std::to_string(width + 2 * guard) + "x" + std::to_string(height + 2 * guard);
}

}  // namespace sao::io::detail
