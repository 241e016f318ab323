// Inputs::frameIndex on Vulkan (sao::frameSpiral), under validation: frames 0, 7 and 1000 recorded
// one after another by one effect (no update()) against the CPU reference (Float) to the
// reference tests' bounds, each frame's block in its ring slot; frame 7 differs from frame 0.
#include <string>

#include "analytic_scenes.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

class FrameIndex : public VkTest {};

TEST_F(FrameIndex, EveryFrameMatchesTheCpuReference) {
  const Camera cam = vulkanCamera(160, 90, 8, INFINITY, /*reversedZ=*/true);
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
  vk::headless::Image image;
  ASSERT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image).ok());
  vk::Config c;
  c.camera = cam;
  c.settings = presetSettings(Preset::Medium);
  c.depthFormat = VK_FORMAT_D32_SFLOAT;
  std::unique_ptr<vk::Effect> effect;
  Status st = vk::Effect::create(context().deviceContext(), c, effect);
  ASSERT_TRUE(st.ok()) << st.message;
  FloatImage frame0;
  for (std::uint32_t frame : {0u, 7u, 1000u}) {
    const std::string name = "vk_frame" + std::to_string(frame);
    vk::Inputs in;
    in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
    in.frameIndex = frame;
    Status recorded;
    ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, in); }).ok());
    ASSERT_TRUE(recorded.ok()) << recorded.message;
    const vk::OutputImage o = effect->output();
    FloatImage actual;
    ASSERT_TRUE(context().readback(o.image, o.format, o.extent, 0, o.layout, c.outputDstStages, c.outputDstAccess, actual).ok());
    cpu::Inputs ci;
    ci.depth = &depth;
    ci.frameIndex = frame;
    cpu::Result ref;
    ASSERT_TRUE(cpu::run(c.settings, cam, ci, {cpu::Precision::Float, 2}, ref).ok());
    const Agreement a = compare(actual, ref.ao, 0, 2.0 / 255.0, 4.0 / 255.0, name);
    EXPECT_TRUE(acceptable(a)) << name << ": max " << a.maxAbs * 255 << "/255, p99.9 " << a.p999 * 255 << "/255";
    std::printf("FRAME %-14s vs CPU: max %.3f/255, p99.9 %.3f/255\n", name.c_str(), a.maxAbs * 255, a.p999 * 255);
    if (frame == 0) {
      frame0 = actual;
    } else {
      std::size_t changed = 0;
      for (std::size_t i = 0; i < actual.data.size(); ++i) changed += actual.data[i] != frame0.data[i];
      EXPECT_GT(changed, actual.data.size() / 10) << name << " looks like frame 0";
    }
    expectNoMessages(name.c_str());
  }
  context().destroy(image);
}

}  // namespace
}  // namespace sao::vktest
