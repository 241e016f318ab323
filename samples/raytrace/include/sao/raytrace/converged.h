// Reference (c): the converged screen-space estimator. The effect's own estimator (AlchemyAO eq. 10
// with its radius cut, docs/effect-math.md "ao_sample") on the effect's own inputs, integrated
// instead of sampled: every tap reads csz level 0 (no MIP levels), no 2x2 reconstruction, no blur,
// all in double. The error of the effect against (c) is what taps, MIP use, blur and resolution
// trade; (c) against the ray-traced references (a) and (b) is the model error no preset can change
// (docs/reference.md, "Reference (c)").
#pragma once
#include <cstdint>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/settings.h"
#include "sao/status.h"

namespace sao::raytrace {

// The effect's inputs, as a backend takes them (viewport + 2 * guard band, the camera's conventions).
struct ConvergedInputs {
  const DepthImage* depth = nullptr;    // required: hardware depth or LinearZ
  const DepthImage* depth2 = nullptr;   // optional second layer (TWO_LAYER): same extent and format
  const FloatImage* normals = nullptr;  // optional camera-space normals (NORMALS_SUPPLIED), >= 3
                                        // channels, read rounded to binary16 as the rgba16f texture
};

// The tap pattern: `rings` radial strata, ring j at r'(j + u)/rings with u uniform in [0, 1) per
// pixel and ring (the spiral's radii (i + 0.5)/s, uniform in radius, jittered within their
// strata), each ring with taps in proportion to its mean radius (at least kMinRingTaps) at equal
// angles under a random rotation. About `taps` taps per pixel in all. The radial strata matter
// most: at 4096 taps, 128 rings leave 2/3 of the noise of 64 (docs/reference.md).
struct ConvergedOptions {
  std::uint32_t rings = 128;
  std::uint32_t taps = 4096;
  std::uint64_t seed = 1;  // the result is a pure function of (inputs, settings, camera, options)
  unsigned threads = 0;    // 0: one per hardware thread
};

inline constexpr std::uint32_t kMinRingTaps = 8;

// `ao`: camera.width x camera.height, 1 channel, A = max(0, 1 - 2 sigma r E[term])^k per pixel
// (sky: 1), E over the spiral's tap distribution (uniform in radius and angle within r', each tap
// truncated to a texel as the effect's int() does). Uses the settings the estimator depends on
// (radius, intensity, bias, epsilon, contrast) and ignores the rest (samples, MIP, blur). Errors:
// the core's for bad settings or camera, InvalidInput for a missing depth, inputs whose extent or
// format disagree, or rings == 0 or taps < rings.
Status convergedEstimator(const Settings& settings, const Camera& camera, const ConvergedInputs& inputs,
                          const ConvergedOptions& options, FloatImage& ao);

}  // namespace sao::raytrace
