// record() allocates nothing per frame: 100 frames recorded and submitted with one configuration
// (effect-owned output, then the caller's own output), counting every operator new called from
// libsao_vulkan.so's code (tests/common/library_allocations.h). update() to a new configuration
// allocates, which shows the counter sees the library.
#include <cstdio>

#include "analytic_scenes.h"
#include "image_compare.h"
#include "library_allocations.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr int kFrames = 100;

class FrameAllocations : public VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
    camera = vulkanCamera(48, 27, 4);
    depth = test::renderDepth(test::sphereOnPlaneScene(), camera, DepthFormat::D32F);
    ASSERT_TRUE(context()
                    .uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image)
                    .ok());
    config.camera = camera;
    config.depthFormat = VK_FORMAT_D32_SFLOAT;
    config.framesInFlight = 2;
  }
  void TearDown() override {
    context().destroy(image);
    VkTest::TearDown();
  }
  vk::Inputs inputs() const {
    vk::Inputs in;
    in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
    return in;
  }
  // Records and submits kFrames frames; the library allocations counted while recording.
  long recordFrames(vk::Effect& e, const vk::OutputImage* output) {
    long counted = 0;
    for (int f = 0; f < kFrames; ++f) {
      Status recorded;
      const Status submitted = context().submit([&](VkCommandBuffer cmd) {
        test::startCountingAllocations();
        recorded = e.record(cmd, inputs(), output);
        test::stopCountingAllocations();
        counted += test::countedAllocations();
      });
      EXPECT_TRUE(submitted.ok()) << submitted.message;
      EXPECT_TRUE(recorded.ok()) << recorded.message;
    }
    return counted;
  }

  Camera camera;
  DepthImage depth;
  vk::headless::Image image;
  vk::Config config;
};

TEST_F(FrameAllocations, RecordAllocatesNothingPerFrame) {
  config.timestamps = true;
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(context().deviceContext(), config, e).ok());
  EXPECT_EQ(recordFrames(*e, nullptr), 0) << "library allocations in " << kFrames << " record() calls";

  // The counter sees the library: a new configuration allocates (a plan, a schedule, images).
  vk::Config other = config;
  other.settings.blur_radius = 0;
  test::startCountingAllocations();
  ASSERT_TRUE(e->update(other).ok());
  test::stopCountingAllocations();
  const long updateAllocations = test::countedAllocations();
  EXPECT_GT(updateAllocations, 0);
  EXPECT_EQ(recordFrames(*e, nullptr), 0) << "after update()";
  std::printf("update(): %ld library allocations; %d record() calls: none\n", updateAllocations, 2 * kFrames);
}

TEST_F(FrameAllocations, RecordIntoTheCallersOutputAllocatesNothing) {
  config.userOutput = true;
  std::unique_ptr<vk::Effect> e;
  ASSERT_TRUE(vk::Effect::create(context().deviceContext(), config, e).ok());
  vk::headless::Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {camera.width, camera.height}, out).ok());
  const vk::OutputImage output{out.image, out.view, VK_FORMAT_R16_SFLOAT, {camera.width, camera.height},
                               config.outputLayout};
  EXPECT_EQ(recordFrames(*e, &output), 0);
  context().destroy(out);
}

}  // namespace
}  // namespace sao::vktest
