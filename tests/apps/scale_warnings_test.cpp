// The scale warnings of the sample programs (sao/samples/scale_warnings.h): each of the three, the
// figures behind them, no warning for a scene at the right scale, and only the no-geometry one
// without geometry.
#include <bit>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sao/samples/scale_warnings.h"

namespace sao::samples {
namespace {

constexpr std::uint32_t kW = 64, kH = 48;

Camera camera(double metersToViewUnits) {
  Camera c = perspectiveCamera(std::numbers::pi / 3, kW, kH, 0.1, INFINITY, ClipDepth::ZeroToOne, true);
  c.metersToViewUnits = metersToViewUnits;
  return c;
}

// Linear z per pixel: `z(x, y)` (view units, < 0), or sky where it returns 0.
template <class F>
DepthImage linearDepth(F z) {
  DepthImage d;
  d.extent = {kW, kH};
  d.format = DepthFormat::LinearZ;
  for (std::uint32_t y = 0; y < kH; ++y)
    for (std::uint32_t x = 0; x < kW; ++x) d.texels.push_back(std::bit_cast<std::uint32_t>(float(z(x, y))));
  return d;
}

FloatImage aoWith(float value) { return FloatImage({kW, kH}, 1, value); }

// S' of the camera: pixels spanned by one view unit at distance 1.
const double kProjScale = 0.5 * kH / std::tan(std::numbers::pi / 6);

TEST(ScaleWarnings, NoneForAWallFiveMetresAwayInMetres) {
  ScaleCheck c;
  FloatImage ao = aoWith(1.0f);
  ao.at(3, 3) = 0.5f;
  ASSERT_TRUE(checkScale(Settings{}, camera(1.0), linearDepth([](auto, auto) { return -5.0; }), ao, c));
  EXPECT_EQ(c.geometryPixels, kW * kH);
  EXPECT_NEAR(c.radiusPxMedian, kProjScale / 5.0, 1e-4);  // ~8.3 px
  EXPECT_EQ(c.fractionBelowOnePx, 0.0);
  EXPECT_EQ(c.fractionAboveImage, 0.0);
  EXPECT_EQ(c.aoMin, 0.5);
  EXPECT_NEAR(c.aoMean, 1.0 - 0.5 / (kW * kH), 1e-12);
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
}

TEST(ScaleWarnings, RadiusBelowOnePixelAndAllWhite) {
  // The same wall 5000 units away read as metres (a scene in millimetres without --units).
  ScaleCheck c;
  ASSERT_TRUE(checkScale(Settings{}, camera(1.0), linearDepth([](auto, auto) { return -5000.0; }), aoWith(1.0f), c));
  EXPECT_EQ(c.fractionBelowOnePx, 1.0);
  ASSERT_EQ(c.warnings.size(), 2u);
  EXPECT_EQ(c.warnings[0],
            "the radius (1 m = 1 scene units) projects below 1 px on 100 % of the geometry (median 0.00831 px over "
            "3072 geometry pixels), where the AO is 1: is the scene in other units than metres (--units), or is the "
            "radius too small?");
  EXPECT_EQ(c.warnings[1],
            "the AO is 1.0 on every geometry pixel: nothing is occluded; if the scene has creases or contacts, check "
            "its units (--units) and the radius");
}

TEST(ScaleWarnings, RadiusBelowOnePixelOnMostButNotHalf) {
  // Left half 5 m away (r' 8.3 px), right half 5 km: exactly half below 1 px is not "most".
  auto halves = [](double right) {
    return linearDepth([right](std::uint32_t x, auto) { return x < kW / 2 ? -5.0 : right; });
  };
  ScaleCheck c;
  ASSERT_TRUE(checkScale(Settings{}, camera(1.0), halves(-5000.0), aoWith(0.9f), c));
  EXPECT_EQ(c.fractionBelowOnePx, 0.5);
  EXPECT_TRUE(c.warnings.empty());
  // One more column far away tips it.
  const DepthImage mostlyFar = linearDepth([](std::uint32_t x, auto) { return x < kW / 2 - 1 ? -5.0 : -5000.0; });
  ASSERT_TRUE(checkScale(Settings{}, camera(1.0), mostlyFar, aoWith(0.9f), c));
  EXPECT_GT(c.fractionBelowOnePx, 0.5);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("projects below 1 px on 52 % of the geometry"), std::string::npos) << c.warnings[0];
}

TEST(ScaleWarnings, RadiusBeyondTheImage) {
  // A wall 5 m away in a scene read as millimetres (u = 1000): r' = 8300 px on a 64 px image.
  ScaleCheck c;
  ASSERT_TRUE(checkScale(Settings{}, camera(1000.0), linearDepth([](auto, auto) { return -5.0; }), aoWith(0.2f), c));
  EXPECT_EQ(c.fractionAboveImage, 1.0);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0],
            "the radius (1 m = 1000 scene units) projects beyond the image's 64 px on 100 % of the geometry (median "
            "8.31e+03 px over 3072 geometry pixels): are the scene's units (--units) right, or is the radius too "
            "large?");
}

TEST(ScaleWarnings, AllWhiteAtAFineRadius) {
  ScaleCheck c;
  ASSERT_TRUE(checkScale(Settings{}, camera(1.0), linearDepth([](auto, auto) { return -5.0; }), aoWith(1.0f), c));
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].rfind("the AO is 1.0 on every geometry pixel", 0), 0u);
  // A single pixel below 1 is occlusion: no warning.
  FloatImage ao = aoWith(1.0f);
  ao.at(10, 10) = 0.999f;
  ASSERT_TRUE(checkScale(Settings{}, camera(1.0), linearDepth([](auto, auto) { return -5.0; }), ao, c));
  EXPECT_TRUE(c.warnings.empty());
}

TEST(ScaleWarnings, SkyOnlyAndSkyPixelsAreLeftOut) {
  ScaleCheck c;
  ASSERT_TRUE(checkScale(Settings{}, camera(1.0), linearDepth([](auto, auto) { return 0.0; }), aoWith(1.0f), c));
  EXPECT_EQ(c.geometryPixels, 0u);
  // No geometry is said (depth_convention.h), never the scale.
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].rfind("no geometry: every one of the 3072 depth texels is sky", 0), 0u) << c.warnings[0];
  // Sky at 5 km (r' would be far below 1 px) beside a wall at 5 m: only the wall counts.
  ASSERT_TRUE(checkScale(Settings{}, camera(1.0),
                         linearDepth([](std::uint32_t x, auto) { return x < 8 ? -5.0 : (x % 2 ? 0.0 : NAN); }),
                         aoWith(0.7f), c));
  EXPECT_EQ(c.geometryPixels, 8u * kH);
  EXPECT_EQ(c.fractionBelowOnePx, 0.0);
}

TEST(ScaleWarnings, HardwareDepthGivesTheSameFigures) {
  // Reversed-Z D32F of the same wall: z = c0 / (d c1 + c2), solved for d.
  const Camera cam = camera(1.0);
  DepthModel m;
  ASSERT_TRUE(analyze(cam, m));
  DepthImage d;
  d.extent = {kW, kH};
  d.format = DepthFormat::D32F;
  const float dWall = float((m.c0 / -5000.0 - m.c2) / m.c1);
  for (std::uint32_t i = 0; i < kW * kH; ++i) d.texels.push_back(std::bit_cast<std::uint32_t>(i % 2 ? dWall : 0.0f));
  ScaleCheck c;
  ASSERT_TRUE(checkScale(Settings{}, cam, d, aoWith(1.0f), c));
  EXPECT_EQ(c.geometryPixels, kW * kH / 2) << "depth 0 is the reversed-Z clear value (sky)";
  EXPECT_NEAR(c.radiusPxMedian, kProjScale / 5000.0, 1e-6);
  EXPECT_EQ(c.warnings.size(), 2u);
}

TEST(ScaleWarnings, MismatchedImagesAreRefused) {
  ScaleCheck c;
  c.geometryPixels = 7;
  const Status s = checkScale(Settings{}, camera(1.0), linearDepth([](auto, auto) { return -5.0; }),
                              FloatImage({kW, kH - 1}, 1, 1.0f), c);
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_EQ(s.message, "scale check: the depth and AO images do not match the camera");
  EXPECT_EQ(c.geometryPixels, 7u) << "out is left untouched";
}

}  // namespace
}  // namespace sao::samples
