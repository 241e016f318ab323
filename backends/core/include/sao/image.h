// Plain CPU images: the user's depth as it sits in a depth buffer, and float images for results.
#pragma once
#include <cstdint>
#include <vector>

#include "sao/plan.h"
#include "sao/status.h"

namespace sao {

// How depth texels are stored. D16 and D24 are unsigned normalised integers (d = v / (2^n - 1)),
// D32F is a float in [0, 1], LinearZ is R32F camera-space z (view units, negative in front).
enum class DepthFormat : std::uint8_t { D16, D24, D32F, LinearZ };

const char* toString(DepthFormat format);

// One channel of depth as the GPU would hold it. `texels` holds the raw value per sample, row 0
// first and a texel's samples together (sample s of texel (x, y) at (y * width + x) * samples + s):
// the integer for D16/D24, the float's bits for D32F and LinearZ. `samples` > 1 is a multisampled
// depth buffer (the CPU reference reads it as Camera::depthSamplePolicy says, like the GPU backends).
struct DepthImage {
  Extent extent;
  DepthFormat format = DepthFormat::D32F;
  std::vector<std::uint32_t> texels;
  std::uint32_t samples = 1;

  // The value a shader reads (texelFetch(..., sample).r), computed in double.
  double value(std::uint32_t x, std::uint32_t y, std::uint32_t sample = 0) const;
  std::uint32_t raw(std::uint32_t x, std::uint32_t y, std::uint32_t sample = 0) const {
    return texels[(std::size_t(y) * extent.width + x) * samples + sample];
  }
};

// The one contract for depth values, on every backend (cpu, gl, vulkan):
//  - In the shader, hardware depth (D16/D24/D32F) that is NaN, +-Inf, below 0 or above 1 is sky
//    (+0.0 in csz), exactly like the clear value; -0.0 is 0. LinearZ is sky when it is NaN, +-Inf,
//    +-0.0 or positive. The GPU paths do not scan the depth each frame, so this rule is what they
//    give, bit for bit the same on every backend.
//  - A GL D32F texture cannot hold such texels: GL clamps NaN, infinities and values outside
//    [0, 1] (and turns -0.0 into +0.0) when they are uploaded or written.
//  - Depth that comes from a file (sao-render --depth) is checked with checkDepthValues first, so
//    a file that is not what its format says is refused with the same error on every backend.

// Ok, or InvalidInput naming how many texels the format cannot hold, the first of them (x, y and
// value, row 0 first) and the likely cause: D16/D24 texels above 2^n - 1; D32F texels that are
// NaN, +-Inf, below 0 or above 1 (-0.0 is fine: it is 0); LinearZ texels that are NaN. A D32F
// image with values above 1 is most likely a linear distance in view units and one with negative
// values a linear camera-space z: the message says so and names the LinearZ format.
Status checkDepthValues(const DepthImage& depth);

// Quantises a window-space depth d in [0, 1] (or a linear z for LinearZ) to the format, as a GPU
// depth write would (round to nearest for the integer formats).
std::uint32_t encodeDepth(DepthFormat format, double d);
double decodeDepth(DepthFormat format, std::uint32_t texel);

// The float value of the binary16 nearest to x (round to nearest, ties to even; overflow to
// +-Inf, subnormals kept, NaN stays NaN): what an rgba16f texture holds for x.
float quantizeHalf(float x);

// The binary16 bits of quantizeHalf(x) (NaN: a quiet NaN with x's sign). Upload half-float data
// as these bits (GL_HALF_FLOAT, VK_FORMAT_R16G16B16A16_SFLOAT) rather than let the driver convert
// floats: Mesa 22.3 truncates float -> half on upload.
std::uint16_t halfBits(float x);

// The float value of binary16 bits (exact; subnormals, infinities and NaNs kept).
float halfToFloat(std::uint16_t bits);

// A float image with `channels` interleaved channels, row 0 first.
struct FloatImage {
  Extent extent;
  std::uint32_t channels = 1;
  std::vector<float> data;

  FloatImage() = default;
  FloatImage(Extent e, std::uint32_t c, float fill = 0.0f)
      : extent(e), channels(c), data(std::size_t(e.width) * e.height * c, fill) {}
  float& at(std::uint32_t x, std::uint32_t y, std::uint32_t c = 0) {
    return data[(std::size_t(y) * extent.width + x) * channels + c];
  }
  float at(std::uint32_t x, std::uint32_t y, std::uint32_t c = 0) const {
    return data[(std::size_t(y) * extent.width + x) * channels + c];
  }
};

}  // namespace sao
