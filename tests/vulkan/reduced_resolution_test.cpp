// resolution_divisor 2 and 4 on Vulkan (under validation and synchronization validation) against
// the CPU reference (float): the final AO, the reduced raw AO and the reduced (A, key) image the
// upsample reads, at the reference tests' bounds (at least 99.9% of the pixels within 2/255, none
// beyond 4/255), at 160x90 with a guard band and the odd sizes 641x359 and 97x61; and no seam at
// the odd sizes (seam_metric.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "analytic_scenes.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "seam_metric.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

Settings reduced(int divisor) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  return s;
}

struct SizeCase {
  std::uint32_t width, height, guard;
};

class ReducedResolution : public VkTest {};

TEST_F(ReducedResolution, MatchesTheCpuReference) {
  const test::Scene scenes[] = {test::planeScene(2.0), test::creaseScene(2.0), test::sphereOnPlaneScene(),
                                test::stairsScene(), test::rodsScene()};
  for (const SizeCase sc : {SizeCase{160, 90, 8}, SizeCase{641, 359, 0}, SizeCase{97, 61, 3}}) {
    const Camera cam = vulkanCamera(sc.width, sc.height, sc.guard, INFINITY, /*reversedZ=*/true);
    for (const test::Scene& scene : scenes) {
      if (sc.width > 200 && scene.name == "plane") continue;  // the seam test runs it
      const VkDepth format = scene.name == "stairs" ? VkDepth::X8D24 : VkDepth::D32F;
      const DepthImage depth = test::renderDepth(scene, cam, cpuFormat(format));
      for (int d : {2, 4}) {
        const std::string name = "vk_" + scene.name + "_" + std::to_string(sc.width) + "x" +
                                 std::to_string(sc.height) + "_d" + std::to_string(d);
        SCOPED_TRACE(name);
        RunResult vk;
        const Status st = runEffect(reduced(d), cam, depth, format, vk);
        ASSERT_TRUE(st.ok()) << st.message;
        cpu::Result ref;
        ASSERT_TRUE(cpu::run(reduced(d), cam, {&depth}, {cpu::Precision::Float, 2}, ref).ok());
        EXPECT_EQ(vk.plan.describe(), ref.plan.describe());
        EXPECT_EQ(std::memcmp(&vk.params, &ref.params, sizeof(ParamBlock)), 0) << "same parameter block";
        const FloatImage& refLow = ref.images[static_cast<std::size_t>(gen::ResourceId::ao_low)].at(0);
        const Agreement f = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_final");
        const Agreement r = compare(vk.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_raw");
        const Agreement l = compare(vk.aoLow, refLow, 0, kWithin, kNever, name + "_low");
        const Agreement k = compare(vk.aoLow, refLow, 1, 0.0, 0.0, name + "_low_key");
        std::printf("AGREEMENT %-28s final max %.3f/255 p99.9 %.3f/255 | raw max %.3f/255 | low max %.3f/255\n",
                    name.c_str(), f.maxAbs * 255, f.p999 * 255, r.maxAbs * 255, l.maxAbs * 255);
        EXPECT_TRUE(acceptable(f)) << "final: max " << f.maxAbs * 255 << "/255, " << f.beyond << " beyond 4/255";
        EXPECT_TRUE(acceptable(r)) << "raw: max " << r.maxAbs * 255 << "/255, " << r.beyond << " beyond 4/255";
        EXPECT_TRUE(acceptable(l)) << "low: max " << l.maxAbs * 255 << "/255, " << l.beyond << " beyond 4/255";
        EXPECT_EQ(k.maxAbs, 0.0) << "the low keys are csz texels, copied";
      }
    }
  }
}

// No row or column of the output stands out at odd sizes: an open plane is 1 everywhere, the
// creases' row (vertical crease) and column (horizontal crease) means are flat (seam_metric.h).
TEST_F(ReducedResolution, NoSeamAtOddSizes) {
  for (const SizeCase sc : {SizeCase{641, 359, 0}, SizeCase{97, 61, 0}}) {
    const Camera cam = vulkanCamera(sc.width, sc.height, sc.guard, 100.0);
    const DepthImage plane = test::renderDepth(test::planeScene(3.0), cam, DepthFormat::D32F);
    const DepthImage vertical = test::renderDepth(test::creaseScene(2.0), cam, DepthFormat::D32F);
    const DepthImage horizontal = test::renderDepth(test::horizontalCreaseScene(2.0), cam, DepthFormat::D32F);
    for (int d : {2, 4}) {
      RunResult p, v, h;
      ASSERT_TRUE(runEffect(reduced(d), cam, plane, VkDepth::D32F, p).ok());
      ASSERT_TRUE(runEffect(reduced(d), cam, vertical, VkDepth::D32F, v).ok());
      ASSERT_TRUE(runEffect(reduced(d), cam, horizontal, VkDepth::D32F, h).ok());
      EXPECT_EQ(*std::min_element(p.ao.data.begin(), p.ao.data.end()), 1.0f) << sc.width << " d=" << d;
      const std::uint32_t margin = 2 * d;
      const test::SeamScore rows = test::seamScore(v.ao, margin), cols = test::seamScore(h.ao, margin);
      std::printf("Vulkan seam %ux%u d=%d: rows %.4f/255 (row %u), columns %.4f/255 (column %u)\n", sc.width,
                  sc.height, d, rows.row * 255, rows.worstRow, cols.column * 255, cols.worstColumn);
      EXPECT_LT(rows.row, test::kSeamBound) << sc.width << " d=" << d << " row " << rows.worstRow;
      EXPECT_LT(cols.column, test::kSeamBound) << sc.width << " d=" << d << " column " << cols.worstColumn;
    }
  }
}

}  // namespace
}  // namespace sao::vktest
