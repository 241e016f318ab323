// Temporal accumulation on Vulkan (Config::settings.temporal), under validation and
// synchronization validation: a camera strafing past a sphere on a plane, given per record
// (Inputs::camera, no update()), six frames against the CPU reference (Float, the history carried
// from run to run) to the reference tests' bounds; record() allocates nothing in the library once
// warm; two frames recorded into two command buffers and submitted together (two frames in
// flight) give what one after the other gives; Inputs::resetHistory and update() start again.
#include <cstring>
#include <string>

#include "cpu_frames.h"
#include "library_allocations.h"
#include "moving_camera.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;

class Temporal : public VkTest {
 public:  // expectStrafeMatchesCpu uses the fixture
  void SetUp() override {
    VkTest::SetUp();
    base = vulkanCamera(kW, kH, kGuard);
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

  std::unique_ptr<vk::Effect> create(std::uint32_t framesInFlight = 2) const {
    vk::Config c;
    c.settings = settings;
    c.camera = cameras[0];
    c.depthFormat = VK_FORMAT_D32_SFLOAT;
    c.userOutput = true;
    c.framesInFlight = framesInFlight;
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_TRUE(st.ok()) << st.message;
    return e;
  }
  vk::Inputs inputs(std::uint32_t frame) const {
    vk::Inputs in;
    in.depth = {images[frame].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depths[frame].extent, VK_FORMAT_D32_SFLOAT};
    in.camera = &cameras[frame];
    in.frameIndex = frame;
    return in;
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
  // The CPU reference's frames 0 .. n-1, the history carried along.
  std::vector<FloatImage> cpuFrames(std::uint32_t n) const {
    std::vector<FloatImage> out;
    test::CpuFrames reference(settings);
    for (std::uint32_t f = 0; f < n; ++f) {
      cpu::Inputs ci;
      ci.depth = &depths[f];
      ci.frameIndex = f;
      out.push_back(reference.run(cameras[f], ci).ao);
    }
    return out;
  }

  static constexpr std::uint32_t kFrames = 6;
  Camera base;
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

// The strafe's frames through one effect, each within the agreement bounds of the CPU reference,
// with no library or device allocation in record() after the first frames. The test's `settings`.
void expectStrafeMatchesCpu(Temporal& t, const std::string& prefix) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  auto effect = t.create();
  ASSERT_TRUE(effect);
  const std::vector<FloatImage> expected = t.cpuFrames(Temporal::kFrames);
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = t.outputOf(out);
  const std::uint64_t allocationsBefore = effect->memoryStats().totalAllocations;
  long counted = 0;
  for (std::uint32_t f = 0; f < Temporal::kFrames; ++f) {
    const std::string name = prefix + std::to_string(f);
    Status recorded;
    ASSERT_TRUE(context()
                    .submit([&](VkCommandBuffer cmd) {
                      const vk::Inputs in = t.inputs(f);
                      test::startCountingAllocations();
                      recorded = effect->record(cmd, in, &o);
                      test::stopCountingAllocations();
                      if (f >= 2) counted += test::countedAllocations();
                    })
                    .ok());
    ASSERT_TRUE(recorded.ok()) << recorded.message;
    const FloatImage actual = t.read(*effect, out);
    const Agreement a = compare(actual, expected[f], 0, 2.0 / 255.0, 4.0 / 255.0, name);
    EXPECT_TRUE(acceptable(a)) << name << ": max " << a.maxAbs * 255 << "/255, p99.9 " << a.p999 * 255 << "/255";
    std::printf("TEMPORAL %-14s vs CPU: max %.3f/255, p99.9 %.3f/255\n", name.c_str(), a.maxAbs * 255, a.p999 * 255);
    expectNoMessages(name.c_str());
  }
  EXPECT_EQ(counted, 0) << "library allocations in record() with a moving camera";
  EXPECT_EQ(effect->memoryStats().totalAllocations, allocationsBefore) << "device memory allocated per frame";
  context().destroy(out);
}

TEST_F(Temporal, StrafeFramesMatchTheCpuReferenceWithoutAllocating) { expectStrafeMatchesCpu(*this, "vk_temporal"); }

// The visibility estimator (with thickness from width) accumulates its occlusion the same way.
TEST_F(Temporal, VisibilityEstimatorStrafeFramesMatchTheCpuReference) {
  settings.estimator = 1;
  settings.thickness_model = 1;
  expectStrafeMatchesCpu(*this, "vk_temporal_visibility");
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
    ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) { recorded = sequential->record(cmd, inputs(f), &o[0]); }).ok());
    ASSERT_TRUE(recorded.ok()) << recorded.message;
    expected[f] = read(*sequential, outs[0]);
  }
  // Frame 0 alone, then frames 1 and 2 in two command buffers submitted together.
  Status recorded;
  ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) { recorded = inFlight->record(cmd, inputs(0), &o[0]); }).ok());
  ASSERT_TRUE(recorded.ok()) << recorded.message;
  const VkDevice device = ctx.device();
  VkCommandBuffer cmds[2]{};
  ASSERT_TRUE(ctx.allocateCommandBuffers(cmds, 2).ok());
  for (std::uint32_t i = 0; i < 2; ++i) {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ASSERT_EQ(vkBeginCommandBuffer(cmds[i], &bi), VK_SUCCESS);
    const Status st = inFlight->record(cmds[i], inputs(i + 1), &o[i]);
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

TEST_F(Temporal, ResetHistoryAndUpdateStartAgain) {
  auto accumulating = create();
  auto fresh = create();
  ASSERT_TRUE(accumulating && fresh);
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = outputOf(out);
  auto run = [&](vk::Effect& e, std::uint32_t frame, bool reset) {
    vk::Inputs in = inputs(frame);
    in.resetHistory = reset;
    Status recorded;
    EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = e.record(cmd, in, &o); }).ok());
    EXPECT_TRUE(recorded.ok()) << recorded.message;
    return read(e, out);
  };
  run(*accumulating, 0, false);
  const FloatImage reset = run(*accumulating, 1, true);
  const FloatImage alone = run(*fresh, 1, false);
  EXPECT_EQ(differences(reset, alone), 0u) << "a reset record must not read the history";
  const FloatImage continued = run(*accumulating, 2, false);
  vk::Config c = accumulating->config();
  ASSERT_TRUE(accumulating->update(c).ok());
  const FloatImage afterUpdate = run(*accumulating, 2, false);
  auto alone2 = create();
  const FloatImage fresh2 = run(*alone2, 2, false);
  EXPECT_EQ(differences(afterUpdate, fresh2), 0u) << "update() must start the history again";
  EXPECT_GT(differences(continued, fresh2), 0u) << "frame 2 with history looks like frame 2 without";
  expectNoMessages("reset");
  context().destroy(out);
}

// Motion vectors (Config::motionFormat, Inputs::motion): frames 1..3 of the strafe recorded with a
// field of (1.5, -0.75) pixels everywhere (R16G16B16A16_SFLOAT), against the CPU reference given
// the same field, under validation.
TEST_F(Temporal, MotionVectorsMatchTheCpuReference) {
  FloatImage motion(depths[0].extent, 4);
  for (std::size_t i = 0; i < motion.data.size(); i += 4) {
    motion.data[i] = 1.5f;
    motion.data[i + 1] = -0.75f;
  }
  Image motionImage;
  ASSERT_TRUE(context()
                  .uploadColor(motion, VK_FORMAT_R16G16B16A16_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                               motionImage)
                  .ok());
  vk::Config c;
  c.settings = settings;
  c.camera = cameras[0];
  c.depthFormat = VK_FORMAT_D32_SFLOAT;
  c.motionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  std::unique_ptr<vk::Effect> effect;
  Status st = vk::Effect::create(context().deviceContext(), c, effect);
  ASSERT_TRUE(st.ok()) << st.message;
  test::CpuFrames reference(settings);
  for (std::uint32_t f = 0; f < 4; ++f) {
    const std::string name = "vk_temporal_motion" + std::to_string(f);
    vk::Inputs in = inputs(f);
    in.motion = {motionImage.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, motion.extent,
                 VK_FORMAT_R16G16B16A16_SFLOAT};
    Status recorded;
    ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, in); }).ok());
    ASSERT_TRUE(recorded.ok()) << recorded.message;
    const vk::OutputImage o = effect->output();
    FloatImage actual;
    ASSERT_TRUE(context()
                    .readback(o.image, o.format, o.extent, 0, o.layout, c.outputDstStages, c.outputDstAccess, actual)
                    .ok());
    cpu::Inputs ci;
    ci.depth = &depths[f];
    ci.motion = &motion;
    ci.frameIndex = f;
    const cpu::Result ref = reference.run(cameras[f], ci);
    const Agreement a = compare(actual, ref.ao, 0, 2.0 / 255.0, 4.0 / 255.0, name);
    EXPECT_TRUE(acceptable(a)) << name << ": max " << a.maxAbs * 255 << "/255, p99.9 " << a.p999 * 255 << "/255";
    std::printf("TEMPORAL %-20s vs CPU: max %.3f/255, p99.9 %.3f/255\n", name.c_str(), a.maxAbs * 255, a.p999 * 255);
    expectNoMessages(name.c_str());
  }
  // A motion format without the temporal setting: refused by name.
  vk::Config off = c;
  off.settings.temporal = false;
  std::unique_ptr<vk::Effect> refused;
  st = vk::Effect::create(context().deviceContext(), off, refused);
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("motion vectors serve temporal accumulation only"), std::string::npos) << st.message;
  context().destroy(motionImage);
}

}  // namespace
}  // namespace sao::vktest
