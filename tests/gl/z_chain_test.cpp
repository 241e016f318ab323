// The z chain in one dispatch per layer (linear_z / linear_z2 write levels 0-7, each invocation
// walking up the rotated grid from its 2x2 block; effect/sao.glsl, SAO_CHAIN_FROM_BLOCK) equals
// the CPU reference's level-by-level chain bit for bit, on every level, for chains of 1 to 8
// levels, odd extents, 1-texel-wide levels, guard bands and the second depth layer.
#include <epoxy/gl.h>

#include <cstring>

#include "gl_support.h"
#include "image_compare.h"
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

    // One dispatch per layer: linear_z, and linear_z2 for the second.
    std::uint32_t zDispatches = 0;
    for (const PlannedPass& p : effect->plan().passes)
      if (p.pass == gen::PassId::linear_z || p.pass == gen::PassId::linear_z2) {
        EXPECT_EQ(p.dispatchCount, 1u) << gen::pass(p.pass).name;
        zDispatches += p.dispatchCount;
      }
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

INSTANTIATE_TEST_SUITE_P(Cases, ZChain, ::testing::ValuesIn(test::zChainCases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace sao::gltest
