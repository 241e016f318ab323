// The depth-value contract (sao/image.h) on Vulkan: a D32_SFLOAT image filled by a buffer copy
// holds NaN, infinities and values outside [0, 1] (lavapipe keeps every bit), and the effect reads
// them as sky, bit for bit like the clear value; -0.0 gives the bits of +0.0; R32F linear z sky
// values give the bits of +0.0. csz level 0 is compared with the CPU reference bit for bit.
#include <bit>
#include <string>

#include "depth_contract.h"
#include "image_compare.h"
#include "sao/cpu/reference.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

RunResult render(const Camera& camera, const DepthImage& depth) {
  RunResult r;
  const Status st = runEffect(Settings{}, camera, depth,
                              depth.format == DepthFormat::LinearZ ? VkDepth::R32F : VkDepth::D32F, r);
  EXPECT_TRUE(st.ok()) << st.message;
  return r;
}

TEST_F(VkTest, DepthContractBadHardwareDepthIsSkyLikeTheClearValue) {
  for (bool reversedZ : {false, true}) {
    const Camera camera = test::contractCamera(reversedZ);
    const DepthImage depth = test::contractDepth(camera, DepthFormat::D32F);
    const RunResult clear = render(camera, test::planted(depth, float(test::clearDepth(camera))));
    ASSERT_FALSE(clear.ao.data.empty());
    for (float v : test::badHardwareDepthValues()) {
      SCOPED_TRACE(std::string(reversedZ ? "reversed-Z" : "standard") + ", d = " + test::valueName(v));
      const DepthImage bad = test::planted(depth, v);
      const RunResult r = render(camera, bad);
      EXPECT_EQ(test::plantedNotSky(r.csz0), 0u);
      EXPECT_TRUE(test::sameBits(r.csz0, clear.csz0));
      EXPECT_TRUE(test::sameBits(r.ao, clear.ao));
      EXPECT_TRUE(test::sameBits(r.csz0, test::cpuCsz0(camera, bad)));
    }
  }
}

TEST_F(VkTest, DepthContractMinusZeroIsZero) { test::expectMinusZeroIsZero(render); }

TEST_F(VkTest, DepthContractLinearZSkyValuesAreSky) { test::expectLinearZSkyValuesAreSky(render); }

}  // namespace
}  // namespace sao::vktest
