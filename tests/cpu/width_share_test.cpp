// thickness_model 1's two halves on the CPU reference (effect/cpu/sao_visibility.h, the GLSL of
// effect/include/sao_visibility.glsl; docs/effect-math.md 5.9, "Thickness from width"): the width
// pass's share of thickness of a texel from its run of continuous depth along x and y (runShare),
// and a tap's thickness from the two shares along its slice (tapThickness). Hand-built z images,
// in double: every expected value is worked out from the texel spacing.
#include <array>
#include <bit>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "sao/cpu/reference.h"
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

// Above level 0 (docs/effect-math.md 5.9): level m's texels are walked on their own level, and
// their ends stand at the level-0 texels their z came from. A strip of w level-1 texels (w odd: its
// end texels share their row's rotated-grid offset) is 2 (w - 1) level-0 texels between its ends
// plus a footprint of 2: the share of a level-0 strip 2w texels wide. Its continuity bound doubles
// with the level: a step of 5 % of z ends a run at level 0 (3 %) but not at level 1 (6 %). (A test
// image of z at level 1 stands for level 0 as well: runShare reads only the level it is given.)
TEST(WidthShare, ALevelAboveZeroMeasuresItsRunInItsOwnTexels) {
  const auto P = block();
  const Image<double> z1 = strip(20, 13, -6.0, -1.0);  // level 1 of a 128x96 level 0
  for (int x = 20; x < 33; ++x)
    EXPECT_NEAR(runShare(z1, 1, 128, 96, x, 24, -1.0, 1, 0, P), stripShare(26, -1.0), 1e-12) << x;
  EXPECT_LT(stripShare(26, -1.0), 1.0);
  // From 6 texels inside a 26-texel strip, 19 on its right: over the reach (16 of the level's texels).
  EXPECT_EQ(runShare(strip(20, 26, -6.0, -1.0), 1, 128, 96, 26, 24, -1.0, 1, 0, P), 1.0);

  Image<double> stepped = strip(20, 4, -6.0, -1.0);
  for (int y = 0; y < stepped.h; ++y)
    for (int x = 24; x < 28; ++x) stepped.at(x, y) = -1.05;
  EXPECT_NEAR(runShare(stepped, 21, 24, -1.0, 1, 0, P), stripShare(4, -1.0), 1e-12) << "level 0: two runs";
  // Level 1: one run of 8, ends at level-0 texels (41, 49) (z -1) and (55, 48) (z -1.05).
  const double dx = 1.0 * (41.5 * -kSpacing + 1.5) - 1.05 * (55.5 * -kSpacing + 1.5);
  const double dy = 1.0 * (49.5 * -kSpacing + 0.875) - 1.05 * (48.5 * -kSpacing + 0.875);
  const double width = std::sqrt(dx * dx + dy * dy + 0.05 * 0.05) + 2.0 * kSpacing;
  EXPECT_NEAR(runShare(stepped, 1, 128, 96, 21, 24, -1.0, 1, 0, P), 0.5 * width / kT, 1e-12) << "level 1: one run of 8";
}

// width_resolve (the CPU reference's whole run): a strip 40 texels wide at z = -2 before a far wall
// is wide at its centre on level 0 (20 texels on each side, the reach 16) and 20 texels wide on
// level 1, so its centre's share along x in csz_share is level 1's measure of it, 40 texels' worth:
// half of 40 pixels at |z| = 2 over a thickness of 1 m. Along y it meets the image's edge: wide at
// every level, 1. A texel of a second strip, 10 texels wide, is narrow on level 0 and keeps its own
// share. csz_share holds each texel's z beside its shares, binary16 (in Double too: its storage's).
TEST(WidthShare, AWideRunTakesItsShareFromTheFirstLevelWhereItIsNarrow) {
  const Extent e{128, 96};
  const Camera cam = perspectiveCamera(std::numbers::pi / 3.0, e.width, e.height, 0.1, 1000.0, ClipDepth::ZeroToOne, false);
  DepthImage depth;
  depth.extent = e;
  depth.format = DepthFormat::LinearZ;
  depth.texels.resize(std::size_t(e.width) * e.height);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x)
      depth.texels[std::size_t(y) * e.width + x] = std::bit_cast<std::uint32_t>((x >= 40 && x < 80) || (x >= 100 && x < 110) ? -2.0f : -20.0f);
  Settings s;
  s.estimator = 1;
  s.thickness_model = 1;
  s.thickness = 1.0f;
  cpu::Inputs in;
  in.depth = &depth;
  cpu::Result r;
  const Status st = cpu::run(s, cam, in, cpu::Options{cpu::Precision::Double, 2}, r);
  ASSERT_TRUE(st.ok()) << st.message;
  const std::vector<FloatImage>& run = r.images[std::size_t(gen::ResourceId::width_run)];
  const std::vector<FloatImage>& packed = r.images[std::size_t(gen::ResourceId::csz_share)];
  ASSERT_GE(run.size(), 2u);
  ASSERT_EQ(packed.size(), run.size());
  auto shares = [&](int x, int y) {
    std::array<float, 2> s{};
    cpu::detail::unpackShares(packed[0].at(x, y, 1), s[0], s[1]);
    return s;
  };
  EXPECT_EQ(packed[0].at(60, 48, 0), r.csz[0].at(60, 48, 0)) << "the texel's own z beside its shares";
  EXPECT_EQ(packed[0].at(105, 48, 0), r.csz[0].at(105, 48, 0));
  EXPECT_EQ(run[0].at(60, 48, 0), 1.0f) << "wide on level 0";
  EXPECT_LT(run[1].at(30, 24, 0), 1.0f) << "narrow on level 1";
  EXPECT_EQ(shares(60, 48)[0], cpu::detail::roundToHalf(run[1].at(30, 24, 0)));
  const double pixel = 2.0 * 2.0 * std::tan(std::numbers::pi / 6.0) / 96.0;  // at |z| = 2
  EXPECT_NEAR(shares(60, 48)[0], 0.5 * 40 * pixel, 1e-3);
  EXPECT_EQ(shares(60, 48)[1], 1.0f);
  EXPECT_LT(run[0].at(105, 48, 0), 1.0f);
  EXPECT_EQ(shares(105, 48)[0], cpu::detail::roundToHalf(run[0].at(105, 48, 0)));
}

// csz_share's packing (sao_pack_shares): every binary16 share from the least one a setting allows
// (SAO_WIDTH_MIN_M over thickness's largest value, 100 m) to 1, along x and along y, comes back
// exactly and packs into a normal positive float, which storage and texelFetch keep bit for bit.
TEST(WidthShare, EveryShareASettingAllowsPacksIntoANormalFloatAndBack) {
  const float least = cpu::detail::roundToHalf(float(gen::SAO_WIDTH_MIN_M) / 100.0f);
  ASSERT_GE(least, std::ldexp(1.0f, -14)) << "the least share must be a normal binary16";
  std::size_t values = 0;
  for (std::uint32_t bits = sao::halfBits(least); bits <= 0x3C00u; ++bits, ++values) {
    const float h = sao::halfToFloat(std::uint16_t(bits));
    ASSERT_EQ(sao::halfBits(h), bits);
    for (const auto& [sx, sy] : {std::pair{h, 1.0f}, std::pair{1.0f, h}, std::pair{h, h}, std::pair{least, h}}) {
      const float p = cpu::detail::packShares(sx, sy);
      ASSERT_EQ(std::fpclassify(p), FP_NORMAL) << sx << ", " << sy;
      ASSERT_GT(p, 0.0f);
      float ux = 0.0f, uy = 0.0f;
      cpu::detail::unpackShares(p, ux, uy);
      ASSERT_EQ(ux, sx);
      ASSERT_EQ(uy, sy);
    }
  }
  EXPECT_GT(values, 5000u) << "binary16 values from 2e-4 to 1: about 13 exponents of 1024";
}

}  // namespace
}  // namespace sao::test
