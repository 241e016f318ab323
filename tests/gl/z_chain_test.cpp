// The z chain in one dispatch per layer (linear_z / linear_z2 write levels 0-7, each invocation
// walking up the rotated grid from its 2x2 block; effect/sao.glsl, SAO_CHAIN_FROM_BLOCK) equals
// the CPU reference's level-by-level chain bit for bit, on every level, for chains of 1 to 8
// levels, odd extents, 1-texel-wide levels, guard bands and the second depth layer; so does the
// width pass's width_share chain (thickness_model 1).
#include <epoxy/gl.h>

#include <cstring>

#include "gl_support.h"
#include "image_compare.h"
#include "sao/schedule.h"
#include "z_chain_cases.h"

namespace sao::gltest {
namespace {

class ZChain : public GlTest, public ::testing::WithParamInterface<test::ZChainCase> {};

TEST_P(ZChain, EveryLevelEqualsTheCpuChainBitForBit) {
  const test::ZChainCase& c = GetParam();
  const Camera cam = camera(c.width, c.height, c.guard);
  for (const bool twoLayer : {false, true}) {
    SCOPED_TRACE(twoLayer ? "two layers" : "one layer");
    const test::ZChainReference z = test::zChainReference(c, cam, twoLayer);
    ASSERT_TRUE(z.status.ok()) << z.status.message;
    const Settings& settings = z.settings;
    const DepthImage &depth = z.depth, &depth2 = z.depth2;
    const cpu::Result& ref = z.cpu;

    const GLuint tex = uploadDepth(depth, GlDepth::D32F);
    const GLuint tex2 = twoLayer ? uploadDepth(depth2, GlDepth::D32F) : 0;
    gl::Inputs gi;
    gi.depth = {tex, internalFormat(GlDepth::D32F)};
    gi.depth2 = {tex2, tex2 ? internalFormat(GlDepth::D32F) : 0};
    auto effect = makeEffect();
    const Status st = effect->render(cam, settings, gi);
    ASSERT_TRUE(st.ok()) << st.message;
    const std::uint32_t levels = effect->plan().cszLevels;
    ASSERT_EQ(levels, ref.plan.cszLevels);
    ASSERT_EQ(ref.csz.size(), levels);

    // One dispatch per layer: linear_z, and linear_z2 for the second (a pass is one dispatch).
    std::uint32_t zDispatches = 0;
    for (const ScheduledDispatch& d : makeSchedule(effect->plan()).dispatches)
      if (d.pass == gen::PassId::linear_z || d.pass == gen::PassId::linear_z2) ++zDispatches;
    EXPECT_EQ(zDispatches, twoLayer ? 2u : 1u) << levels << " levels";

    for (std::uint32_t m = 0; m < levels; ++m) {
      EXPECT_EQ(test::differingValues(readTextureLevel(effect->texture(gen::ResourceId::csz), m), ref.csz[m]), 0u)
          << c.name << " csz level " << m << " of " << levels;
      if (twoLayer)
        EXPECT_EQ(test::differingValues(readTextureLevel(effect->texture(gen::ResourceId::csz2), m), ref.csz2[m]), 0u)
            << c.name << " csz2 level " << m << " of " << levels;
    }
    deleteTexture(tex);
    deleteTexture(tex2);
  }
}

// thickness_model 1: the width pass (shared-memory bit scans over 16x16 tiles, effect/sao.glsl)
// finds the runs the CPU reference's walk finds, and its chain copies csz's rotated grid: every
// level of width_share equals the CPU's bit for bit (blocks of 1 .. 40 texels, sky, runs across
// block edges; the same extents, guard bands and 1-texel levels).
TEST_P(ZChain, WidthShareEqualsTheCpuBitForBit) {
  const test::ZChainCase& c = GetParam();
  const Camera cam = camera(c.width, c.height, c.guard);
  const test::ZChainReference z = test::widthShareReference(c, cam);
  ASSERT_TRUE(z.status.ok()) << z.status.message;
  const std::vector<FloatImage>& ref = z.cpu.images[std::size_t(gen::ResourceId::width_share)];
  const GLuint tex = uploadDepth(z.depth, GlDepth::D32F);
  gl::Inputs gi;
  gi.depth = {tex, internalFormat(GlDepth::D32F)};
  auto effect = makeEffect();
  const Status st = effect->render(cam, z.settings, gi);
  ASSERT_TRUE(st.ok()) << st.message;
  const std::uint32_t levels = effect->plan().cszLevels;
  ASSERT_EQ(ref.size(), levels);
  std::size_t narrow = 0;  // shares (x or y) under 1: runs the pass measured
  for (float v : ref[0].data) narrow += v < 1.0f;
  if (c.width * c.height >= 1000)  // the 1x1 and 37x23 images are mostly runs to their edges: wide
    EXPECT_GT(narrow, ref[0].data.size() / 8) << "the blocks must give measured runs, or the comparison says little";
  for (std::uint32_t m = 0; m < levels; ++m)
    EXPECT_EQ(test::differingValues(readTextureLevel(effect->texture(gen::ResourceId::width_share), m, 2), ref[m]), 0u)
        << c.name << " width_share level " << m << " of " << levels;
  deleteTexture(tex);
}

INSTANTIATE_TEST_SUITE_P(Cases, ZChain, ::testing::ValuesIn(test::zChainCases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace sao::gltest
