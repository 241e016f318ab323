// What the walkthrough test renders on OpenGL and on the CPU reference, both built against the
// extended effect: one analytic scene, one camera, two settings.
#pragma once
#include <array>
#include <cstdint>

#include "analytic_scenes.h"
#include "test_cameras.h"

namespace sao::walkthrough {

inline constexpr std::uint32_t kWidth = 64, kHeight = 48, kGuard = 8;

// With the view (identity: a camera that does not move), which temporal accumulation needs.
inline Camera caseCamera() {
  Camera c = test::openglCamera(kWidth, kHeight, kGuard);
  c.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  return c;
}

inline DepthImage caseDepth() {
  return test::renderDepth(test::sphereOnPlaneScene(), caseCamera(), DepthFormat::D32F);
}

struct Case {
  const char* name;
  Settings settings;
};

// Blurred (ao_halve reads ao_low), and blur_radius 0 with temporal accumulation (the blur is
// skipped and ao_halve reads ao_raw through its alias_when; without temporal, ao_sample_output
// would write the output and ao_halve, which has nothing to read then, would be skipped).
inline std::array<Case, 2> cases() {
  // The medium preset of 2026-12-03 (16 taps, 5-tap blur), spelled out: the GL = CPU bit-for-bit
  // check below holds for it (at 24 taps two texels of this scene land one binary16 step apart,
  // within the reference tests' 2/255 but not bit for bit).
  Settings medium;
  medium.samples = 16;
  medium.blur_radius = 2;
  medium.resolution_divisor = 1;  // the new pass reads ao_low at the output's size: full resolution
  Settings unblurred = medium;
  unblurred.blur_radius = 0;
  unblurred.temporal = true;
  return {Case{"medium", medium}, Case{"blur_radius_0", unblurred}};
}

}  // namespace sao::walkthrough
