// The multi-bounce term (setting albedo) on Vulkan against the CPU reference (Float): the five
// analytic scenes x every agreement configuration (each preset, the z hierarchy off, the untuned
// defaults, and no blur at full resolution, where ao_sample_output stores the output) at albedo 0.6,
// to the reference tests' bounds (99.9 % within 2/255, none beyond 4/255). The raw (pre-output) AO
// does not see the albedo: it stays within the same bounds of the CPU's single-bounce raw AO. And
// every output format, mask and blend of the output-format tests at albedo 0.6, at full and half
// resolution, into the caller's image.
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
  Settings direct = presetSettings(Preset::Ultra);
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

VkFormat vkOutput(gen::Format f) {
  switch (f) {
    case gen::Format::R8: return VK_FORMAT_R8_UNORM;
    case gen::Format::RGBA8: return VK_FORMAT_R8G8B8A8_UNORM;
    case gen::Format::RGBA16F: return VK_FORMAT_R16G16B16A16_SFLOAT;
    default: return VK_FORMAT_R16_SFLOAT;
  }
}

TEST_F(VkTest, MultiBounceInEveryOutputFormatAndBlendMatchesTheCpuReference) {
  const Camera camera = vulkanCamera(160, 90, 8, INFINITY, /*reversedZ=*/true);
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
  vk::headless::Image depthImage;
  ASSERT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depthImage).ok());
  vk::Inputs inputs;
  inputs.depth = {depthImage.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
  for (int divisor : {1, 2}) {
    Settings s = presetSettings(Preset::Medium);
    s.resolution_divisor = divisor;
    s.albedo = kAlbedo;
    for (const test::OutputCase& oc : test::kOutputCases) {
      const std::string name = "vk_bounce_" + test::caseName(oc) + "_d" + std::to_string(divisor);
      SCOPED_TRACE(name);
      vk::Config c;
      c.camera = camera;
      c.settings = s;
      c.depthFormat = VK_FORMAT_D32_SFLOAT;
      c.userOutput = true;
      c.outputFormat = vkOutput(oc.format);
      c.outputChannels = oc.mask;
      c.outputBlend = oc.blend;
      std::unique_ptr<vk::Effect> effect;
      const Status created = vk::Effect::create(context().deviceContext(), c, effect);
      ASSERT_TRUE(created.ok()) << created.message;
      const FloatImage sentinel = test::sentinelOutput({camera.width, camera.height}, oc.format);
      vk::headless::Image out;
      ASSERT_TRUE(context()
                      .uploadColor(sentinel, c.outputFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, out,
                                   VK_IMAGE_USAGE_STORAGE_BIT)
                      .ok());
      const vk::OutputImage o{out.image, out.view, c.outputFormat, sentinel.extent, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      Status recorded;
      ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, inputs, &o); }).ok());
      ASSERT_TRUE(recorded.ok()) << recorded.message;
      FloatImage actual;
      ASSERT_TRUE(context()
                      .readback(out.image, c.outputFormat, sentinel.extent, 0, c.outputLayout, c.outputDstStages,
                                c.outputDstAccess, actual)
                      .ok());
      context().destroy(out);
      cpu::Inputs ci;
      ci.depth = &depth;
      ci.outputFormat = oc.format;
      ci.outputChannels = oc.mask;
      ci.outputBlend = oc.blend;
      ci.output = &sentinel;
      cpu::Result ref;
      ASSERT_TRUE(cpu::run(s, camera, ci, {cpu::Precision::Float, 2}, ref).ok());
      test::checkOutput(actual, ref.ao, sentinel, oc.format, oc.mask, compare, name);
      expectNoMessages(name.c_str());
    }
  }
  context().destroy(depthImage);
}

}  // namespace
}  // namespace sao::vktest
