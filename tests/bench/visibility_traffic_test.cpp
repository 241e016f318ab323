// The traffic model counts the visibility estimator's taps (estimator = 1; effect/cpu/tap_trace.h):
// every slice tap that leaves the centre texel is a read, and with the z hierarchy its L2 bytes per
// pixel stay within 2x over r = 1 .. 16 m and below 1.5x SAO's worst (without it they grow 8x).
#include <gtest/gtest.h>

#include <bit>
#include <algorithm>
#include <cstdio>
#include <numbers>

#include "traffic_model.h"
#include "traffic_replay.h"

namespace sao::bench {
namespace {

// A camera-facing plane 2 m away, n x n, as linear z: every pixel has geometry, every run of
// continuous depth goes on to the image's edges.
struct Plane {
  explicit Plane(std::uint32_t n = 256)
      : camera(perspectiveCamera(std::numbers::pi / 3, n, n, 0.1, 100.0, ClipDepth::NegativeOneToOne, false)),
        depth{{n, n}, DepthFormat::LinearZ, std::vector<std::uint32_t>(n * n, std::bit_cast<std::uint32_t>(-2.0f))} {}
  Camera camera;
  DepthImage depth;
};

Machine smallGpu() {
  Machine m;
  m.name = "small";
  m.sms = 2;
  m.groupsInFlight = 1;
  m.warpLanes = 32;
  m.l1 = {16 * 1024, 128, 0};
  m.l2 = {64 * 1024, 128, 16};
  m.l2Shared = true;
  return m;
}

// The visibility estimator with 16 taps: 2 slices x 2 sides x 4 steps, at full resolution.
Settings visibility16() {
  Settings s;
  s.estimator = 1;
  s.samples = 16;
  s.slices = 2;
  s.resolution_divisor = 1;
  return s;
}

TEST(VisibilityTraffic, CountsTheSliceTapsAndStaysFlatInTheRadius) {
  const Plane plane;
  std::unique_ptr<TrafficScene> scene;
  ASSERT_TRUE(TrafficScene::create(plane.depth, plane.camera, scene));
  const std::vector<Machine> machines = {smallGpu()};
  Settings s = visibility16();
  auto l2BytesPerPixel = [&](float radius, bool hierarchy, ReplayResult& r) {
    s.radius = radius;
    EXPECT_TRUE(scene->replay(s, {"visibility", hierarchy, false, 4}, machines, r));
    return double(r.traffic[0].l2Misses) * r.traffic[0].lineBytes / double(r.pixels);
  };
  // Reads per pixel: the centre, four neighbours, and the 16 taps but those that stay on the centre
  // texel (h_0 = r'(xi/4)^2 is below a pixel for a small xi even at r' ~ 440 px).
  ReplayResult r4;
  const double b4 = l2BytesPerPixel(4.0f, true, r4);
  EXPECT_LE(r4.traffic[0].reads, (1u + 4u + 16u) * 256 * 256);
  EXPECT_GT(r4.traffic[0].reads, (1u + 4u + 15u) * 256 * 256);
  EXPECT_GE(r4.maxMip, 4);
  // L2 bytes per pixel over r = 1 .. 16 m (r' ~ 110 .. 1770 px), against SAO's 16 spiral taps.
  double visLo = 1e30, visHi = 0, saoHi = 0;
  for (float radius : {1.0f, 2.0f, 4.0f, 8.0f, 16.0f}) {
    ReplayResult v, a;
    s.estimator = 1;
    const double bv = l2BytesPerPixel(radius, true, v);
    s.estimator = 0;
    const double ba = l2BytesPerPixel(radius, true, a);
    std::printf("[traffic] plane 256x256, 16 taps, r %5.1f m: L2 bytes/pixel visibility %.1f, SAO %.1f\n", radius, bv,
                ba);
    visLo = std::min(visLo, bv);
    visHi = std::max(visHi, bv);
    saoHi = std::max(saoHi, ba);
  }
  s.estimator = 1;
  ReplayResult flat;
  const double b4Flat = l2BytesPerPixel(4.0f, false, flat);
  std::printf("[traffic] visibility r 4 m: %.1f with the hierarchy, %.1f from level 0 only\n", b4, b4Flat);
  EXPECT_LE(visHi, 2.0 * visLo) << "flat in r with the hierarchy";
  EXPECT_LE(visHi, 1.5 * saoHi) << "as SAO's";
  EXPECT_GT(b4Flat, 4.0 * b4) << "without the hierarchy far taps miss";
}

// thickness_model 1 reads each tap's csz_share texel (its z and shares, 8 bytes) instead of its csz
// texel, after the width passes: the L2 bytes per pixel of the three do not grow with r (at
// most 10 % above r = 1 m's over r = 1 .. 16 m; like SAO's they fall as the taps move up the
// hierarchy).
TEST(VisibilityTraffic, WidthShareStaysFlatInTheRadius) {
  const Plane plane;
  std::unique_ptr<TrafficScene> scene;
  ASSERT_TRUE(TrafficScene::create(plane.depth, plane.camera, scene));
  const std::vector<Machine> machines = {smallGpu()};
  Settings s = visibility16();
  s.thickness_model = 1;
  double first = 0, hi = 0;
  for (float radius : {1.0f, 2.0f, 4.0f, 8.0f, 16.0f}) {
    s.radius = radius;
    ReplayResult r;
    ASSERT_TRUE(scene->replay(s, {"visibility", true, false, 4}, machines, r));
    const double b = double(r.traffic[0].l2Misses) * r.traffic[0].lineBytes / double(r.pixels);
    const double bw = double(r.widthTraffic[0].l2Misses) * r.widthTraffic[0].lineBytes / double(r.pixels);
    std::printf("[traffic] plane 256x256, 16 taps, thickness_model 1, r %5.1f m: L2 bytes/pixel %.1f (the width passes "
                "%.1f), reads/pixel %.1f\n",
                radius, b, bw, double(r.traffic[0].reads) / double(r.pixels));
    EXPECT_GT(r.widthTraffic[0].reads, 0u);
    EXPECT_LT(r.widthTraffic[0].l2Misses, r.traffic[0].l2Misses);
    if (radius == 4.0f) {  // as the test above: all 16 taps leave the centre texel but for a small xi
      const std::uint64_t perTap = 1, aoSampleReads = r.traffic[0].reads - r.widthTraffic[0].reads;
      EXPECT_LE(aoSampleReads, (1u + 4u + 16u * perTap) * 256 * 256);
      EXPECT_GT(aoSampleReads, (1u + 4u + 15u * perTap) * 256 * 256);
    }
    if (radius == 1.0f) first = b;
    hi = std::max(hi, b);
  }
  EXPECT_LE(hi, 1.1 * first) << "no growth in r with the hierarchy";
}

// The width passes' reads on a 32x32 plane, counted by hand: no run breaks, so every walk of a
// texel of level m (n x n texels) reads until it leaves the level or has read SAO_WIDTH_REACH texels,
// and every share is 1 (wide), so width_resolve reads each texel's ancestors up to max_mip.
TEST(VisibilityTraffic, TheWidthPassesReadTheirWalksAndTheResolveItsAncestors) {
  const Plane plane(32);
  std::unique_ptr<TrafficScene> scene;
  ASSERT_TRUE(TrafficScene::create(plane.depth, plane.camera, scene));
  const std::vector<Machine> machines = {smallGpu()};
  Settings s = visibility16();
  s.thickness_model = 1;
  s.radius = 4.0f;
  ReplayResult r;
  ASSERT_TRUE(scene->replay(s, {"visibility", true, false, 4}, machines, r));
  ASSERT_GE(r.maxMip, 2) << "levels 2+ go to whole work groups: the test needs one";
  const std::uint64_t reach = 16;  // SAO_WIDTH_REACH
  // width: 2x2 groups of 64 invocations, six 2x2 gathers each; then each texel of levels 1 ..
  // max_mip: its centre and, along x and y, min(reach, n - p) reads on the + side (the last one
  // outside the level, clamped) and min(reach, p + 1) on the - side.
  std::uint64_t width = 2 * 2 * 64 * 6 * 4;
  // Each texel of width_resolve reads its csz z, then its width_run texel and its ancestors.
  std::uint64_t resolve = 32 * 32 * std::uint64_t(2 + r.maxMip);  // level 0: z, itself, max_mip ancestors
  for (int m = 1; m <= r.maxMip; ++m) {
    const std::uint64_t n = std::max(32u >> m, 1u);
    std::uint64_t axis = 0;
    for (std::uint64_t p = 0; p < n; ++p) axis += std::min(reach, n - p) + std::min(reach, p + 1);
    width += n * n + 2 * n * axis;  // each texel its centre, every row its x walks, every column its y walks
    resolve += n * n * std::uint64_t(2 + r.maxMip - m);
  }
  EXPECT_EQ(r.widthTraffic[0].reads, width + resolve);
  // ao_sample's reads come after them: centre, four neighbours, up to 16 taps (z and shares in one).
  EXPECT_LE(r.traffic[0].reads - r.widthTraffic[0].reads, (1u + 4u + 16u) * 32 * 32);
}

}  // namespace
}  // namespace sao::bench
