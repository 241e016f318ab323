// The whole effect at the extremes of cameras, units, settings and inputs, on every backend (one
// file per suite in this folder): sky frames, sub-pixel and off-screen radii, world scale, every
// setting at both ends of its range, NaN / Inf / out-of-range / denormal depth, walls facing the
// camera and at grazing incidence, depth discontinuities, and the near / far grid. Every run is
// checked by runCase (finite, in [0, 1], sky = 1, GL = Vulkan within 1/255); each test adds its own
// bound. This header holds what several suites share.
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "stability_support.h"

namespace sao::stability {

inline constexpr double kInf = INFINITY;
inline constexpr double k255 = 1.0 / 255.0;

// The depth conventions every case loops over.
struct Conv {
  const char* name;
  ClipDepth clip;
  bool reversed;
  double far;
};
inline constexpr Conv kConvs[] = {
    {"standard [-1,1] far 1e4", ClipDepth::NegativeOneToOne, false, 1e4},
    {"standard [-1,1] infinite", ClipDepth::NegativeOneToOne, false, kInf},
    {"standard [0,1] infinite", ClipDepth::ZeroToOne, false, kInf},
    {"reversed [0,1] far 1e4", ClipDepth::ZeroToOne, true, 1e4},
    {"reversed [0,1] infinite", ClipDepth::ZeroToOne, true, kInf},
    {"reversed [-1,1] infinite (no clip control)", ClipDepth::NegativeOneToOne, true, kInf},
};

// A camera for a convention: perspective 60°, near 0.1 m (or orthographic over 0.1 .. 100 m when
// `ortho`; an orthographic camera has no infinite far plane, so 1e4 is used there).
Camera convCamera(const Conv& cv, std::uint32_t w, std::uint32_t h, std::uint32_t guard, bool ortho = false,
                  double orthoHalfHeight = 3.0);

// One analytic scene through every backend, with what the checks need to know about it.
struct SceneRun {
  DepthImage depth;
  std::vector<bool> sky;
  std::vector<double> z;  // analytic z per AO pixel (0 = sky)
  CaseRuns runs;
};
// Renders the scene's GPU depth in `format` and runs the case on it with the scene's sky mask.
SceneRun runScene(const std::string& label, const Settings& settings, const Camera& cam, const test::Scene& scene,
                  DepthFormat format, CaseOptions opt = {});

std::vector<bool> notMask(const std::vector<bool>& m);

// The depth formats and conventions of the wall and discontinuity cases.
struct WallSetup {
  const char* name;
  DepthFormat fm;
  ClipDepth clip;
  bool reversed;
};
inline constexpr WallSetup kWallSetups[] = {
    {"D16 standard [-1,1]", DepthFormat::D16, ClipDepth::NegativeOneToOne, false},
    {"D24 standard [-1,1]", DepthFormat::D24, ClipDepth::NegativeOneToOne, false},
    {"D32F standard [0,1]", DepthFormat::D32F, ClipDepth::ZeroToOne, false},
    {"D32F reversed [0,1]", DepthFormat::D32F, ClipDepth::ZeroToOne, true},
    {"R32F linear z", DepthFormat::LinearZ, ClipDepth::ZeroToOne, true},
};

}  // namespace sao::stability
