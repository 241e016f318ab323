// half_intermediates (HALF_INTERMEDIATES: rg16f ao_raw and ao_low) against the CPU reference (float):
// the images are rg16f and hold binary16 values; the keys are the CPU's bit for bit (csz level 0 times
// key_scale, rounded to binary16 in the shader, so the store does not round again); A raw, low and final
// at the agreement bounds, at full, half and quarter resolution, with a guard band and at an odd size,
// under GL's and Vulkan's depth conventions. Switching back restores the rg32f path bit for bit.
#include <algorithm>
#include <cstdio>
#include <string>

#include "harness.h"
#include "sao/presets.h"

namespace sao::exectest {
namespace {

Settings halfSettings(int divisor) {
  Settings s = presetSettings(Preset::Medium);
  s.resolution_divisor = divisor;
  s.half_intermediates = true;
  return s;
}

// The planned format (what both backends allocate) and whether every stored value is a binary16
// value: rg16f storage rounds every value, rg32f keeps the float keys and A unrounded.
void expectStorage(Executor& e, gen::ResourceId resource, gen::Format format) {
  const std::string_view name = gen::kResources[std::size_t(resource)].name;
  ASSERT_NE(e.plan().image(resource), nullptr) << name;
  EXPECT_EQ(e.plan().image(resource)->format, format) << name;
  const FloatImage image = e.image(resource);
  ASSERT_FALSE(image.data.empty());
  const bool allHalves = std::ranges::all_of(image.data, [](float v) { return cpu::quantizeHalf(v) == v; });
  EXPECT_EQ(allHalves, format == gen::Format::RG16F) << name;
}

struct SizeCase {
  std::string name;
  Camera camera;
};
std::string caseName(const SizeCase& c) { return c.name; }
std::vector<SizeCase> sizeCases() {
  return {{"160x90_opengl", test::openglCamera(160, 90, 8)},
          {"160x90_vulkan_reversed_infinite", test::vulkanCamera(160, 90, 8, INFINITY, /*reversedZ=*/true)},
          {"97x61_opengl", test::openglCamera(97, 61, 3)},
          {"97x61_vulkan_reversed_infinite", test::vulkanCamera(97, 61, 3, INFINITY, /*reversedZ=*/true)}};
}

using HalfIntermediates = ApiCaseTest<SizeCase>;
TEST_P(HalfIntermediates, MatchTheCpuReference) {
  const Camera& cam = param().camera;
  auto e = make();
  for (const char* scene : {"crease", "sphere", "stairs", "rods"}) {
    Frame f;
    f.camera = cam;
    f.format = std::string(scene) == "stairs" ? Depth::D24 : Depth::D32F;
    const DepthImage depth = test::renderDepth(sceneByName(scene), cam, cpuFormat(f.format));
    f.depth = &depth;
    for (int d : {1, 2, 4}) {
      const std::string name = std::string("half_") + scene + "_" + param().name + "_d" + std::to_string(d);
      SCOPED_TRACE(name);
      f.settings = halfSettings(d);
      const Status st = e->render(f);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Result ref;
      ASSERT_TRUE(runCpu(f, ref).ok());
      EXPECT_EQ(e->plan().describe(), ref.plan.describe());
      expectAgreesWithCpu(*e, ref, name);  // final and raw A at the bounds, the parameter blocks
      expectStorage(*e, gen::ResourceId::ao_raw, gen::Format::RG16F);
      const Agreement rk = compare(api(), e->image(gen::ResourceId::ao_raw), ref.aoRaw, 1, 0.0, 0.0, name + "_raw_key");
      EXPECT_EQ(rk.maxAbs, 0.0) << "raw keys: csz level 0 times key_scale, rounded alike";
      if (d == 1) continue;
      expectStorage(*e, gen::ResourceId::ao_low, gen::Format::RG16F);
      const FloatImage low = e->image(gen::ResourceId::ao_low);
      const FloatImage& refLow = ref.images[std::size_t(gen::ResourceId::ao_low)].at(0);
      const Agreement l = compare(api(), low, refLow, 0, kWithin, kNever, name + "_low");
      const Agreement lk = compare(api(), low, refLow, 1, 0.0, 0.0, name + "_low_key");
      std::printf("AGREEMENT %-7s %-34s low max %.4f/255\n", toString(api()), name.c_str(), l.maxAbs * 255);
      EXPECT_TRUE(acceptable(l)) << "low: max " << l.maxAbs * 255 << "/255, " << l.beyond << " beyond 4/255";
      EXPECT_EQ(lk.maxAbs, 0.0) << "the low keys are the raw keys, copied";
    }
  }
}
SAO_INSTANTIATE_API_CASES(HalfIntermediates, sizeCases());

// Switching half_intermediates on and off between frames plans again with the intermediates in the
// other format, and the rg32f frame after a half one is the rg32f frame before it.
using HalfIntermediatesSwitch = ApiTest;
TEST_P(HalfIntermediatesSwitch, SwitchingBackRestoresTheFloatPath) {
  const Camera cam = test::openglCamera(160, 90, 8);
  const DepthImage depth = test::renderDepth(sceneByName("crease"), cam, DepthFormat::D32F);
  Frame f;
  f.camera = cam;
  f.depth = &depth;
  f.settings = presetSettings(Preset::Medium);
  f.settings.half_intermediates = false;
  const Settings full = f.settings, half = halfSettings(full.resolution_divisor);
  auto e = make();
  ASSERT_TRUE(e->render(f).ok());
  expectStorage(*e, gen::ResourceId::ao_raw, gen::Format::RG32F);
  const FloatImage before = e->output();
  for (const Settings& s : {half, full}) {
    const std::uint64_t plans = e->plans();
    f.settings = s;
    ASSERT_TRUE(e->render(f).ok());
    EXPECT_EQ(e->plans(), plans + 1) << "a new plan";
    expectStorage(*e, gen::ResourceId::ao_raw, s.half_intermediates ? gen::Format::RG16F : gen::Format::RG32F);
  }
  EXPECT_EQ(e->output().data, before.data);
}
SAO_INSTANTIATE_APIS(HalfIntermediatesSwitch);

}  // namespace
}  // namespace sao::exectest
