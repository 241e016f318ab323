// record() allocates nothing per frame with timestamps (Config::timestamps), what only Vulkan
// has (the shared cases, the effect's own output, the caller's output, supplied normals and a new
// configuration allocating, are tests/executors/frame_allocation_test.cpp): 100 frames recorded
// and submitted, before and after update(), counting every operator new called from
// libsao_vulkan.so's code (tests/common/library_allocations.h).
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
  config.camera = vulkanCamera(48, 27, 4);
  config.depthFormat = VK_FORMAT_D32_SFLOAT;
  config.framesInFlight = 2;
  config.timestamps = true;
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), config.camera, DepthFormat::D32F);
  vk::headless::Image image;
  ASSERT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image).ok());
  vk::Inputs in;
  in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(context().deviceContext(), config, e).ok());
  auto recordFrames = [&] {  // the library allocations counted while recording kFrames frames
    long counted = 0;
    for (int f = 0; f < kFrames; ++f) {
      Status recorded;
      const Status submitted = context().submit([&](VkCommandBuffer cmd) {
        test::startCountingAllocations();
        recorded = e->record(cmd, in);
        test::stopCountingAllocations();
        counted += test::countedAllocations();
      });
      EXPECT_TRUE(submitted.ok()) << submitted.message;
      EXPECT_TRUE(recorded.ok()) << recorded.message;
    }
    return counted;
  };
  EXPECT_EQ(recordFrames(), 0) << "library allocations in " << kFrames << " record() calls";
  config.settings.blur_radius = 0;
  ASSERT_TRUE(e->update(config).ok());
  EXPECT_EQ(recordFrames(), 0) << "after update()";
  e.reset();
  context().destroy(image);
}

}  // namespace
}  // namespace sao::vktest
