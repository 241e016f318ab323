// The per-frame call allocates nothing: 100 frames with one configuration (the effect's own
// output, the caller's output, supplied normals), counting every operator new called from the
// API's own library (tests/common/library_allocations.h; GL render(), Vulkan record()). A changed
// setting makes the next call plan again and allocate, which shows the counter sees the library.
// Timed frames and GL's stereo layers stay in tests/gl and tests/vulkan.
#include <cstdio>

#include "harness.h"
#include "api_allocations.h"

namespace sao::exectest {
namespace {

constexpr int kFrames = 100;

// Each API's old case: GL's camera and D24, Vulkan's camera and D32F.
struct ViewCase {
  std::string name;
  Camera camera;
  Depth format;
};
std::string caseName(const ViewCase& c) { return c.name; }
void PrintTo(const ViewCase& c, std::ostream* os) { *os << c.name; }
const std::vector<ViewCase> kViews = {{"opengl_camera_D24", test::openglCamera(48, 27, 4), Depth::D24},
                                      {"vulkan_camera_D32F", test::vulkanCamera(48, 27, 4), Depth::D32F}};

class FrameAllocations : public ApiCaseTest<ViewCase> {
 protected:
  void SetUp() override {
    ApiCaseTest::SetUp();
    ASSERT_TRUE(watchApiLibrary(api()));
    depth = test::renderDepth(test::sphereOnPlaneScene(), param().camera, cpuFormat(param().format));
    frame.camera = param().camera;
    frame.depth = &depth;
    frame.format = param().format;
  }
  // One call counted.
  long countedRun(Executor& e) {
    test::startCountingAllocations();
    const Status st = e.run(frame);
    test::stopCountingAllocations();
    EXPECT_TRUE(st.ok()) << st.message;
    return test::countedAllocations();
  }
  // Uploads the frame and runs it once (the configuration's first frame), then counts kFrames calls
  // with a jittered camera (TAA: it keeps the plan, so nothing is planned or allocated).
  long steadyFrames(Executor& e) {
    EXPECT_TRUE(e.render(frame).ok());
    const Camera still = frame.camera;
    long counted = 0;
    for (int f = 0; f < kFrames; ++f) {
      frame.camera.projection[8] = still.projection[8] + 1e-4 * (f % 4);
      counted += countedRun(e);
    }
    frame.camera = still;
    return counted;
  }

  DepthImage depth;
  Frame frame;
};

TEST_P(FrameAllocations, EffectOwnedOutputAllocatesNothingPerFrame) {
  auto e = make();
  EXPECT_EQ(steadyFrames(*e), 0) << "library allocations in " << kFrames << " calls";
  frame.settings.blur_radius = 0;  // another plan: one call plans, schedules and allocates
  const long replanned = countedRun(*e);
  EXPECT_GT(replanned, 0);
  long counted = 0;
  for (int f = 0; f < kFrames; ++f) counted += countedRun(*e);
  EXPECT_EQ(counted, 0) << "after the new configuration";
  std::printf("%s: a new configuration: %ld library allocations; %d steady calls: none\n", toString(api()), replanned,
              2 * kFrames);
}

TEST_P(FrameAllocations, CallersOutputAllocatesNothingPerFrame) {
  frame.output.callerOwned = true;
  EXPECT_EQ(steadyFrames(*make()), 0);
}

// Supplied normals are checked every frame (their format against the camera's encoding): an
// accepted image costs no allocation either, two-channel octahedral or four-channel xyz.
TEST_P(FrameAllocations, WithSuppliedNormalsAllocatesNothingPerFrame) {
  FloatImage facing(depth.extent, 4);  // +z either way: octahedral (0, 0) in .xy, xyz (0, 0, 1)
  for (std::size_t i = 2; i < facing.data.size(); i += 4) facing.data[i] = 1.0f;
  frame.normals = &facing;
  auto e = make();
  for (auto [texels, encoding] : {std::pair{Texels::RG16F, NormalsEncoding::CameraOctahedral},
                                  std::pair{Texels::RGBA16F, NormalsEncoding::CameraXyz}}) {
    frame.normalsTexels = texels;
    frame.camera.normalsEncoding = encoding;
    EXPECT_EQ(steadyFrames(*e), 0) << "normals texels " << int(texels);
  }
}
SAO_INSTANTIATE_API_CASES(FrameAllocations, kViews);

}  // namespace
}  // namespace sao::exectest
