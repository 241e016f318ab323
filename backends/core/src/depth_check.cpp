// checkDepthValues: a depth image from a file is refused when its texels are not what its format
// can hold, with the count, the first bad texel and the likely cause (sao/image.h).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <string>

#include "sao/image.h"

namespace sao {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// How far outside [0, 1] a value is taken for noise rather than another convention: a camera-space
// z or a distance in metres is rarely within a millimetre of 0 or 1 everywhere.
constexpr float kNoise = 1e-3f;

std::string brief(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

struct BadTexels {
  std::size_t nan = 0, positiveInf = 0, negativeInf = 0, below = 0, above = 0;
  std::size_t first = 0;
  float lowest = 0, highest = 1;  // of the finite values below 0 and above 1
  std::size_t count() const { return nan + positiveInf + negativeInf + below + above; }
};

std::string kinds(const BadTexels& b) {
  std::string s;
  auto add = [&](std::size_t n, const char* what) {
    if (n) s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(b.nan, "NaN");
  add(b.positiveInf, "+inf");
  add(b.negativeInf, "-inf");
  add(b.below, "below 0");
  add(b.above, "above 1");
  return s;
}

// What most likely went wrong, judged from the kinds of bad texels.
std::string likelyCause(const BadTexels& b) {
  const std::string linearZ = "store it as LinearZ (camera-space z, negative in front of the camera; sao.depthFormat "
                              "\"LinearZ\", see sao/io.h)";
  // Noise, not a convention: a lossy compression (B44 on HALF gives -6e-6) or filtering moves a
  // sky or near plane of 0 (or a far plane of 1) by far less than any camera-space z.
  if (b.below && !b.above && !b.nan && !b.negativeInf && b.lowest >= -kNoise)
    return "values just below 0 (the lowest " + brief(b.lowest) + ") are noise around a depth of 0 (the sky of "
           "reversed-Z), as a lossy compression (B44, DWA) or filtering leaves, not linear z: store the depth "
           "losslessly (ZIP, PIZ or none) or clamp it to [0, 1]";
  if (b.above && !b.below && !b.nan && !b.positiveInf && b.highest <= 1 + kNoise)
    return "values just above 1 (the highest " + brief(b.highest) + ") are noise around a depth of 1 (the sky of "
           "standard depth), as a lossy compression (B44, DWA) or filtering leaves, not linear depth: store the "
           "depth losslessly (ZIP, PIZ or none) or clamp it to [0, 1]";
  if (b.above && !b.below && !b.nan)
    return "values above 1 look like linear depth (a distance in view units, e.g. metres), not hardware depth in "
           "[0, 1]: " + linearZ;
  if (b.below && !b.above && !b.nan)
    return "values below 0 look like linear camera-space z, not hardware depth in [0, 1]: " + linearZ;
  return "hardware depth lies in [0, 1] and holds no NaN or infinity; write the sky as the clear value (1, or 0 "
         "with reversed-Z)";
}

}  // namespace

Status checkDepthValues(const DepthImage& depth) {
  if (depth.samples == 0) return Status::error(StatusCode::InvalidInput, "depth image has 0 samples per texel");
  const std::size_t n = std::size_t(depth.extent.width) * depth.extent.height * depth.samples;
  if (depth.texels.size() != n)
    return Status::error(StatusCode::InvalidInput,
                         "depth image holds " + std::to_string(depth.texels.size()) + " texels, its extent " +
                             std::to_string(depth.extent.width) + "x" + std::to_string(depth.extent.height) +
                             (depth.samples > 1 ? " with " + std::to_string(depth.samples) + " samples per texel" : "") +
                             " needs " + std::to_string(n));
  BadTexels bad;
  auto note = [&](std::size_t& kind, std::size_t i) {
    if (bad.count() == 0) bad.first = i;
    ++kind;
  };
  if (depth.format == DepthFormat::D16 || depth.format == DepthFormat::D24) {
    const std::uint32_t max = depth.format == DepthFormat::D16 ? 0xffffu : 0xffffffu;
    for (std::size_t i = 0; i < n; ++i)
      if (depth.texels[i] > max) note(bad.above, i);
  } else {
    const bool linear = depth.format == DepthFormat::LinearZ;
    for (std::size_t i = 0; i < n; ++i) {
      const float v = std::bit_cast<float>(depth.texels[i]);
      if (std::isnan(v)) note(bad.nan, i);
      else if (linear) continue;  // every other linear z is geometry (z < 0) or sky
      else if (v == INFINITY) note(bad.positiveInf, i);
      else if (v == -INFINITY) note(bad.negativeInf, i);
      else if (v < 0) {  // -0.0 == 0 is not below
        note(bad.below, i);
        bad.lowest = std::min(bad.lowest, v);
      } else if (v > 1) {
        note(bad.above, i);
        bad.highest = std::max(bad.highest, v);
      }
    }
  }
  if (bad.count() == 0) return Status::success();
  const std::size_t texel = bad.first / depth.samples;
  const auto x = std::uint32_t(texel % depth.extent.width), y = std::uint32_t(texel / depth.extent.width);
  const std::string where = "the first is (" + std::to_string(x) + ", " + std::to_string(y) + ")" +
                            (depth.samples > 1 ? " sample " + std::to_string(bad.first % depth.samples) : "") + " = ";
  const std::string counted = std::to_string(bad.count()) + " of " + std::to_string(n) + (depth.samples > 1 ? " samples " : " texels ");
  std::string message;
  if (depth.format == DepthFormat::D16 || depth.format == DepthFormat::D24)
    message = counted + "are above " + std::to_string(depth.format == DepthFormat::D16 ? 0xffffu : 0xffffffu) +
              ", the largest " + toString(depth.format) + " texel; " + where + std::to_string(depth.texels[bad.first]);
  else
    message = counted + "are not " + toString(depth.format) + " depth (" + kinds(bad) + "); " + where +
              number(std::bit_cast<float>(depth.texels[bad.first])) + ": " +
              (depth.format == DepthFormat::LinearZ ? "linear z holds no NaN; write the sky as +0 or +inf"
                                                    : likelyCause(bad));
  return Status::error(StatusCode::InvalidInput, message);
}

}  // namespace sao
