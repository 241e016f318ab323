// Reference (d): converged screen-space visibility (issue 40, /work/notes/EST_SPEC.md). The
// cosine-weighted fraction of directions from each pixel's point that travel the radius r without
// passing through the solid slab of finite thickness T behind a stored depth sample: what a
// screen-space estimator that sees one depth layer (or two, TWO_LAYER) can converge to at best.
// Same inputs as reference (c) (converged.h): the effect's depth, optional second layer, supplied
// or rebuilt normals, the effect's own formulas from effect/cpu/sao_math.h in double. Its error
// against (a) is what screen space cannot see; (c) against it is the estimator's definition
// (docs/reference.md, "Reference (d)").
#pragma once
#include <cstdint>
#include <optional>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/raytrace/converged.h"
#include "sao/settings.h"
#include "sao/status.h"

namespace sao::raytrace {

struct ScreenVisibilityOptions {
  // Slices per pixel: screen directions phi = pi (k + xi) / slices, xi uniform in [0, 1) per pixel.
  // Each slice's two sides are marched at every pixel h = 1, 2, ... <= r' and the covered angles
  // integrated exactly (a sorted union), so the slice count is the only sampling: 64 slices leave
  // an error of about 1e-3 on the closed-form crease (docs/reference.md).
  std::uint32_t slices = 64;
  // T and tol of the definition: unset, the settings' `thickness` (metres) and `depth_tolerance`
  // (unitless, relative to depth), those the visibility estimator uses; set, these instead (T may
  // then be +infinity: a pure heightfield, beyond the setting's range). T is converted to view units
  // with Camera::metersToViewUnits like the radius.
  std::optional<double> thicknessMeters;
  std::optional<double> tolerance;
  // Thickness from width (docs/reference.md, "A thickness model"; unset: the setting thickness_model,
  // 1 = on, what the visibility estimator approximates with probes): off, every slab is T deep; on,
  // each run of continuous depth along a slice's line (consecutive texels whose depths differ by at
  // most widthJump of the depth; the line marched to 2 r' for this) is taken as deep as widthScale
  // times its width (the distance between its ends' points plus one texel's footprint), clamped to
  // [widthMinMeters, T]; a run that reaches the end of the line takes T. The second layer's slabs
  // stay T deep. Measured against (a) it beats every constant T on every built-in scene (thin
  // grass and a thick sphere need opposite T).
  std::optional<bool> thicknessFromWidth;
  double widthScale = gen::SAO_WIDTH_SCALE;
  double widthMinMeters = gen::SAO_WIDTH_MIN_M;
  double widthJump = gen::SAO_WIDTH_JUMP;
  // Evaluate every stride-th pixel in x and y only (those with x % stride == 0 and y % stride == 0);
  // the others are NaN, so that a comparison must take the strided pixels only (sao-bench does).
  std::uint32_t stride = 1;
  // Each slice weighted by d(azimuth about the view direction)/d(screen angle) as well as by its
  // cosine weight: with it the slices sample the azimuth about V uniformly and V is the cosine-
  // weighted hemisphere integral exactly; without it (the estimator's uniform screen angles) the
  // result differs off the image centre and with non-square pixels (docs/reference.md).
  bool azimuthWeight = true;
  std::uint64_t seed = 1;  // the result is a pure function of (inputs, settings, camera, options)
  unsigned threads = 0;    // 0: one per hardware thread
};

// `ao`: camera.width x camera.height, 1 channel, visibility V in [0, 1] per pixel (sky: 1; pixels off
// the stride: NaN). No intensity, contrast or bias: V is compared with (a) directly. Uses the
// settings' radius, thickness and depth_tolerance only (and the camera's projection and
// metersToViewUnits). Errors: the core's for
// bad settings or camera; InvalidInput for a missing depth, inputs whose extent or format disagree
// (as convergedEstimator), slices or stride 0, a thickness that is NaN or <= 0, a tolerance
// outside [0, 1), or (thicknessFromWidth) a widthScale, widthMinMeters or widthJump not > 0 and finite.
Status screenVisibility(const Settings& settings, const Camera& camera, const ConvergedInputs& inputs,
                        const ScreenVisibilityOptions& options, FloatImage& ao);

}  // namespace sao::raytrace
