// The frame loop holds (issue 19): one effect recorded once into 2 command buffers and resubmitted
// for 2000 frames with 2 in flight, under validation and synchronization validation. Host memory in
// use (mallinfo2) after a 100-frame warm-up may grow by less than 1 KB per frame, amortised.
// Lavapipe 22.3 grew ~400 KB per frame here until ao_sample took its loop count from a push
// constant (docs/ROBUSTNESS.md; bisect with sao-vk-frame-loop-probe). Temporal accumulation is
// looped as an engine runs it: recorded anew every frame with its camera.
#include <malloc.h>

#include <cstdio>
#include <cstdlib>

#include "analytic_scenes.h"
#include "msaa_depth.h"
#include "vk_msaa_depth_writer.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr int kFrames = 2000;
constexpr int kWarmUp = 100;
constexpr double kAllowedBytesPerFrame = 1024;

// Under AddressSanitizer the allocator quarantines freed blocks: mallinfo2 says nothing there
// (ci/sanitize.sh sets SAO_SANITIZED for the uninstrumented-compiler case too).
bool sanitized() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#else
  return std::getenv("SAO_SANITIZED") != nullptr;
#endif
}

class VkFrameLoop : public VkTest {};

// Records `effect` once into 2 command buffers (the first record plans) and resubmits them kFrames
// times, 2 in flight: the heap bytes per frame after the warm-up.
double resubmittedGrowth(vk::Effect& effect, const Camera& camera, const Settings& settings, const vk::Inputs& in) {
  vk::headless::Context& ctx = context();
  const VkDevice device = ctx.device();
  VkCommandBuffer cmds[2]{};
  EXPECT_TRUE(ctx.allocateCommandBuffers(cmds, 2).ok());
  VkFence fences[2]{};
  for (VkFence& f : fences) {
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    EXPECT_EQ(vkCreateFence(device, &fi, nullptr, &f), VK_SUCCESS);
  }
  for (VkCommandBuffer cmd : cmds) {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    EXPECT_EQ(vkBeginCommandBuffer(cmd, &bi), VK_SUCCESS);
    const Status st = effect.record(cmd, camera, settings, in);
    EXPECT_EQ(vkEndCommandBuffer(cmd), VK_SUCCESS);
    EXPECT_TRUE(st.ok()) << st.message;
  }
  EXPECT_EQ(effect.plans(), 1u) << "the second record kept the first one's plan";
  std::size_t warm = 0;
  for (int f = 0; f < kFrames; ++f) {
    VkFence fence = fences[f % 2];
    EXPECT_EQ(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
    EXPECT_EQ(vkResetFences(device, 1, &fence), VK_SUCCESS);
    if (f == kWarmUp) warm = mallinfo2().uordblks;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmds[f % 2];
    EXPECT_EQ(vkQueueSubmit(ctx.queue(), 1, &si, fence), VK_SUCCESS);
  }
  EXPECT_EQ(vkWaitForFences(device, 2, fences, VK_TRUE, UINT64_MAX), VK_SUCCESS);
  const double perFrame = (double(mallinfo2().uordblks) - double(warm)) / (kFrames - kWarmUp);
  for (VkFence f : fences) vkDestroyFence(device, f, nullptr);
  vkFreeCommandBuffers(device, ctx.commandPool(), 2, cmds);
  return perFrame;
}

TEST_F(VkFrameLoop, RecordedOnceResubmitted2000FramesHoldsHostMemory) {
  if (sanitized()) GTEST_SKIP() << "heap figures are meaningless under the sanitizers' allocator";
  vk::headless::Context& ctx = context();
  const Camera camera = vulkanCamera(64, 64, 4);
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
  vk::headless::Image image;
  ASSERT_TRUE(ctx.uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image).ok());
  vk::Config config;
  config.framesInFlight = 2;
  config.timestamps = true;  // every command of the stream, queries included
  std::unique_ptr<vk::Effect> effect;
  Status st = vk::Effect::create(ctx.deviceContext(), config, effect);
  ASSERT_TRUE(st.ok()) << st.message;
  vk::Inputs in;
  in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
  const double perFrame = resubmittedGrowth(*effect, camera, Settings{}, in);
  Timings timings;
  st = effect->timings(timings);
  EXPECT_TRUE(st.ok()) << st.message;
  effect.reset();
  ctx.destroy(image);
  std::printf("[frame loop] Vulkan (%s): %+.1f heap bytes/frame over %d frames after %d, 2 in flight\n",
              ctx.properties().deviceName, perFrame, kFrames - kWarmUp, kWarmUp);
  EXPECT_LT(perFrame, kAllowedBytesPerFrame) << "host memory grows with resubmitted frames";
}

// The same loop with multisampled depth read by the Nearest policy: linear_z's sample loop takes
// its trip count from the uniform block (depth_samples), the pattern that grew on lavapipe 22.3 in
// ao_sample's tap loop; this one measured flat (+0.1 bytes/frame), and this test keeps it so.
TEST_F(VkFrameLoop, MultisampledNearestDepthHoldsHostMemory) {
  if (sanitized()) GTEST_SKIP() << "heap figures are meaningless under the sanitizers' allocator";
  vk::headless::Context& ctx = context();
  Camera camera = vulkanCamera(64, 64, 4);
  camera.depthSamplePolicy = DepthSamplePolicy::Nearest;
  const DepthImage near = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
  const DepthImage rods = test::renderDepth(test::rodsScene(), camera, DepthFormat::D32F);
  const DepthImage msaa = test::interleaveSamples({&near, &rods}, 4);
  vk::headless::Image image;
  ASSERT_TRUE(writeMultisampledDepth(ctx, msaa, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image).ok());
  vk::Config config;
  config.framesInFlight = 2;
  std::unique_ptr<vk::Effect> effect;
  const Status st = vk::Effect::create(ctx.deviceContext(), config, effect);
  ASSERT_TRUE(st.ok()) << st.message;
  vk::Inputs in;
  in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, msaa.extent, VK_FORMAT_D32_SFLOAT,
              VK_SAMPLE_COUNT_4_BIT};
  const double perFrame = resubmittedGrowth(*effect, camera, Settings{}, in);
  effect.reset();
  ctx.destroy(image);
  std::printf("[frame loop] Vulkan, 4-sample depth, Nearest: %+.1f heap bytes/frame over %d frames after %d\n",
              perFrame, kFrames - kWarmUp, kWarmUp);
  EXPECT_LT(perFrame, kAllowedBytesPerFrame) << "host memory grows with resubmitted frames";
}

// Temporal accumulation in an engine's loop: every frame recorded anew with its own camera (moving:
// Camera::view, which keeps the plan) and frame index, the history images trading places, each
// submission waited for. Host memory stays flat.
TEST_F(VkFrameLoop, TemporalRecordedEveryFrameHoldsHostMemory) {
  if (sanitized()) GTEST_SKIP() << "heap figures are meaningless under the sanitizers' allocator";
  vk::headless::Context& ctx = context();
  Camera base = vulkanCamera(64, 64, 4);
  base.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), base, DepthFormat::D32F);
  vk::headless::Image image;
  ASSERT_TRUE(ctx.uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image).ok());
  Settings settings;
  settings.temporal = true;
  std::unique_ptr<vk::Effect> effect;
  const Status st = vk::Effect::create(ctx.deviceContext(), {}, effect);
  ASSERT_TRUE(st.ok()) << st.message;
  std::size_t warm = 0;
  for (int f = 0; f < kFrames; ++f) {
    if (f == kWarmUp) warm = mallinfo2().uordblks;
    Camera cam = base;
    (*cam.view)[12] = -0.001 * (f % 100);
    vk::Inputs in;
    in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
    in.frameIndex = std::uint32_t(f);
    Status recorded;
    ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, cam, settings, in); }).ok());
    ASSERT_TRUE(recorded.ok()) << "frame " << f << ": " << recorded.message;
  }
  EXPECT_EQ(effect->plans(), 1u) << "the moving camera kept the plan";
  const double perFrame = (double(mallinfo2().uordblks) - double(warm)) / (kFrames - kWarmUp);
  expectNoMessages("temporal frame loop");
  effect.reset();
  ctx.destroy(image);
  std::printf("[frame loop] Vulkan temporal, recorded every frame: %+.1f heap bytes/frame over %d frames after %d\n",
              perFrame, kFrames - kWarmUp, kWarmUp);
  EXPECT_LT(perFrame, kAllowedBytesPerFrame) << "host memory grows with recorded frames";
}

}  // namespace
}  // namespace sao::vktest
