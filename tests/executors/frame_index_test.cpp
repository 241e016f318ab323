// Inputs::frameIndex (sao::frameSpiral): frames 0, 7 and 1000 rendered one after another by one
// effect, each against the CPU reference (float) at the agreement bounds; frames 7 and 1000 differ
// from frame 0, and a new frame is no new plan, image or pipeline (Vulkan: each
// frame's block in its ring slot). Under GL's and Vulkan's depth conventions.
#include <cstdio>
#include <string>

#include "harness.h"
#include "sao/presets.h"

namespace sao::exectest {
namespace {

using FrameIndex = ApiTest;

TEST_P(FrameIndex, EveryFrameMatchesTheCpuReference) {
  for (const auto& [convention, cam] :
       {std::pair{"opengl", test::openglCamera(160, 90, 8)},
        std::pair{"vulkan_reversed_infinite", test::vulkanCamera(160, 90, 8, INFINITY, /*reversedZ=*/true)}}) {
    SCOPED_TRACE(convention);
    const DepthImage depth = test::renderDepth(sceneByName("sphere"), cam, DepthFormat::D32F);
    Frame f;
    f.settings = presetSettings(Preset::Medium);
    f.camera = cam;
    f.depth = &depth;
    auto e = make();
    FloatImage frame0;
    std::uint64_t plans = 0, images = 0, pipelines = 0;
    for (std::uint32_t frame : {0u, 7u, 1000u}) {
      const std::string name = std::string(convention) + "_frame" + std::to_string(frame);
      f.frameIndex = frame;
      const Status st = e->render(f);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Result ref;
      ASSERT_TRUE(runCpu(f, ref).ok());
      expectAgreesWithCpu(*e, ref, name);
      const FloatImage ao = e->output();
      if (frame == 0) {
        frame0 = ao;
        plans = e->plans(), images = e->imageAllocations(), pipelines = e->pipelines();
        continue;
      }
      std::size_t changed = 0;
      for (std::size_t i = 0; i < ao.data.size(); ++i) changed += ao.data[i] != frame0.data[i];
      EXPECT_GT(changed, ao.data.size() / 10) << name << " looks like frame 0";
    }
    EXPECT_EQ(e->plans(), plans) << "a new frame is not a new plan";
    EXPECT_EQ(e->imageAllocations(), images) << "a new frame is not a new plan";
    EXPECT_EQ(e->pipelines(), pipelines) << "a new frame is not a new plan";
  }
}
SAO_INSTANTIATE_APIS(FrameIndex);

}  // namespace
}  // namespace sao::exectest
