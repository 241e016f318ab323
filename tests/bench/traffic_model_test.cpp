// The memory-traffic model of sao-bench: LRU caches with known hits and misses, the 2D tiling of
// texels into lines, the machine's SMs and shared L2, and ao_sample's replayed reads on a plane:
// the z hierarchy reads fewer lines than full-resolution z at a large radius (the paper's claim).
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <numbers>

#include "untuned_settings.h"
#include "sao/presets.h"
#include "traffic_model.h"
#include "traffic_replay.h"

namespace sao::bench {
namespace {

std::vector<bool> hits(LruCache& c, const std::vector<std::uint64_t>& lines) {
  std::vector<bool> out;
  for (std::uint64_t l : lines) out.push_back(c.access(l));
  return out;
}

TEST(TrafficLru, FullyAssociativeEvictsTheLeastRecentlyUsed) {
  LruCache c({4 * 64, 64, 0});  // 4 lines, one set
  EXPECT_EQ(c.sets(), 1u);
  // 1 2 3 4 miss; 1 hits (now 2 is the oldest); 5 evicts 2; 2 misses and evicts 3; 1 still hits.
  EXPECT_EQ(hits(c, {1, 2, 3, 4, 1, 5, 2, 1, 3}),
            (std::vector<bool>{false, false, false, false, true, false, false, true, false}));
}

TEST(TrafficLru, SetsAreIndependent) {
  LruCache c({4 * 64, 64, 2});  // 2 sets of 2 ways; even lines in set 0
  EXPECT_EQ(c.sets(), 2u);
  // 0 2 4 fill set 0 and evict 0; 0 comes back and evicts 2; line 1 lives in set 1 and survives.
  EXPECT_EQ(hits(c, {1, 0, 2, 4, 0, 1, 4, 2}),
            (std::vector<bool>{false, false, false, false, false, true, true, false}));
}

TEST(TrafficLayout, TilesFollowLineAndTexelSize) {
  auto tile = [](std::uint32_t line, std::uint32_t texel, TexelLayout l) {
    const Tile t = tileOf(line, texel, l);
    return std::pair(t.w, t.h);
  };
  EXPECT_EQ(tile(128, 4, TexelLayout::Tiled), std::pair(8u, 4u));   // r32f, GPU lines
  EXPECT_EQ(tile(64, 4, TexelLayout::Tiled), std::pair(4u, 4u));
  EXPECT_EQ(tile(128, 8, TexelLayout::Tiled), std::pair(4u, 4u));   // rgba16f
  EXPECT_EQ(tile(128, 16, TexelLayout::Tiled), std::pair(4u, 2u));  // rgba32f
  EXPECT_EQ(tile(64, 4, TexelLayout::Linear), std::pair(16u, 1u));
}

TEST(TrafficLayout, TexelsOfATileShareALineAndLevelsFollowEachOther) {
  // r32f 20x10 level 0 (3x3 tiles of 8x4), 10x5 level 1 (2x2 tiles), then an rgba16f 4x4 surface.
  const AddressMap map(TexelLayout::Tiled, 128, {{4, {{20, 10}, {10, 5}}}, {8, {{4, 4}}}});
  auto line = [&](int s, int l, int x, int y) { return map.line({0, std::uint8_t(s), std::uint8_t(l), x, y}); };
  EXPECT_EQ(line(0, 0, 0, 0), line(0, 0, 7, 3));
  EXPECT_EQ(line(0, 0, 8, 0), 1u);
  EXPECT_EQ(line(0, 0, 0, 4), 3u);
  EXPECT_EQ(line(0, 0, 19, 9), 8u);
  EXPECT_EQ(line(0, 1, 0, 0), 9u);
  EXPECT_EQ(line(0, 1, 9, 4), 12u);
  EXPECT_EQ(line(1, 0, 0, 0), 13u);
  EXPECT_EQ(line(1, 0, 3, 3), 13u);
}

Machine tinyMachine(std::uint32_t sms, bool sharedL2) {
  Machine m;
  m.name = "tiny";
  m.sms = sms;
  m.groupsInFlight = 1;
  m.warpLanes = 4;
  m.l1 = {4 * 128, 128, 0};
  m.l2 = {16 * 128, 128, 4};
  m.l2Shared = sharedL2;
  return m;
}

GroupReads groupReading(int x, int y, int times) {
  GroupReads g;
  for (int i = 0; i < times; ++i) {
    g.beginStep();
    g.read(0, 0, 0, x, y);
  }
  g.beginStep();
  return g;
}

TEST(TrafficModelRun, RepeatedReadsMissOnceAndTheSharedL2ServesTheSecondSm) {
  const std::vector<SurfaceShape> surfaces = {{4, {{64, 64}}}};
  for (bool shared : {true, false}) {
    TrafficModel model(tinyMachine(2, shared), surfaces);
    model.add(groupReading(3, 2, 10));  // SM 0
    model.add(groupReading(5, 1, 10));  // SM 1: the same 8x4 tile
    model.finish();
    const Traffic& t = model.traffic();
    EXPECT_EQ(t.reads, 20u);
    EXPECT_EQ(t.l1Misses, 2u);                 // one per SM
    EXPECT_EQ(t.l2Misses, shared ? 1u : 2u);  // a private L2 fetches the line again
    EXPECT_EQ(t.l2Bytes(), 256u);
  }
}

TEST(TrafficModelRun, RejectsMachinesItCannotModel) {
  Machine m = tinyMachine(1, true);
  m.l2.lineBytes = 64;
  EXPECT_NE(validate(m).message.find("L1 and L2 lines differ"), std::string::npos);
  m = tinyMachine(1, true);
  m.l1.lineBytes = 96;
  EXPECT_NE(validate(m).message.find("power of two"), std::string::npos);
  m = tinyMachine(1, true);
  m.l2.ways = 3;
  EXPECT_NE(validate(m).message.find("whole sets"), std::string::npos);
  m = tinyMachine(0, true);
  EXPECT_FALSE(validate(m));
  EXPECT_TRUE(validate(tinyMachine(2, false)));
}

// A camera-facing plane 2 m away, 256x256, as linear z: every pixel has geometry.
struct Plane {
  Camera camera = perspectiveCamera(std::numbers::pi / 3, 256, 256, 0.1, 100.0, ClipDepth::NegativeOneToOne, false);
  DepthImage depth{{256, 256}, DepthFormat::LinearZ,
                   std::vector<std::uint32_t>(256 * 256, std::bit_cast<std::uint32_t>(-2.0f))};
};

TEST(TrafficReplay, TheHierarchyReadsFewerLinesAtALargeRadius) {
  const Plane plane;
  std::unique_ptr<TrafficScene> scene;
  ASSERT_TRUE(TrafficScene::create(plane.depth, plane.camera, scene));
  Settings s = test::untunedMedium();  // 11 taps
  s.radius = 1.0f;                              // ~110 px at 2 m: taps up to MIP level 3
  Machine m = tinyMachine(2, true);
  m.warpLanes = 32;
  m.l1 = {16 * 1024, 128, 0};
  m.l2 = {64 * 1024, 128, 16};
  const std::vector<Machine> machines = {m};
  ReplayResult mip, flat, alchemy;
  ASSERT_TRUE(scene->replay(s, {"SAO", true, false, 4}, machines, mip));
  ASSERT_TRUE(scene->replay(s, {"no hierarchy", false, false, 4}, machines, flat));
  ASSERT_TRUE(scene->replay(s, {"AlchemyAO-style", false, true, 4}, machines, alchemy));
  EXPECT_EQ(mip.pixels, 256u * 256u);
  EXPECT_GE(mip.maxMip, 3);
  EXPECT_EQ(flat.maxMip, 0);
  // Per pixel: the centre, four neighbours (or one normal) and 11 taps, no sky.
  EXPECT_EQ(mip.traffic[0].reads, 16u * 256 * 256);
  EXPECT_EQ(flat.traffic[0].reads, 16u * 256 * 256);
  EXPECT_EQ(alchemy.traffic[0].reads, 13u * 256 * 256);
  std::printf("[traffic] plane 256x256, r 1 m: L1 misses with the hierarchy %llu, without %llu\n",
              (unsigned long long)mip.traffic[0].l1Misses, (unsigned long long)flat.traffic[0].l1Misses);
  // Same reads, fewer L1 misses: far taps come from coarse levels that stay in the L1.
  EXPECT_LT(4 * mip.traffic[0].l1Misses, flat.traffic[0].l1Misses)
      << mip.traffic[0].l1Misses << " vs " << flat.traffic[0].l1Misses;
}

TEST(TrafficReplay, AReducedResolutionSamplesOnePixelPerBlock) {
  const Plane plane;
  std::unique_ptr<TrafficScene> scene;
  ASSERT_TRUE(TrafficScene::create(plane.depth, plane.camera, scene));
  Settings s = test::untunedMedium();  // 11 taps
  s.resolution_divisor = 2;  // ao_sample runs on 128x128, each pixel at its block's representative
  const std::vector<Machine> machines = {tinyMachine(1, true)};
  ReplayResult r;
  ASSERT_TRUE(scene->replay(s, {"SAO", true, false, 4}, machines, r));
  EXPECT_EQ(r.pixels, 128u * 128u);
  EXPECT_EQ(r.traffic[0].reads, 16u * 128 * 128);
}

TEST(TrafficReplay, RefusesBadInputWithAClearMessage) {
  const Plane plane;
  std::unique_ptr<TrafficScene> scene;
  const DepthImage empty{{0, 0}, DepthFormat::LinearZ, {}};
  Status st = TrafficScene::create(empty, plane.camera, scene);  // the CPU reference's own check
  EXPECT_NE(st.message.find("empty"), std::string::npos) << st.message;
  EXPECT_EQ(scene, nullptr);

  ASSERT_TRUE(TrafficScene::create(plane.depth, plane.camera, scene));
  Machine bad = tinyMachine(1, true);
  bad.l1.bytes = 100;
  const std::vector<Machine> machines = {bad};
  ReplayResult r;
  st = scene->replay(presetSettings(Preset::Medium), {"SAO", true, false, 4}, machines, r);
  EXPECT_NE(st.message.find("traffic model 'tiny': L1 of 100 bytes"), std::string::npos) << st.message;
}

}  // namespace
}  // namespace sao::bench
