// checkScale: the projected radius and the AO over the geometry pixels of a finished run.
#include "sao/samples/scale_warnings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sao/constants.h"
#include "sao/samples/depth_convention.h"

namespace sao::samples {

namespace {

std::string format(const char* pattern, double a = 0, double b = 0, double c = 0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

// Camera-space z of a depth texel, or NaN for sky (the effect's rule, sao/image.h).
double geometryZ(const DepthImage& depth, const Camera& camera, const DepthModel& model, std::uint32_t x,
                 std::uint32_t y) {
  const double d = depth.value(x, y);
  if (depth.format == DepthFormat::LinearZ) return (std::isfinite(d) && d < 0) ? d : NAN;
  if (!(d >= 0 && d <= 1) || (camera.reversedZ ? d <= 0 : d >= 1)) return NAN;
  const double z = linearZ(model, camera.kind, d);
  return (std::isfinite(z) && z < 0) ? z : NAN;
}

}  // namespace

Status checkScale(const Settings& settings, const Camera& camera, const DepthImage& depth, const FloatImage& ao,
                  ScaleCheck& out) {
  const DepthEncoding encoding =
      depth.format == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  ParamBlock block;  // the radius and S' exactly as the effect gets them
  if (Status s = computeConstants(settings, camera, encoding, block); !s) return s;
  DepthModel model;
  if (Status s = analyze(camera, model); !s) return s;
  const std::uint32_t g = camera.guardBand;
  if (depth.extent != Extent{camera.width + 2 * g, camera.height + 2 * g} ||
      ao.extent != Extent{camera.width, camera.height} || ao.channels != 1 ||
      depth.texels.size() != std::size_t(depth.extent.width) * depth.extent.height ||
      ao.data.size() != std::size_t(ao.extent.width) * ao.extent.height)
    return Status::error(StatusCode::InvalidInput, "scale check: the depth and AO images do not match the camera");

  const std::vector<std::string> convention = depthConventionWarnings(depth, camera, settings);
  ScaleCheck c;
  std::vector<double> radiusPx;
  double aoSum = 0;
  const double imageSide = std::max(camera.width, camera.height);
  std::size_t below = 0, above = 0;
  for (std::uint32_t y = 0; y < camera.height; ++y)
    for (std::uint32_t x = 0; x < camera.width; ++x) {
      const double z = geometryZ(depth, camera, model, x + g, y + g);
      if (std::isnan(z)) continue;
      const double distance = camera.kind == ProjectionKind::Orthographic ? 1.0 : -z;
      const double r = double(block.radius) * block.proj_scale / distance;
      radiusPx.push_back(r);
      below += r < 1.0;
      above += r > imageSide;
      const double a = ao.at(x, y);
      c.aoMin = std::min(c.aoMin, a);
      aoSum += a;
    }
  c.geometryPixels = radiusPx.size();
  if (c.geometryPixels > 0) {
    const double n = double(c.geometryPixels);
    std::nth_element(radiusPx.begin(), radiusPx.begin() + radiusPx.size() / 2, radiusPx.end());
    c.radiusPxMedian = radiusPx[radiusPx.size() / 2];
    c.fractionBelowOnePx = below / n;
    c.fractionAboveImage = above / n;
    c.aoMean = aoSum / n;
  }
  c.warnings = convention;  // first: they name the cause
  // A buffer read with the wrong convention explains the figures below: its warning says what to do.
  if (c.geometryPixels > 0 && convention.empty()) {
    const double n = double(c.geometryPixels);
    const std::string radius = format("the radius (%g m = %g scene units)", settings.radius, block.radius);
    const std::string where = format("(median %.3g px over %.0f geometry pixels)", c.radiusPxMedian, n);
    if (2 * below > c.geometryPixels)
      c.warnings.push_back(radius + " projects below 1 px on " + format("%.0f %%", 100.0 * c.fractionBelowOnePx) +
                           " of the geometry " + where + ", where the AO is 1: is the scene in other units than " +
                           "metres (--units), or is the radius too small?");
    if (2 * above > c.geometryPixels)
      c.warnings.push_back(radius + " projects beyond the image's " + format("%.0f px", imageSide) + " on " +
                           format("%.0f %%", 100.0 * c.fractionAboveImage) + " of the geometry " + where +
                           ": are the scene's units (--units) right, or is the radius too large?");
    if (c.aoMin == 1.0)
      c.warnings.push_back("the AO is 1.0 on every geometry pixel: nothing is occluded; if the scene has creases or "
                           "contacts, check its units (--units) and the radius");
  }
  out = std::move(c);
  return Status::success();
}

}  // namespace sao::samples
