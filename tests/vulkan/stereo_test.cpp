// Stereo, Vulkan only (the rest: tests/executors/stereo_test.cpp): ONE effect made for stereo
// (2 frames in flight x 2 eyes, the caller's 2-layer output) recorded for both eyes into ONE
// command buffer with each eye's per-layer views, OutputImage::layer and camera (the right eye's
// keeps the left eye's plan: one plan): every frame's layers a single-eye effect's bits, no library
// allocation after the first frame's plan; the fixed costs (device memory with the ring, pipelines)
// one effect's; a layer beyond maxImageArrayLayers refused.
#include <cstdio>

#include "analytic_scenes.h"
#include "library_allocations.h"
#include "sao/presets.h"
#include "vk_array_image.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kEyes = 2;
constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

// The left (eye 0) and right (eye 1) cameras: mirrored asymmetric frusta (projection row 0, column 2).
Camera eyeCamera(std::uint32_t eye) {
  Camera c = vulkanCamera(kW, kH, 8);
  c.projection[2 * 4 + 0] += eye == 0 ? 0.04 : -0.04;
  return c;
}

class Stereo : public VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
      cameras[eye] = eyeCamera(eye);
      depth[eye] = test::renderDepth(test::sphereOnPlaneScene(), cameras[eye], DepthFormat::D32F);
    }
    ASSERT_TRUE(uploadDepthLayers({&depth[0], &depth[1]}, kRead, depthArray).ok());
    ASSERT_TRUE(
        createArrayImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, kEyes, kOutputArrayUsage, VK_IMAGE_ASPECT_COLOR_BIT, outputArray)
            .ok());
  }
  void TearDown() override {
    destroy(depthArray);
    destroy(outputArray);
    VkTest::TearDown();
  }

  // The stereo effect has a ring of 2 * kEyes: two records (eyes) per frame, two frames in flight.
  // Its output is the caller's (one layer per eye).
  static std::unique_ptr<vk::Effect> create(std::uint32_t n) { return makeEffect({.framesInFlight = n}); }
  vk::OutputImage eyeOutput(std::uint32_t eye) const {
    return {outputArray.image, outputArray.views[eye], VK_FORMAT_R16_SFLOAT, {kW, kH}, VK_IMAGE_LAYOUT_UNDEFINED, eye};
  }
  vk::Inputs eyeInputs(std::uint32_t eye) const {
    vk::Inputs in;
    in.depth = {depthArray.views[eye], kRead, depth[eye].extent, VK_FORMAT_D32_SFLOAT};
    return in;
  }
  // One eye's record of `e` into `cmd`: its camera, depth layer and output layer.
  Status recordEye(vk::Effect& e, VkCommandBuffer cmd, std::uint32_t eye, const Settings& settings) const {
    const vk::OutputImage o = eyeOutput(eye);
    return e.record(cmd, cameras[eye], settings, eyeInputs(eye), &o);
  }
  // One stereo frame: both eyes recorded into one command buffer (left, then right), submitted and
  // waited for; library allocations within the records counted.
  Status stereoFrame(vk::Effect& e, long* counted = nullptr,
                     const Settings& settings = presetSettings(Preset::Medium)) const {
    Status recorded;
    const Status submitted = context().submit([&](VkCommandBuffer cmd) {
      test::startCountingAllocations();
      for (std::uint32_t eye = 0; eye < kEyes && recorded; ++eye) recorded = recordEye(e, cmd, eye, settings);
      test::stopCountingAllocations();
      if (counted) *counted += test::countedAllocations();
    });
    return submitted ? recorded : submitted;
  }
  FloatImage layer(const vk::Effect& e, std::uint32_t eye) const {
    FloatImage out;
    const vk::Config& c = e.config();
    EXPECT_TRUE(readLayer(outputArray, eye, c.outputLayout, c.outputDstStages, c.outputDstAccess, out).ok());
    return out;
  }
  // A single-eye effect on a plain 2D depth with that eye's camera: the reference.
  FloatImage mono(std::uint32_t eye, const Settings& settings) const {
    RunResult r;
    const Status st = runEffect(settings, cameras[eye], depth[eye], VkDepth::D32F, r, {.readIntermediates = false});
    EXPECT_TRUE(st.ok()) << st.message;
    return r.ao;
  }

  Camera cameras[kEyes];
  DepthImage depth[kEyes];
  ArrayImage depthArray, outputArray;
};

// Nine stereo frames per estimator (1: the visibility estimator, thickness from width): each
// layer the single-eye effect's bits every frame, no library allocation after the first frame. (The
// single-eye effect within the CPU reference's bounds on these cameras, both estimators:
// exec.stereo's OneEffectRendersEachLayerAsASingleEyeEffect/vulkan_camera*.)
TEST_F(Stereo, BothEyesInOneCommandBufferMatchSingleEyeEffects) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  for (int estimator : {0, 1}) {
    SCOPED_TRACE("estimator " + std::to_string(estimator));
    Settings settings = presetSettings(Preset::Medium);
    settings.estimator = settings.thickness_model = estimator;
    const FloatImage expected[kEyes] = {mono(0, settings), mono(1, settings)};
    auto effect = create(2 * kEyes);
    ASSERT_TRUE(effect);
    long counted = 0;
    for (int f = 0; f < 9; ++f) {
      const Status st = stereoFrame(*effect, f > 0 ? &counted : nullptr, settings);
      ASSERT_TRUE(st.ok()) << "frame " << f << ": " << st.message;
      for (std::uint32_t eye = 0; eye < kEyes; ++eye)
        EXPECT_EQ(test::differingValues(layer(*effect, eye), expected[eye]), 0u) << "frame " << f << " eye " << eye;
    }
    EXPECT_EQ(counted, 0) << "library allocations in 16 stereo record() calls";
    EXPECT_EQ(effect->plans(), 1u) << "the right eye's camera keeps the left eye's plan";
  }
}

// The fixed costs of stereo are one eye's: once planned, the stereo effect (both eyes recorded)
// holds exactly the device memory and pipelines of a single-eye effect with the same ring (one eye
// recorded), and less memory than two single-eye effects (the VR renderer's alternative, one per eye
// with 2 frames in flight each).
TEST_F(Stereo, FixedCostsAreOneEffects) {
  auto stereo = create(2 * kEyes);
  auto sameRing = create(2 * kEyes);
  auto left = create(2);
  auto right = create(2);
  ASSERT_TRUE(stereo && sameRing && left && right);
  ASSERT_TRUE(stereoFrame(*stereo).ok());
  // Each single-eye effect records its eye once (the record that plans), into its own command buffer.
  const std::pair<vk::Effect*, std::uint32_t> singles[] = {{sameRing.get(), 1}, {left.get(), 0}, {right.get(), 1}};
  for (const auto& [e, eye] : singles) {
    const Status recorded =
        submitRecord([&](VkCommandBuffer cmd) { return recordEye(*e, cmd, eye, presetSettings(Preset::Medium)); });
    ASSERT_TRUE(recorded.ok()) << recorded.message;
  }
  const vk::MemoryStats s = stereo->memoryStats(), m = sameRing->memoryStats();
  const std::uint64_t two = left->memoryStats().liveBytes + right->memoryStats().liveBytes;
  std::printf("device memory: stereo (framesInFlight 4) %llu bytes in %llu allocations, one eye's with the same ring %llu, "
              "two single-eye effects (2 each) %llu\n", (unsigned long long)s.liveBytes,
              (unsigned long long)s.liveAllocations, (unsigned long long)m.liveBytes, (unsigned long long)two);
  EXPECT_EQ(s.liveBytes, m.liveBytes) << "the stereo effect is one effect's memory";
  EXPECT_EQ(s.liveAllocations, m.liveAllocations);
  EXPECT_LT(s.liveBytes, two);
  EXPECT_EQ(stereo->pipelineCount(), left->pipelineCount());
  EXPECT_EQ(left->pipelineCount(), right->pipelineCount());
  // Recording both eyes again builds nothing more and allocates no device memory.
  const Status st = stereoFrame(*stereo);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(stereo->memoryStats().totalAllocations, s.totalAllocations);
  EXPECT_EQ(stereo->pipelineCount(), left->pipelineCount());
  EXPECT_EQ(stereo->plans(), 1u);
}

// A layer beyond the device's maxImageArrayLayers cannot be one of the image's: refused on a planned
// effect, nothing recorded, no new plan; the next stereo frame is right.
TEST_F(Stereo, RefusesALayerNoImageHas) {
  auto effect = create(2 * kEyes);
  ASSERT_TRUE(effect);
  ASSERT_TRUE(stereoFrame(*effect).ok());
  vk::OutputImage o = eyeOutput(1);
  o.layer = context().properties().limits.maxImageArrayLayers;
  const Settings settings = presetSettings(Preset::Medium);
  const Status st =
      submitRecord([&](VkCommandBuffer cmd) { return effect->record(cmd, cameras[1], settings, eyeInputs(1), &o); });
  expectStatus(st, StatusCode::InvalidInput, "OutputImage::layer");
  EXPECT_NE(st.message.find("maxImageArrayLayers"), std::string::npos) << st.message;
  EXPECT_EQ(effect->plans(), 1u);
  ASSERT_TRUE(stereoFrame(*effect).ok());
  EXPECT_EQ(test::differingValues(layer(*effect, 1), mono(1, presetSettings(Preset::Medium))), 0u);
}

}  // namespace
}  // namespace sao::vktest
