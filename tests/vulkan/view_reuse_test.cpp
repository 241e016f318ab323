// Regression: a caller destroys an input view and creates another, which may get the same handle
// value. The effect must not keep a descriptor set that points at the destroyed view (lavapipe
// crashed on it). Runs WITHOUT validation layers, which wrap handles and hide the reuse.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analytic_scenes.h"
#include "sao/vulkan/effect.h"
#include "sao/vulkan/headless.h"

namespace {

using namespace sao;

TEST(VkViewReuse, ANewInputViewIsAlwaysBound) {
  std::unique_ptr<vk::headless::Context> ctx;
  ASSERT_TRUE(vk::headless::Context::create({}, ctx).ok());
  Camera camera = perspectiveCamera(std::numbers::pi / 3, 96, 64, 0.1, INFINITY, ClipDepth::ZeroToOne, true);
  const vk::Config config;
  const Settings settings;
  constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
  std::unique_ptr<vk::Effect> effect;
  ASSERT_TRUE(vk::Effect::create(ctx->deviceContext(), config, effect).ok());
  const VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

  auto runOn = [&](const DepthImage& depth, FloatImage& ao) {
    vk::headless::Image image;
    ASSERT_TRUE(ctx->uploadDepth(depth, kDepthFormat, layout, image).ok());
    vk::Inputs in;
    in.depth = {image.view, layout, depth.extent, kDepthFormat};
    Status recorded;
    ASSERT_TRUE(ctx->submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, camera, settings, in); }).ok());
    ASSERT_TRUE(recorded.ok()) << recorded.message;
    const auto out = effect->output();
    ASSERT_TRUE(ctx->readback(out.image, out.format, out.extent, 0, out.layout, config.outputDstStages,
                              config.outputDstAccess, ao)
                    .ok());
    ctx->destroy(image);  // the next upload may reuse the view's handle value
  };
  const DepthImage sky = test::renderDepth(test::skyScene(), camera, DepthFormat::D32F);
  const DepthImage crease = test::renderDepth(test::creaseScene(2.0), camera, DepthFormat::D32F);
  FloatImage first, second, third;
  runOn(sky, first);
  for (int frame = 0; frame < 4; ++frame) runOn(crease, second);  // every ring slot sees the new views
  runOn(sky, third);
  float darkest = 1.0f;
  for (float a : second.data) darkest = std::min(darkest, a);
  EXPECT_LT(darkest, 0.9f) << "the crease frame must show occlusion, not the sky frame's stale input";
  for (float a : third.data) ASSERT_EQ(a, 1.0f) << "sky again after the crease";
}

}  // namespace
