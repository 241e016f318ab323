// thickness_model 1's two halves on the CPU reference (effect/cpu/sao_visibility.h, the GLSL of
// effect/include/sao_visibility.glsl; docs/effect-math.md 5.9, "Thickness from width"): the width
// pass's share of thickness of a texel from its run of continuous depth along x and y (runShare),
// and a tap's thickness from the two shares along its slice (tapThickness). Hand-built z images,
// in double: every expected value is worked out from the texel spacing.
#include <cmath>
#include <vector>

#include "sao_visibility.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::detail::Image;
using cpu::detail::runShare;
using cpu::detail::tapThickness;

// Exact in float (the block is float, read as double): one texel is |z| / 128 across.
constexpr double kSpacing = 1.0 / 128.0;
constexpr double kT = 0.25, kTMin = 1.0 / 64.0;

cpu::detail::Block<double> block() {
  gen::SaoParams p{};
  p.proj_info = {float(-kSpacing), float(-kSpacing), 1.5f, 0.875f};
  p.ortho = 0;
  p.thickness = float(kT);
  p.thickness_min = float(kTMin);
  return cpu::detail::Block<double>(p);
}

// A 64x48 image of z = background with columns [x0, x0 + width) at z = zs (full height).
Image<double> strip(int x0, int width, double background, double zs = -3.0) {
  Image<double> z(64, 48, 1);
  for (int y = 0; y < z.h; ++y)
    for (int x = 0; x < z.w; ++x) z.at(x, y) = (x >= x0 && x < x0 + width) ? zs : background;
  return z;
}

// A strip of w texels at z = zs is w texels of |zs| * kSpacing wide (end points w - 1 apart, plus
// one texel's footprint): its share along x is 0.5 * that clamped to [kTMin, kT], over kT.
double stripShare(int w, double zs = -3.0) {
  return std::min(kT, std::max(kTMin, 0.5 * w * -zs * kSpacing)) / kT;
}

TEST(WidthShare, ANarrowStripIsAsDeepAsHalfItsWidthAcrossAndWideAlong) {
  const auto P = block();
  for (double background : {-6.0, 0.0}) {  // a far wall, or sky (+0.0): either ends the run
    const Image<double> z = strip(30, 5, background);
    for (int x = 30; x < 35; ++x) {  // every texel of the strip: the same run
      EXPECT_NEAR(runShare(z, x, 24, -3.0, 1, 0, P), stripShare(5), 1e-12) << x << ", background " << background;
      // Along y the strip runs to the image's top and bottom: wide.
      EXPECT_EQ(runShare(z, x, 24, -3.0, 0, 1, P), 1.0) << x;
    }
  }
  EXPECT_NEAR(stripShare(5), 0.05859375 / kT, 1e-15);
  // One texel: 0.01171875 under the least thickness.
  EXPECT_NEAR(runShare(strip(30, 1, -6.0), 30, 24, -3.0, 1, 0, P), kTMin / kT, 1e-12);
}

TEST(WidthShare, ARunLongerThanTheReachOnEitherSideIsWide) {
  const auto P = block();
  const int reach = gen::SAO_WIDTH_REACH;
  // Longer than the reach on one side only: wide, whatever the other side (the strip's left end
  // is 1 texel away).
  const Image<double> z = strip(10, reach + 3, -6.0);
  EXPECT_EQ(runShare(z, 11, 24, -3.0, 1, 0, P), 1.0);
  // A run must end within the reach on both sides to be measured: 2 reach - 1 texels from its
  // centre (at z = -1, so that half its width stays under kT: a share under 1).
  const Image<double> fits = strip(10, 2 * reach - 1, -6.0, -1.0);
  EXPECT_NEAR(runShare(fits, 10 + reach - 1, 24, -1.0, 1, 0, P), stripShare(2 * reach - 1, -1.0), 1e-12);
  EXPECT_LT(stripShare(2 * reach - 1, -1.0), 0.6);
  // One more texel and the centre's right side goes on through all of its reach.
  const Image<double> over = strip(10, 2 * reach, -6.0, -1.0);
  EXPECT_EQ(runShare(over, 10 + reach - 1, 24, -1.0, 1, 0, P), 1.0);
  // A run that meets the image's edge is wide too.
  EXPECT_EQ(runShare(strip(0, 3, -6.0), 1, 24, -3.0, 1, 0, P), 1.0);
}

TEST(WidthShare, ASmallDepthStepContinuesTheRunALargeOneEndsIt) {
  const auto P = block();
  // Two strips side by side, 4 texels at -3 then 4 at -3 - step: within SAO_WIDTH_JUMP of z
  // (0.03 * 3.08 = 0.092 > 0.08) one run of 8; beyond it (0.1) two runs of 4.
  for (double step : {0.08, 0.1}) {
    Image<double> z = strip(30, 4, -6.0);
    for (int y = 0; y < z.h; ++y)
      for (int x = 34; x < 38; ++x) z.at(x, y) = -3.0 - step;
    const double share = runShare(z, 31, 24, -3.0, 1, 0, P);
    if (step < 0.09) {
      // End points (30.5, z -3) and (37.5, z -3.08), plus the footprint at -3.
      const double dx = 3.0 * (30.5 * -kSpacing + 1.5) - 3.08 * (37.5 * -kSpacing + 1.5);
      const double dy = 3.0 * (24.5 * -kSpacing + 0.875) - 3.08 * (24.5 * -kSpacing + 0.875);
      const double width = std::sqrt(dx * dx + dy * dy + 0.08 * 0.08) + 3.0 * kSpacing;
      EXPECT_NEAR(share, 0.5 * width / kT, 1e-12);
    } else {
      EXPECT_NEAR(share, stripShare(4), 1e-12);
    }
  }
}

TEST(WidthShare, ATapTakesTheShareOfItsSlicesMajorCrossing) {
  // A vertical blade (share 0.125 across, wide along): a slice along x crosses its width, one
  // along y its length, one at 45 degrees sqrt(2) of its width.
  EXPECT_NEAR(tapThickness(0.125, 1.0, 1.0, 0.0, kT), 0.125 * kT, 1e-15);
  EXPECT_NEAR(tapThickness(0.125, 1.0, 0.0, -1.0, kT), kT, 1e-15);
  const double c = std::sqrt(0.5);
  EXPECT_NEAR(tapThickness(0.125, 1.0, -c, c, kT), 0.125 / c * kT, 1e-12);
  // Never more than thickness, and a wide surface is thickness deep along every slice.
  EXPECT_NEAR(tapThickness(0.9, 0.9, c, c, kT), kT, 1e-15);
  EXPECT_NEAR(tapThickness(1.0, 1.0, 0.6, 0.8, kT), kT, 1e-15);
}

}  // namespace
}  // namespace sao::test
