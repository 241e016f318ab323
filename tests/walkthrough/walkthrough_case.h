// What the walkthrough test renders on OpenGL and on the CPU reference, both built against the
// extended effect: one analytic scene, one camera, two settings.
#pragma once
#include <array>
#include <cstdint>

#include "analytic_scenes.h"
#include "sao/presets.h"
#include "test_cameras.h"

namespace sao::walkthrough {

inline constexpr std::uint32_t kWidth = 64, kHeight = 48, kGuard = 8;

inline Camera caseCamera() { return test::openglCamera(kWidth, kHeight, kGuard); }

inline DepthImage caseDepth() {
  return test::renderDepth(test::sphereOnPlaneScene(), caseCamera(), DepthFormat::D32F);
}

struct Case {
  const char* name;
  Settings settings;
};

// Blurred (ao_halve reads ao_low), and blur_radius 0 (the blur is skipped and ao_halve reads
// ao_raw through its alias_when).
inline std::array<Case, 2> cases() {
  Settings medium = presetSettings(Preset::Medium);
  medium.resolution_divisor = 1;  // the new pass reads ao_low at the output's size: full resolution
  Settings unblurred = medium;
  unblurred.blur_radius = 0;
  return {Case{"medium", medium}, Case{"blur_radius_0", unblurred}};
}

}  // namespace sao::walkthrough
