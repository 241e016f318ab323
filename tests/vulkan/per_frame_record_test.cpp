// The per-frame record(cmd, camera, settings, inputs[, output]) with frames in flight: what only
// Vulkan has (the shared suite, tests/executors, drives Vulkan through this call: every change of
// settings, camera, inputs or output equal to a fresh effect, steady frames allocating nothing). A
// new plan made inside the call while earlier frames are pending destroys what the old plan alone
// used only once the ring says those frames completed: checked under the validation layer with
// synchronization validation (a destroyed image in use, a missing barrier: a message fails the
// test), the frames equal to fresh effects, the memory given back.
#include "analytic_scenes.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;
constexpr std::uint32_t kW = 96, kH = 54, kGuard = 4;
constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// One depth buffer per viewport size.
struct Depth {
  Camera camera;
  DepthImage depth;
  Image image;
  explicit Depth(Camera c) : camera(c), depth(test::renderDepth(test::stairsScene(), c, DepthFormat::D32F)) {
    EXPECT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, kRead, image).ok());
  }
  ~Depth() { context().destroy(image); }
  vk::Inputs inputs() const {
    vk::Inputs in;
    in.depth = {image.view, kRead, depth.extent, VK_FORMAT_D32_SFLOAT};
    return in;
  }
};

FloatImage read(const vk::Effect& e, const vk::OutputImage& o) {
  FloatImage out;
  EXPECT_TRUE(context()
                  .readback(o.image, o.format, o.extent, 0, o.layout, e.config().outputDstStages,
                            e.config().outputDstAccess, out)
                  .ok());
  return out;
}

// What a fresh effect (its first record, the one that plans, with this frame's camera and
// settings) writes into its own output of `format`.
FloatImage freshOutput(const Depth& d, const Settings& settings, VkFormat format) {
  vk::Config c;
  c.outputFormat = format;
  std::unique_ptr<vk::Effect> e;
  EXPECT_TRUE(vk::Effect::create(context().deviceContext(), c, e).ok());
  if (!e) return {};
  Status recorded;
  EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = e->record(cmd, d.camera, settings, d.inputs()); }).ok());
  EXPECT_TRUE(recorded.ok()) << recorded.message;
  return read(*e, e->output());
}

using PerFrameRecord = VkTest;

// Two frames in flight, a new plan every frame (full and half resolution alternate), no wait but
// the ring's: each command buffer is waited for only before it is recorded again. The validation
// layer reports any image destroyed while a pending frame uses it; the last two frames equal fresh
// effects; the images the alternation dropped are given back two frames after the last re-plan.
TEST_F(PerFrameRecord, NewPlansWhileFramesArePendingWaitForTheRing) {
  const Depth d(vulkanCamera(kW, kH, kGuard));
  vk::Config c;
  c.framesInFlight = 2;
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(context().deviceContext(), c, e).ok());
  auto settingsOf = [](std::uint32_t frame) {
    Settings s = presetSettings(Preset::Medium);
    s.resolution_divisor = frame % 2 ? 2 : 1;
    return s;
  };
  const VkDevice device = context().device();
  VkCommandBuffer cmds[2]{};
  ASSERT_TRUE(context().allocateCommandBuffers(cmds, 2).ok());
  VkFence fences[2]{};
  Image outs[2];
  for (std::uint32_t i = 0; i < 2; ++i) {
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    ASSERT_EQ(vkCreateFence(device, &fi, nullptr, &fences[i]), VK_SUCCESS);
    ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, outs[i]).ok());
  }
  auto frame = [&](std::uint32_t f, const Settings& settings) {
    const std::uint32_t i = f % 2;
    ASSERT_EQ(vkWaitForFences(device, 1, &fences[i], VK_TRUE, UINT64_MAX), VK_SUCCESS);  // the ring's wait
    ASSERT_EQ(vkResetFences(device, 1, &fences[i]), VK_SUCCESS);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ASSERT_EQ(vkBeginCommandBuffer(cmds[i], &bi), VK_SUCCESS);
    const vk::OutputImage o{outs[i].image, outs[i].view, VK_FORMAT_R16_SFLOAT, {kW, kH}, VK_IMAGE_LAYOUT_UNDEFINED};
    const Status st = e->record(cmds[i], d.camera, settings, d.inputs(), &o);
    ASSERT_EQ(vkEndCommandBuffer(cmds[i]), VK_SUCCESS);
    ASSERT_TRUE(st.ok()) << st.message;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmds[i];
    ASSERT_EQ(vkQueueSubmit(context().queue(), 1, &si, fences[i]), VK_SUCCESS);
  };
  constexpr std::uint32_t kFrames = 8;
  for (std::uint32_t f = 0; f < kFrames; ++f) frame(f, settingsOf(f));
  const std::uint64_t pendingBytes = e->memoryStats().liveBytes;  // the last re-plan's retired images held
  ASSERT_EQ(vkWaitForFences(device, 2, fences, VK_TRUE, UINT64_MAX), VK_SUCCESS);
  const vk::OutputImage last[2] = {{outs[0].image, outs[0].view, VK_FORMAT_R16_SFLOAT, {kW, kH}, e->config().outputLayout},
                                   {outs[1].image, outs[1].view, VK_FORMAT_R16_SFLOAT, {kW, kH}, e->config().outputLayout}};
  for (std::uint32_t i = 0; i < 2; ++i)
    EXPECT_TRUE(test::sameBits(read(*e, last[i]), freshOutput(d, settingsOf(kFrames - 2 + i), VK_FORMAT_R16_SFLOAT)))
        << "frame " << kFrames - 2 + i;
  // Two more frames on the last plan: the ring passes the re-plan, its retired images go.
  for (std::uint32_t f = kFrames; f < kFrames + 2; ++f) frame(f, settingsOf(kFrames - 1));
  const std::uint64_t settledBytes = e->memoryStats().liveBytes;
  std::printf("device memory with a re-plan's images retired %llu bytes, after the ring passed it %llu bytes\n",
              static_cast<unsigned long long>(pendingBytes), static_cast<unsigned long long>(settledBytes));
  EXPECT_LT(settledBytes, pendingBytes) << "the images full resolution no longer uses were given back";
  ASSERT_EQ(vkWaitForFences(device, 2, fences, VK_TRUE, UINT64_MAX), VK_SUCCESS);
  for (std::uint32_t i = 0; i < 2; ++i) {
    vkDestroyFence(device, fences[i], nullptr);
    context().destroy(outs[i]);
  }
  vkFreeCommandBuffers(device, context().commandPool(), 2, cmds);
}

// create() plans nothing (plan() empty, the parameter buffer its only memory); the first record()
// plans, and one whose normals view comes without InputImage::format (a view cannot tell it) is
// refused, naming it, and plans nothing.
TEST_F(PerFrameRecord, CreatePlansNothingAndAnInputWithoutItsFormatIsRefused) {
  const Depth d(vulkanCamera(kW, kH, kGuard));
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(context().deviceContext(), {}, e).ok());
  EXPECT_EQ(e->plans(), 0u);
  EXPECT_TRUE(e->plan().passes.empty());
  EXPECT_TRUE(e->plan().images.empty());
  EXPECT_EQ(e->memoryStats().liveAllocations, 1u) << "the parameter buffer only";
  Status recorded;
  vk::Inputs normalsWithoutFormat = d.inputs();
  normalsWithoutFormat.normals = {d.image.view, kRead, d.depth.extent};
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    recorded = e->record(cmd, d.camera, Settings{}, normalsWithoutFormat);
                  })
                  .ok());
  EXPECT_EQ(recorded.code, StatusCode::InvalidInput);
  EXPECT_NE(recorded.message.find("Inputs::normals.format is VK_FORMAT_UNDEFINED"), std::string::npos)
      << recorded.message;
  EXPECT_EQ(e->plans(), 0u) << "the refused record planned nothing";
  EXPECT_EQ(e->memoryStats().liveAllocations, 1u);
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = e->record(cmd, d.camera, Settings{}, d.inputs()); })
                  .ok());
  EXPECT_TRUE(recorded.ok()) << recorded.message;
  EXPECT_EQ(e->plans(), 1u);
  EXPECT_FALSE(e->plan().passes.empty());
}

}  // namespace
}  // namespace sao::vktest
