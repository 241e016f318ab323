#include "sao/scenes/camera_path.h"

#include <array>
#include <cmath>
#include <numbers>

namespace sao::scenes {
namespace {

constexpr std::array<std::string_view, 3> kNames = {"orbit", "dolly", "strafe"};

// The path parameter of a frame: -1 at frame 0, +1 at the last frame (frames > 1).
double pathParameter(std::uint32_t frame, std::uint32_t frames) {
  return -1.0 + 2.0 * double(frame) / double(frames - 1);
}

}  // namespace

std::span<const std::string_view> pathNames() { return kNames; }

std::string_view toString(PathKind kind) { return kNames[static_cast<std::size_t>(kind)]; }

std::optional<PathKind> parsePathKind(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (name == kNames[i]) return static_cast<PathKind>(i);
  return std::nullopt;
}

View pathView(const View& base, PathKind kind, std::uint32_t frame, std::uint32_t frames) {
  if (frames <= 1) return base;
  const double t = pathParameter(frame, frames);
  View v = base;
  const glm::dvec3 toEye = base.eye - base.target;
  switch (kind) {
    case PathKind::Orbit: {
      const double a = t * (15.0 * std::numbers::pi / 180.0);
      const double c = std::cos(a), s = std::sin(a);
      v.eye = base.target + glm::dvec3(c * toEye.x + s * toEye.z, toEye.y, -s * toEye.x + c * toEye.z);
      break;
    }
    case PathKind::Dolly: {
      const double keep = 1.0 - 0.2 * (t + 1.0);  // 1 at frame 0, 0.6 at the last
      v.eye = base.target + keep * toEye;
      break;
    }
    case PathKind::Strafe: {
      const glm::dvec3 forward = -toEye;
      const glm::dvec3 side = glm::normalize(glm::cross(forward, glm::dvec3(0, 1, 0)));
      const glm::dvec3 offset = side * (0.15 * t * glm::length(toEye));
      v.eye = base.eye + offset;
      v.target = base.target + offset;
      break;
    }
  }
  return v;
}

}  // namespace sao::scenes
