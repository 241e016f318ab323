// record() allocates nothing per frame with timestamps (Config::timestamps), what only Vulkan
// has (the shared cases, the effect's own output, the caller's output, supplied normals and a new
// configuration allocating, are tests/executors/frame_allocation_test.cpp): 100 frames recorded
// and submitted after the record that plans, and again after a record with other settings plans
// again, counting every operator new called from libsao_vulkan.so's code
// (tests/common/library_allocations.h).
#include "analytic_scenes.h"
#include "library_allocations.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr int kFrames = 100;

using FrameAllocations = VkTest;
TEST_F(FrameAllocations, TimestampedRecordAllocatesNothingPerFrame) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  vk::Config config;
  config.framesInFlight = 2;
  config.timestamps = true;
  const Camera camera = vulkanCamera(48, 27, 4);
  Settings settings;
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
  vk::headless::Image image;
  ASSERT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image).ok());
  vk::Inputs in;
  in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(context().deviceContext(), config, e).ok());
  // The record that plans (not counted: a plan allocates), then the library allocations counted
  // while recording kFrames frames on that plan.
  auto recordFrames = [&] {
    long counted = 0;
    for (int f = 0; f <= kFrames; ++f) {
      Status recorded;
      const Status submitted = context().submit([&](VkCommandBuffer cmd) {
        test::startCountingAllocations();
        recorded = e->record(cmd, camera, settings, in);
        test::stopCountingAllocations();
        if (f > 0) counted += test::countedAllocations();
      });
      EXPECT_TRUE(submitted.ok()) << submitted.message;
      EXPECT_TRUE(recorded.ok()) << recorded.message;
    }
    return counted;
  };
  EXPECT_EQ(recordFrames(), 0) << "library allocations in " << kFrames << " record() calls";
  EXPECT_EQ(e->plans(), 1u);
  // Other settings: the first record plans again (its old images retired two records later, within
  // the counted frames), then kFrames on the new plan.
  settings.blur_radius = 0;
  EXPECT_EQ(recordFrames(), 0) << "after a new plan";
  EXPECT_EQ(e->plans(), 2u);
  e.reset();
  context().destroy(image);
}

}  // namespace
}  // namespace sao::vktest
