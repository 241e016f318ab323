// The multi-bounce term (setting albedo) on Vulkan against the CPU reference (Float): the five
// analytic scenes x every agreement configuration (each preset, the z hierarchy off, the untuned
// defaults, and no blur at full resolution, where ao_sample_output stores the output) at albedo 0.6,
// to the reference tests' bounds (99.9 % within 2/255, none beyond 4/255). The raw (pre-output) AO
// does not see the albedo: it stays within the same bounds of the CPU's single-bounce raw AO. Every
// output format, mask and blend at albedo 0.6: output_format_test.cpp.
#include <cstdio>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "analytic_scenes.h"
#include "output_format_check.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "untuned_settings.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr float kAlbedo = 0.6f;
constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

TEST_F(VkTest, MultiBounceAgreesWithTheCpuReferenceOnEveryScene) {
  const Camera camera = vulkanCamera(160, 90, 8, 100.0);
  std::vector<test::NamedSettings> configs = test::agreementSettings();
  Settings direct = presetSettings(Preset::Reference);
  direct.blur_radius = 0;  // with resolution_divisor 1: ao_sample_output writes the output
  configs.push_back({"direct", direct});
  for (const test::Scene& scene : {test::planeScene(2.0), test::creaseScene(2.0), test::sphereOnPlaneScene(),
                                   test::stairsScene(), test::rodsScene()}) {
    const DepthImage depth = test::renderDepth(scene, camera, DepthFormat::D32F);
    for (const auto& [label, base] : configs) {
      const std::string name = "vk_bounce_" + scene.name + "_" + label;
      SCOPED_TRACE(name);
      Settings settings = base;
      settings.albedo = kAlbedo;
      RunResult vk;
      RunOptions o;
      o.readIntermediates = label != "direct";  // ao_sample_output: there is no ao_raw
      const Status st = runEffect(settings, camera, depth, VkDepth::D32F, vk, o);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Inputs in;
      in.depth = &depth;
      cpu::Result ref;
      ASSERT_TRUE(cpu::run(settings, camera, in, {cpu::Precision::Float, 2}, ref).ok());
      EXPECT_EQ(std::memcmp(&vk.params, &ref.params, sizeof(ParamBlock)), 0) << "same parameter block";
      EXPECT_EQ(ref.params.multi_bounce, 1);
      const Agreement f = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_final");
      EXPECT_TRUE(acceptable(f)) << "max |diff| " << f.maxAbs * 255 << "/255, " << f.fractionWithin * 100
                                 << "% within 2/255, " << f.beyond << " beyond 4/255";
      if (o.readIntermediates) {
        cpu::Result single;
        ASSERT_TRUE(cpu::run(base, camera, in, {cpu::Precision::Float, 2}, single).ok());
        const Agreement r = compare(vk.aoRaw, single.aoRaw, 0, kWithin, kNever, name + "_raw");
        EXPECT_TRUE(acceptable(r)) << "raw AO: max |diff| " << r.maxAbs * 255 << "/255";
      }
      std::printf("BOUNCE %-34s max %.4f/255 p99.9 %.4f/255\n", name.c_str(), f.maxAbs * 255, f.p999 * 255);
    }
  }
}

}  // namespace
}  // namespace sao::vktest
