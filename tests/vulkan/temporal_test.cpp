// Temporal accumulation on Vulkan, what only Vulkan has (the shared cases, strafing frames against
// the CPU reference, reset and motion vectors, are tests/executors/temporal_test.cpp): two frames
// recorded into two command buffers and submitted together (two frames in flight) give what one
// after the other gives, under synchronization validation; a record that plans again (other
// settings) starts the history again.
#include <cstring>
#include <string>

#include "moving_camera.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;

class Temporal : public VkTest {
 public:
  void SetUp() override {
    VkTest::SetUp();
    const Camera base = vulkanCamera(kW, kH, kGuard);
    settings = presetSettings(Preset::Medium);
    settings.temporal = true;
    for (std::uint32_t f = 0; f < kFrames; ++f) {
      cameras[f] = test::movedCamera(base, eye(f));
      depths[f] = test::renderDepth(test::seenFrom(test::sphereOnPlaneScene(), eye(f)), cameras[f], DepthFormat::D32F);
      ASSERT_TRUE(context()
                      .uploadDepth(depths[f], VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, images[f])
                      .ok());
    }
  }
  void TearDown() override {
    for (Image& i : images) context().destroy(i);
    VkTest::TearDown();
  }
  static test::Vec3 eye(std::uint32_t frame) { return {0.03 * frame, 0.0, 0.0}; }

  std::unique_ptr<vk::Effect> create() const {
    vk::Config c;
    c.framesInFlight = 2;
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_TRUE(st.ok()) << st.message;
    return e;
  }
  vk::Inputs inputs(std::uint32_t frame) const {
    vk::Inputs in;
    in.depth = {images[frame].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depths[frame].extent, VK_FORMAT_D32_SFLOAT};
    in.frameIndex = frame;
    return in;
  }
  // Frame `frame` of `e` (its camera, depth and index) with `s` into `o`.
  Status record(vk::Effect& e, VkCommandBuffer cmd, std::uint32_t frame, const vk::OutputImage& o,
                const Settings* s = nullptr) const {
    return e.record(cmd, cameras[frame], s ? *s : settings, inputs(frame), &o);
  }
  static vk::OutputImage outputOf(const Image& out) {
    return {out.image, out.view, VK_FORMAT_R16_SFLOAT, {kW, kH}, VK_IMAGE_LAYOUT_UNDEFINED};
  }
  static FloatImage read(const vk::Effect& e, const Image& out) {
    FloatImage ao;
    const vk::Config& c = e.config();
    EXPECT_TRUE(context()
                    .readback(out.image, VK_FORMAT_R16_SFLOAT, {kW, kH}, 0, c.outputLayout, c.outputDstStages,
                              c.outputDstAccess, ao)
                    .ok());
    return ao;
  }

  static constexpr std::uint32_t kFrames = 3;
  Settings settings;
  Camera cameras[kFrames];
  DepthImage depths[kFrames];
  Image images[kFrames];
};

std::size_t differences(const FloatImage& a, const FloatImage& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i)
    n += std::memcmp(&a.data[i], &b.data[i], sizeof(float)) != 0;
  return n + (a.data.size() != b.data.size());
}

TEST_F(Temporal, TwoFramesInFlightGiveWhatOneAfterTheOtherGives) {
  auto sequential = create();
  auto inFlight = create();
  ASSERT_TRUE(sequential && inFlight);
  vk::headless::Context& ctx = context();
  Image outs[2];
  for (Image& i : outs) ASSERT_TRUE(ctx.createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, i).ok());
  const vk::OutputImage o[2] = {outputOf(outs[0]), outputOf(outs[1])};
  // One after the other, each waited for.
  FloatImage expected[3];
  for (std::uint32_t f = 0; f < 3; ++f) {
    Status recorded;
    ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) { recorded = record(*sequential, cmd, f, o[0]); }).ok());
    ASSERT_TRUE(recorded.ok()) << recorded.message;
    expected[f] = read(*sequential, outs[0]);
  }
  // Frame 0 alone, then frames 1 and 2 in two command buffers submitted together.
  Status recorded;
  ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) { recorded = record(*inFlight, cmd, 0, o[0]); }).ok());
  ASSERT_TRUE(recorded.ok()) << recorded.message;
  const VkDevice device = ctx.device();
  VkCommandBuffer cmds[2]{};
  ASSERT_TRUE(ctx.allocateCommandBuffers(cmds, 2).ok());
  for (std::uint32_t i = 0; i < 2; ++i) {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ASSERT_EQ(vkBeginCommandBuffer(cmds[i], &bi), VK_SUCCESS);
    const Status st = record(*inFlight, cmds[i], i + 1, o[i]);
    ASSERT_EQ(vkEndCommandBuffer(cmds[i]), VK_SUCCESS);
    ASSERT_TRUE(st.ok()) << st.message;
  }
  VkFence fence = VK_NULL_HANDLE;
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  ASSERT_EQ(vkCreateFence(device, &fi, nullptr, &fence), VK_SUCCESS);
  VkSubmitInfo si[2]{};
  for (std::uint32_t i = 0; i < 2; ++i) {
    si[i].sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si[i].commandBufferCount = 1;
    si[i].pCommandBuffers = &cmds[i];
  }
  ASSERT_EQ(vkQueueSubmit(ctx.queue(), 2, si, fence), VK_SUCCESS);
  ASSERT_EQ(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
  vkDestroyFence(device, fence, nullptr);
  vkFreeCommandBuffers(device, ctx.commandPool(), 2, cmds);
  EXPECT_EQ(differences(read(*inFlight, outs[0]), expected[1]), 0u) << "frame 1 in flight";
  EXPECT_EQ(differences(read(*inFlight, outs[1]), expected[2]), 0u) << "frame 2 in flight";
  EXPECT_GT(differences(expected[1], expected[2]), 0u);
  expectNoMessages("two frames in flight");
  for (Image& i : outs) ctx.destroy(i);
}

// A record with other settings (a hysteresis of 0.8: nothing else changes) plans again within the
// call, and a new plan starts the history again: frame 2 after frames 0 and 1 with the old
// settings is frame 2 of a fresh effect, while frames 0, 1, 2 all with the new settings differ.
TEST_F(Temporal, ANewPlanStartsTheHistoryAgain) {
  Settings other = settings;
  other.temporal_hysteresis = 0.8f;
  auto accumulating = create();
  auto fresh = create();
  auto continuing = create();
  ASSERT_TRUE(accumulating && fresh && continuing);
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = outputOf(out);
  auto run = [&](vk::Effect& e, std::uint32_t frame, const Settings& s) {
    Status recorded;
    EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = record(e, cmd, frame, o, &s); }).ok());
    EXPECT_TRUE(recorded.ok()) << recorded.message;
    return read(e, out);
  };
  run(*accumulating, 0, settings);
  run(*accumulating, 1, settings);
  EXPECT_EQ(accumulating->plans(), 1u);
  const FloatImage afterNewPlan = run(*accumulating, 2, other);
  EXPECT_EQ(accumulating->plans(), 2u) << "other settings plan again";
  const FloatImage alone = run(*fresh, 2, other);
  run(*continuing, 0, other);
  run(*continuing, 1, other);
  const FloatImage continued = run(*continuing, 2, other);
  EXPECT_EQ(differences(afterNewPlan, alone), 0u) << "a new plan must start the history again";
  EXPECT_GT(differences(continued, alone), 0u) << "frame 2 with history looks like frame 2 without";
  expectNoMessages("a new plan");
  context().destroy(out);
}

}  // namespace
}  // namespace sao::vktest
