// half_intermediates (HALF_INTERMEDIATES: rg16f ao_raw and ao_low) on Vulkan (under
// validation and synchronization validation) against the CPU reference (float): the images are
// VK_FORMAT_R16G16_SFLOAT; the keys are the CPU's bit for bit; A raw, low and final at the
// reference tests' bounds (99.9% within 2/255, none beyond 4/255), at full, half and quarter
// resolution, with a guard band and at an odd size.
#include <cstdio>
#include <cstring>
#include <string>

#include "analytic_scenes.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

Settings halfSettings(int divisor) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  s.half_intermediates = true;
  return s;
}

class HalfIntermediates : public VkTest {};

TEST_F(HalfIntermediates, MatchTheCpuReference) {
  const test::Scene scenes[] = {test::creaseScene(2.0), test::sphereOnPlaneScene(), test::stairsScene(),
                                test::rodsScene()};
  struct SizeCase {
    std::uint32_t width, height, guard;
  };
  for (const SizeCase sc : {SizeCase{160, 90, 8}, SizeCase{97, 61, 3}}) {
    const Camera cam = vulkanCamera(sc.width, sc.height, sc.guard, INFINITY, /*reversedZ=*/true);
    for (const test::Scene& scene : scenes) {
      const VkDepth format = scene.name == "stairs" ? VkDepth::X8D24 : VkDepth::D32F;
      const DepthImage depth = test::renderDepth(scene, cam, cpuFormat(format));
      for (int d : {1, 2, 4}) {
        const std::string name = "vk_" + scene.name + "_" + std::to_string(sc.width) + "x" +
                                 std::to_string(sc.height) + "_d" + std::to_string(d);
        SCOPED_TRACE(name);
        const Settings settings = halfSettings(d);
        RunResult vk;
        const Status st = runEffect(settings, cam, depth, format, vk);
        ASSERT_TRUE(st.ok()) << st.message;
        cpu::Result ref;
        ASSERT_TRUE(cpu::run(settings, cam, {&depth}, {cpu::Precision::Float, 2}, ref).ok());
        EXPECT_EQ(vk.plan.describe(), ref.plan.describe());
        EXPECT_EQ(std::memcmp(&vk.params, &ref.params, sizeof(ParamBlock)), 0) << "same parameter block";
        EXPECT_EQ(vk.aoRawFormat, VK_FORMAT_R16G16_SFLOAT);
        const Agreement f = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_half_final");
        const Agreement r = compare(vk.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_half_raw");
        const Agreement rk = compare(vk.aoRaw, ref.aoRaw, 1, 0.0, 0.0, name + "_half_raw_key");
        double lowMax = 0.0;
        if (d > 1) {
          const FloatImage& refLow = ref.images[static_cast<std::size_t>(gen::ResourceId::ao_low)].at(0);
          const Agreement l = compare(vk.aoLow, refLow, 0, kWithin, kNever, name + "_half_low");
          const Agreement lk = compare(vk.aoLow, refLow, 1, 0.0, 0.0, name + "_half_low_key");
          EXPECT_TRUE(acceptable(l)) << "low: max " << l.maxAbs * 255 << "/255, " << l.beyond << " beyond 4/255";
          EXPECT_EQ(lk.maxAbs, 0.0) << "the low keys are the raw keys, copied";
          lowMax = l.maxAbs;
        }
        std::printf("AGREEMENT half %-26s final max %.3f/255 p99.9 %.3f/255 | raw max %.3f/255 | low max %.3f/255\n",
                    name.c_str(), f.maxAbs * 255, f.p999 * 255, r.maxAbs * 255, lowMax * 255);
        EXPECT_TRUE(acceptable(f)) << "final: max " << f.maxAbs * 255 << "/255, " << f.beyond << " beyond 4/255";
        EXPECT_TRUE(acceptable(r)) << "raw: max " << r.maxAbs * 255 << "/255, " << r.beyond << " beyond 4/255";
        EXPECT_EQ(rk.maxAbs, 0.0) << "raw keys: csz level 0 times key_scale, rounded alike";
      }
    }
  }
}

}  // namespace
}  // namespace sao::vktest
