// Round trip: camera-space points -> projection -> quantised depth (D16, D24, D32F) -> eq. 2
// with the block's float constants, evaluated in float as the shader does. The error stays under
// each format's bound: the depth quantum plus float evaluation, mapped through dz/dd = z^2 c1/c0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "sao/constants.h"
#include "sao/image.h"

namespace {

struct Convention {
  const char* name;
  sao::ClipDepth clip;
  bool reversed;
  double far;
};

double windowDepth(const sao::Camera& c, double z) {
  const double C = c.projection[10], D = c.projection[14];
  const double ndc = (C * z + D) / (-z);
  return c.clipDepth == sao::ClipDepth::ZeroToOne ? ndc : 0.5 * ndc + 0.5;
}

// Half a quantum of the stored depth near d (round to nearest on write).
double depthQuantum(sao::DepthFormat f, double d) {
  switch (f) {
    case sao::DepthFormat::D16: return 0.5 / 65535.0;
    case sao::DepthFormat::D24: return 0.5 / 16777215.0;
    default: return std::fmax(std::ldexp(1.0, std::ilogb(std::fmax(std::fabs(d), 1e-30)) - 24), 1e-45);
  }
}

TEST(DepthRoundTrip, ErrorStaysUnderEachFormatsBound) {
  const Convention setups[] = {
      {"gl_standard_far1e4", sao::ClipDepth::NegativeOneToOne, false, 1e4},
      {"gl_standard_infinite", sao::ClipDepth::NegativeOneToOne, false, INFINITY},
      {"zero_one_standard_infinite", sao::ClipDepth::ZeroToOne, false, INFINITY},
      {"zero_one_reversed_infinite", sao::ClipDepth::ZeroToOne, true, INFINITY},
      {"gl_reversed_far1e4", sao::ClipDepth::NegativeOneToOne, true, 1e4},
  };
  const sao::DepthFormat formats[] = {sao::DepthFormat::D16, sao::DepthFormat::D24, sao::DepthFormat::D32F};
  std::mt19937_64 rng(1234);
  std::printf("%-28s %-6s %12s %12s %12s  (worst |dz| in metres, near = 0.1 m)\n", "convention", "format", "1 m",
              "10 m", "100 m");
  for (const auto& su : setups) {
    const auto cam = sao::perspectiveCamera(1.0, 256, 256, 0.1, su.far, su.clip, su.reversed);
    sao::ParamBlock p;
    ASSERT_TRUE(sao::computeConstants(sao::Settings{}, cam, sao::DepthEncoding::Hardware, p).ok()) << su.name;
    const double c1OverC0 = std::fabs(double(p.clip_info.y) / double(p.clip_info.x));
    for (auto fmt : formats) {
      double worst[3] = {0, 0, 0};
      for (int bin = 0; bin < 3; ++bin) {
        const double centre = std::pow(10.0, bin);
        std::uniform_real_distribution<double> dist(0.9 * centre, 1.1 * centre);
        for (int i = 0; i < 4000; ++i) {
          const double z = -dist(rng);
          const double d = windowDepth(cam, z);
          // What the shader sees: the stored texel converted to float, then eq. 2 in float.
          const float df = static_cast<float>(sao::decodeDepth(fmt, sao::encodeDepth(fmt, d)));
          const float zf = p.clip_info.x / (df * p.clip_info.y + p.clip_info.z);
          const double err = std::fabs(double(zf) - z);
          worst[bin] = std::fmax(worst[bin], err);
          // Bound: quantum of d plus ~2 ulps of the float evaluation of d*c1 + c2 (|.| <= 1),
          // through dz/dd; plus a few ulps of z itself.
          const double bound = (depthQuantum(fmt, d) + std::ldexp(1.0, -23)) * z * z * c1OverC0 * 1.01 +
                               4.0 * std::ldexp(std::fabs(z), -24);
          ASSERT_LE(err, bound) << su.name << " " << sao::toString(fmt) << " z=" << z << " d=" << d;
          ASSERT_TRUE(std::isfinite(zf));
        }
      }
      std::printf("%-28s %-6s %12.3g %12.3g %12.3g\n", su.name, sao::toString(fmt), worst[0], worst[1], worst[2]);
    }
  }
}

TEST(DepthRoundTrip, ReversedZD32FIsFarBetterThanD24At100m) {
  // Design notes: reversed-Z D32F [0,1] should be >= 100x better than D24 at 100 m.
  const auto d24cam = sao::perspectiveCamera(1.0, 256, 256, 0.1, INFINITY, sao::ClipDepth::ZeroToOne, false);
  const auto revcam = sao::perspectiveCamera(1.0, 256, 256, 0.1, INFINITY, sao::ClipDepth::ZeroToOne, true);
  sao::ParamBlock p24, prev;
  ASSERT_TRUE(sao::computeConstants(sao::Settings{}, d24cam, sao::DepthEncoding::Hardware, p24).ok());
  ASSERT_TRUE(sao::computeConstants(sao::Settings{}, revcam, sao::DepthEncoding::Hardware, prev).ok());
  double worst24 = 0, worstRev = 0;
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> dist(90.0, 110.0);
  for (int i = 0; i < 20000; ++i) {
    const double z = -dist(rng);
    const float d24 = float(sao::decodeDepth(sao::DepthFormat::D24, sao::encodeDepth(sao::DepthFormat::D24, windowDepth(d24cam, z))));
    const float drev = float(windowDepth(revcam, z));
    worst24 = std::fmax(worst24, std::fabs(double(p24.clip_info.x / (d24 * p24.clip_info.y + p24.clip_info.z)) - z));
    worstRev = std::fmax(worstRev, std::fabs(double(prev.clip_info.x / (drev * prev.clip_info.y + prev.clip_info.z)) - z));
  }
  std::printf("at 100 m: D24 standard %.3g m, D32F reversed-Z %.3g m, ratio %.0f\n", worst24, worstRev, worst24 / worstRev);
  EXPECT_GE(worst24 / worstRev, 100.0);
}

}  // namespace
