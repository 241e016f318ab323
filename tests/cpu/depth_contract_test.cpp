// The depth-value contract (sao/image.h) on the CPU reference, float and double: NaN, +-Inf, values
// below 0 or above 1 in hardware depth are sky, bit for bit like the clear value; -0.0 is 0; linear
// z that is NaN, +-Inf, +-0 or positive is sky. The gl and vulkan tests check the same on the GPU.
#include <gtest/gtest.h>

#include "depth_contract.h"
#include "image_compare.h"
#include "sao/cpu/reference.h"

namespace sao::test {
namespace {

cpu::Result run(const Camera& camera, const DepthImage& depth, cpu::Precision precision) {
  cpu::Inputs in;
  in.depth = &depth;
  cpu::Result r;
  const Status st = cpu::run(Settings{}, camera, in, {precision, 2}, r);
  EXPECT_TRUE(st.ok()) << st.message;
  return r;
}

TEST(DepthContract, BadHardwareDepthIsSkyLikeTheClearValue) {
  for (bool reversedZ : {false, true})
    for (cpu::Precision precision : {cpu::Precision::Float, cpu::Precision::Double}) {
      const Camera camera = contractCamera(reversedZ);
      const DepthImage depth = contractDepth(camera, DepthFormat::D32F);
      const cpu::Result clear = run(camera, planted(depth, float(clearDepth(camera))), precision);
      ASSERT_EQ(plantedNotSky(clear.csz[0]), 0u);
      for (float v : badHardwareDepthValues()) {
        SCOPED_TRACE(std::string(reversedZ ? "reversed-Z, " : "standard, ") + cpu::toString(precision) + ", d = " +
                     valueName(v));
        const cpu::Result bad = run(camera, planted(depth, v), precision);
        EXPECT_EQ(plantedNotSky(bad.csz[0]), 0u);
        EXPECT_TRUE(sameBits(bad.csz[0], clear.csz[0]));
        EXPECT_TRUE(sameBits(bad.ao, clear.ao));
      }
    }
}

TEST(DepthContract, MinusZeroIsZero) {
  for (bool reversedZ : {false, true}) {
    SCOPED_TRACE(reversedZ ? "reversed-Z (-0.0 is the sky)" : "standard (-0.0 is the near plane)");
    const Camera camera = contractCamera(reversedZ);
    const DepthImage depth = contractDepth(camera, DepthFormat::D32F);
    const cpu::Result plus = run(camera, planted(depth, 0.0f), cpu::Precision::Float);
    const cpu::Result minus = run(camera, planted(depth, -0.0f), cpu::Precision::Float);
    EXPECT_TRUE(sameBits(minus.csz[0], plus.csz[0]));
    EXPECT_TRUE(sameBits(minus.ao, plus.ao));
    EXPECT_EQ(plantedNotSky(plus.csz[0]), reversedZ ? 0u : plantedTexels(depth.extent).size());
  }
}

TEST(DepthContract, LinearZSkyValuesAreSkyLikePlusZero) {
  const Camera camera = contractCamera(true);
  const DepthImage depth = contractDepth(camera, DepthFormat::LinearZ);
  const cpu::Result sky = run(camera, planted(depth, 0.0f), cpu::Precision::Float);
  for (float v : skyLinearZValues()) {
    SCOPED_TRACE("z = " + valueName(v));
    const cpu::Result r = run(camera, planted(depth, v), cpu::Precision::Float);
    EXPECT_EQ(plantedNotSky(r.csz[0]), 0u);
    EXPECT_TRUE(sameBits(r.ao, sky.ao));
  }
}

}  // namespace
}  // namespace sao::test
