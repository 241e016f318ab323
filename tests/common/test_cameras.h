// The backend tests' perspective cameras: 60-degree vertical field of view, near 0.1, a guard band
// of `guard` texels, far `farDistance` (inf: infinite).
#pragma once
#include <cstdint>
#include <numbers>

#include "sao/camera.h"

namespace sao::test {

// OpenGL's clip depth range [-1, 1].
inline Camera openglCamera(std::uint32_t width, std::uint32_t height, std::uint32_t guard, double farDistance = 1000.0,
                           bool reversedZ = false) {
  Camera c = perspectiveCamera(std::numbers::pi / 3.0, width, height, 0.1, farDistance, ClipDepth::NegativeOneToOne,
                               reversedZ);
  c.guardBand = guard;
  return c;
}

// Vulkan's clip depth range [0, 1]; flipY for a negative-height viewport.
inline Camera vulkanCamera(std::uint32_t width, std::uint32_t height, std::uint32_t guard, double farDistance = 100.0,
                           bool reversedZ = false, bool flipY = false) {
  Camera c = perspectiveCamera(std::numbers::pi / 3.0, width, height, 0.1, farDistance, ClipDepth::ZeroToOne, reversedZ);
  c.guardBand = guard;
  c.flipY = flipY;
  return c;
}

}  // namespace sao::test
