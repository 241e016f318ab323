// The z chain in one dispatch per layer (linear_z / linear_z2 write levels 0-7 as a storage-image
// array, each invocation walking up the rotated grid from its 2x2 block; effect/sao.glsl,
// SAO_CHAIN_FROM_BLOCK) equals the CPU reference's level-by-level chain bit for bit, on every level,
// for chains of 1 to 8 levels, odd extents, 1-texel-wide levels, guard bands and the second depth
// layer, under the validation layers (array slots past the chain's end bound, never written); so
// does the width pass's width_share chain (thickness_model 1).
#include <cstdint>

#include "image_compare.h"
#include "vk_support.h"
#include "sao/schedule.h"
#include "z_chain_cases.h"

namespace sao::vktest {
namespace {

class ZChain : public VkTest, public ::testing::WithParamInterface<test::ZChainCase> {};

TEST_P(ZChain, EveryLevelEqualsTheCpuChainBitForBit) {
  const test::ZChainCase& c = GetParam();
  const Camera cam = vulkanCamera(c.width, c.height, c.guard);
  for (const bool twoLayer : {false, true}) {
    SCOPED_TRACE(twoLayer ? "two layers" : "one layer");
    const test::ZChainReference z = test::zChainReference(c, cam, twoLayer);
    ASSERT_TRUE(z.status.ok()) << z.status.message;
    const Settings& settings = z.settings;
    const DepthImage &depth = z.depth, &depth2 = z.depth2;
    const cpu::Result& ref = z.cpu;

    RunOptions options;
    options.depth2 = twoLayer ? &depth2 : nullptr;
    options.readChain = true;
    RunResult r;
    const Status st = runEffect(settings, cam, depth, VkDepth::D32F, r, options);
    ASSERT_TRUE(st.ok()) << st.message;
    const std::uint32_t levels = r.plan.cszLevels;
    ASSERT_EQ(levels, ref.plan.cszLevels);
    ASSERT_EQ(r.csz.size(), levels);
    ASSERT_EQ(r.csz2.size(), twoLayer ? levels : 0u);

    std::uint32_t zDispatches = 0;
    for (const ScheduledDispatch& d : makeSchedule(r.plan).dispatches)
      if (d.pass == gen::PassId::linear_z || d.pass == gen::PassId::linear_z2) ++zDispatches;
    EXPECT_EQ(zDispatches, twoLayer ? 2u : 1u) << levels << " levels";

    for (std::uint32_t m = 0; m < levels; ++m) {
      EXPECT_EQ(test::differingValues(r.csz[m], ref.csz[m]), 0u) << c.name << " csz level " << m << " of " << levels;
      if (twoLayer)
        EXPECT_EQ(test::differingValues(r.csz2[m], ref.csz2[m]), 0u) << c.name << " csz2 level " << m << " of " << levels;
    }
  }
}

// thickness_model 1: every level of width_share (the width pass's shared-memory bit scans and its
// chain) equals the CPU reference's bit for bit (tests/gl/z_chain_test.cpp says why these inputs).
TEST_P(ZChain, WidthShareEqualsTheCpuBitForBit) {
  const test::ZChainCase& c = GetParam();
  const Camera cam = vulkanCamera(c.width, c.height, c.guard);
  const test::ZChainReference z = test::widthShareReference(c, cam);
  ASSERT_TRUE(z.status.ok()) << z.status.message;
  const std::vector<FloatImage>& ref = z.cpu.images[std::size_t(gen::ResourceId::width_share)];
  RunOptions options;
  options.readChain = true;
  RunResult r;
  const Status st = runEffect(z.settings, cam, z.depth, VkDepth::D32F, r, options);
  ASSERT_TRUE(st.ok()) << st.message;
  ASSERT_EQ(r.widthShare.size(), ref.size());
  for (std::size_t m = 0; m < ref.size(); ++m)
    EXPECT_EQ(test::differingValues(r.widthShare[m], ref[m]), 0u) << c.name << " width_share level " << m;
}

INSTANTIATE_TEST_SUITE_P(Cases, ZChain, ::testing::ValuesIn(test::zChainCases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace sao::vktest
