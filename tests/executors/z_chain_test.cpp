// The z chain in one dispatch per layer (linear_z / linear_z2 write levels 0-7, each invocation
// walking up the rotated grid from its 2x2 block; effect/sao.glsl, SAO_CHAIN_FROM_BLOCK) equals the
// CPU reference's level-by-level chain bit for bit, on every level, for chains of 1 to 8 levels,
// odd extents, 1-texel-wide levels, guard bands and the second depth layer (Vulkan: array slots past
// the chain's end bound, never written); so do the width passes' width_run and csz_share chains
// (thickness_model 1). Each case under GL's and Vulkan's depth convention.
#include "harness.h"
#include "image_compare.h"
#include "sao/schedule.h"
#include "z_chain_cases.h"
#include "../../effect/cpu/sao_math.h"

namespace sao::exectest {
namespace {

std::string caseName(const test::ZChainCase& c) { return c.name; }

// The distinct depth is linearised under both clip depth ranges.
std::vector<std::pair<const char*, Camera>> cameras(const test::ZChainCase& c) {
  return {{"opengl", test::openglCamera(c.width, c.height, c.guard)},
          {"vulkan", test::vulkanCamera(c.width, c.height, c.guard)}};
}

// Every level of `resource` equals the CPU's `levels` bit for bit.
void expectLevelsEqual(Executor& e, gen::ResourceId resource, const std::vector<FloatImage>& levels,
                       const std::string& what) {
  for (std::uint32_t m = 0; m < levels.size(); ++m)
    EXPECT_EQ(test::differingValues(e.image(resource, m), levels[m]), 0u)
        << what << " level " << m << " of " << levels.size();
}

using ZChain = ApiCaseTest<test::ZChainCase>;

TEST_P(ZChain, EveryLevelEqualsTheCpuChainBitForBit) {
  const test::ZChainCase& c = param();
  auto e = make();
  for (const auto& [convention, cam] : cameras(c))
    for (const bool twoLayer : {false, true}) {
      SCOPED_TRACE(std::string(convention) + (twoLayer ? ", two layers" : ", one layer"));
      const test::ZChainReference z = test::zChainReference(c, cam, twoLayer);
      ASSERT_TRUE(z.status.ok()) << z.status.message;
      Frame f;
      f.settings = z.settings;
      f.camera = cam;
      f.depth = &z.depth;
      f.depth2 = twoLayer ? &z.depth2 : nullptr;
      const Status st = e->render(f);
      ASSERT_TRUE(st.ok()) << st.message;
      const std::uint32_t levels = e->plan().cszLevels;
      ASSERT_EQ(levels, z.cpu.plan.cszLevels);
      ASSERT_EQ(z.cpu.csz.size(), levels);
      EXPECT_EQ(e->plan().image(gen::ResourceId::csz2) != nullptr, twoLayer) << "csz2 only with the second layer";

      // One dispatch per layer: linear_z, and linear_z2 for the second (a pass is one dispatch).
      std::uint32_t zDispatches = 0;
      for (const ScheduledDispatch& d : makeSchedule(e->plan()).dispatches)
        zDispatches += d.pass == gen::PassId::linear_z || d.pass == gen::PassId::linear_z2;
      EXPECT_EQ(zDispatches, twoLayer ? 2u : 1u) << levels << " levels";

      expectLevelsEqual(*e, gen::ResourceId::csz, z.cpu.csz, c.name + " csz");
      if (twoLayer) expectLevelsEqual(*e, gen::ResourceId::csz2, z.cpu.csz2, c.name + " csz2");
    }
}

// thickness_model 1: the width pass (level 0 by shared-memory bit scans over 16x16 tiles, the
// levels above by a walk on each level, effect/sao.glsl) finds the runs the CPU reference's walk
// finds, and width_resolve takes a wide run's share from the levels above as the CPU does: every
// level of width_run and of csz_share (z and the packed shares) equals the CPU's bit for bit (blocks
// of 1 .. 40 texels, sky, runs across block edges; the same extents, guard bands and 1-texel levels).
TEST_P(ZChain, WidthShareEqualsTheCpuBitForBit) {
  const test::ZChainCase& c = param();
  auto e = make();
  for (const auto& [convention, cam] : cameras(c)) {
    SCOPED_TRACE(convention);
    const test::ZChainReference z = test::widthShareReference(c, cam);
    ASSERT_TRUE(z.status.ok()) << z.status.message;
    const std::vector<FloatImage>& run = z.cpu.images[std::size_t(gen::ResourceId::width_run)];
    const std::vector<FloatImage>& ref = z.cpu.images[std::size_t(gen::ResourceId::csz_share)];
    Frame f;
    f.settings = z.settings;
    f.camera = cam;
    f.depth = &z.depth;
    const Status st = e->render(f);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_EQ(ref.size(), e->plan().cszLevels);
    ASSERT_EQ(run.size(), e->plan().cszLevels);
    std::size_t narrow = 0;    // level-0 shares (x or y) under 1: runs the pass measured
    std::size_t resolved = 0;  // level-0 shares wide on level 0 and measured above it
    for (std::size_t t = 0; 2 * t + 1 < ref[0].data.size(); ++t) {
      float share[2];
      cpu::detail::unpackShares(ref[0].data[2 * t + 1], share[0], share[1]);
      for (std::size_t a = 0; a < 2; ++a) {
        narrow += run[0].data[2 * t + a] < 1.0f;
        resolved += run[0].data[2 * t + a] >= 1.0f && share[a] < 1.0f;
      }
    }
    if (c.width * c.height >= 1000) {  // the 1x1 and 37x23 images are mostly runs to their edges: wide
      EXPECT_GT(narrow, ref[0].data.size() / 8) << "the blocks must give measured runs, or the comparison says little";
      EXPECT_GT(resolved, 0u) << "some runs must be wide at level 0 and narrow above, or width_resolve is untested";
    }
    expectLevelsEqual(*e, gen::ResourceId::width_run, run, c.name + " width_run");
    expectLevelsEqual(*e, gen::ResourceId::csz_share, ref, c.name + " csz_share");
  }
}

SAO_INSTANTIATE_API_CASES(ZChain, test::zChainCases());

}  // namespace
}  // namespace sao::exectest
