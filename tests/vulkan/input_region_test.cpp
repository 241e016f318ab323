// Vulkan only (the shared cases: tests/executors/input_region_test.cpp): a region refused by
// record() records nothing, so a good record in the same command buffer works; and a declared
// extent (vk::InputImage::extent) beyond the device's maxImageDimension2D is refused.
#include <string>

#include "analytic_scenes.h"
#include "input_region.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

class Region : public VkTest {};

TEST_F(Region, RefusedRecordsLeaveTheCommandBufferUsable) {
  const Camera cam = vulkanCamera(41, 23, 3);  // needs 47x29
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
  auto& ctx = context();
  const VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  vk::headless::Image big;
  ASSERT_TRUE(ctx.uploadDepth(test::embedDepth(depth, {50, 31}, {3, 2}), VK_FORMAT_D32_SFLOAT, layout, big).ok());
  std::unique_ptr<vk::Effect> effect;
  const Status sc = vk::Effect::create(ctx.deviceContext(), {}, effect);
  ASSERT_TRUE(sc.ok()) << sc.message;
  const Settings settings;

  vk::Inputs good;
  good.depth = {big.view, layout, {50, 31}, VK_FORMAT_D32_SFLOAT};
  good.region = Offset{3, 2};
  // The effect is planned first (by a good record), as a running effect is: the refusals below
  // happen on the frame's checks, not on a first plan.
  Status planned;
  ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) { planned = effect->record(cmd, cam, settings, good); }).ok());
  ASSERT_TRUE(planned.ok()) << planned.message;
  vk::Inputs outside = good, tooLarge = good;
  outside.region = Offset{4, 2};
  tooLarge.depth.extent = {ctx.properties().limits.maxImageDimension2D + 1, 31};  // no image of this device
  const std::pair<vk::Inputs, std::string> cases[] = {
      {outside, "at offset (4, 2), which ends at (51, 31): the region must lie inside the texture"},
      {tooLarge, "exceeds this device's maxImageDimension2D"},
  };
  std::vector<Status> results;
  Status after;
  ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) {
                   for (const auto& c : cases) results.push_back(effect->record(cmd, cam, settings, c.first));
                   after = effect->record(cmd, cam, settings, good);
                 }).ok());
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE(cases[i].second);
    EXPECT_EQ(results[i].code, StatusCode::InvalidInput);
    EXPECT_NE(results[i].message.find(cases[i].second), std::string::npos) << results[i].message;
  }
  EXPECT_TRUE(after.ok()) << after.message;
  EXPECT_EQ(effect->plans(), 1u) << "the refused records planned nothing";
  effect.reset();
  ctx.destroy(big);
}

}  // namespace
}  // namespace sao::vktest
