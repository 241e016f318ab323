// sao-render's --depth file: notes, distances, binary16 precision. See depth_input.h.
#include "depth_input.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

namespace sao::render {
namespace {

std::string number(double v, const char* format = "%.3g") {
  char text[48];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// The binary16 value after |v| (away from 0), as a float of v's sign.
float nextHalf(float v) {
  const float a = halfToFloat(halfBits(std::abs(v)));
  const float next = halfToFloat(std::uint16_t(halfBits(a) + 1));
  return v < 0 ? -next : next;
}

}  // namespace

std::vector<std::string> depthFileNotes(const std::string& path, const DepthFileInfo& info) {
  std::vector<std::string> notes;
  if (info.lossyNoiseTexels)
    notes.push_back("'" + path + "': " + std::to_string(info.lossyNoiseTexels) +
                    " depth texels lay just outside [0, 1] (the farthest " + number(info.lossyNoiseWorst, "%.3g") +
                    "): noise of its lossy " + info.compression +
                    " compression around a sky or far plane of 0 or 1, read as 0 or 1 (store depth losslessly: "
                    "ZIP, PIZ or none)");
  if (info.cropFillTexels)
    notes.push_back("'" + path + "': its data window is cropped inside the display window: the image is the display "
                    "window, and its " + std::to_string(info.cropFillTexels) +
                    " texels outside the data window are sky (no surface)");
  return notes;
}

Status distancesToLinearZ(DepthImage& depth, double far) {
  std::size_t negative = 0, first = 0;
  for (std::size_t i = 0; i < depth.texels.size(); ++i) {
    const float d = std::bit_cast<float>(depth.texels[i]);
    if (d < 0 && negative++ == 0) first = i;
  }
  if (negative) {
    const std::uint32_t w = depth.extent.width;
    return Status::error(StatusCode::InvalidInput,
                         std::to_string(negative) + " of " + std::to_string(depth.texels.size()) +
                             " texels are negative, the first (" + std::to_string(first % w) + ", " +
                             std::to_string(first / w) + ") = " +
                             number(std::bit_cast<float>(depth.texels[first]), "%.9g") +
                             ": --depth-distances reads positive distances; negative values in front of the camera "
                             "are camera-space z, which a file states with sao.depthFormat \"LinearZ\" (sao/io.h)");
  }
  for (std::uint32_t& t : depth.texels) {
    const float d = std::bit_cast<float>(t);
    const bool sky = !std::isfinite(d) || d == 0 || double(d) >= far;
    t = std::bit_cast<std::uint32_t>(sky ? 0.0f : -d);
  }
  depth.format = DepthFormat::LinearZ;
  return Status::success();
}

std::optional<std::string> halfPrecisionWarning(const std::string& path, const DepthImage& depth, const Camera& camera,
                                                double radiusMeters) {
  DepthModel model;
  if (!analyze(camera, model)) return std::nullopt;
  const bool linear = depth.format == DepthFormat::LinearZ;
  if (depth.format != DepthFormat::D32F && !linear) return std::nullopt;
  // The surface texels (at most about a million of them, evenly spread), their median.
  const std::size_t stride = std::max<std::size_t>(1, depth.texels.size() >> 20);
  std::vector<float> surface;
  for (std::size_t i = 0; i < depth.texels.size(); i += stride) {
    const float v = std::bit_cast<float>(depth.texels[i]);
    const bool isSurface = linear ? std::isfinite(v) && v < 0 : v >= 0 && v <= 1 && double(v) != model.depthAtFar;
    if (isSurface) surface.push_back(v);
  }
  if (surface.empty()) return std::nullopt;
  auto middle = surface.begin() + std::ptrdiff_t(surface.size() / 2);
  std::nth_element(surface.begin(), middle, surface.end());
  const float d = *middle;
  const double z = linear ? double(d) : linearZ(model, camera.kind, d);
  const double zNext = linear ? double(nextHalf(d)) : linearZ(model, camera.kind, nextHalf(d));
  const double meters = std::abs(zNext - z) / camera.metersToViewUnits;
  if (!(meters > kHalfDepthStepOfRadius * radiusMeters)) return std::nullopt;
  return "'" + path + "' stores its depth as HALF (binary16), which cannot hold " +
         (linear ? std::string("this depth") : std::string(camera.reversedZ ? "this" : "standard (not reversed-Z)") +
                                                   " depth") +
         ": at the median surface texel (" + (linear ? std::string() : "depth " + number(d, "%.6g") + ", ") +
         number(std::abs(z) / camera.metersToViewUnits) + " m away) the next binary16 value is " + number(meters) +
         " m farther, " + number(100.0 * meters / radiusMeters, "%.2g") + " % of the radius " + number(radiusMeters) +
         " m, so surfaces become steps and the AO is wrong: store the depth as FLOAT (or as reversed-Z or linear "
         "depth, which binary16 holds far better)";
}

}  // namespace sao::render
