// Stereo (VR) on each API: two eyes with mirrored off-axis projections (as VR runtimes give), their
// depth in one 2-layer array and their AO in the caller's 2-layer output array (Frame::depthLayers),
// rendered by ONE effect, one call per eye with the eye's camera (GL Inputs::layer; Vulkan a 2D
// view per layer and OutputImage::layer). For both estimators and both cameras' depth conventions:
// the eyes plan alike; every frame each layer is bit for bit what a single-eye effect writes from a
// plain 2D depth, and agrees with the CPU reference within reference_test.cpp's bounds; the second
// eye and later frames plan nothing, make no image or pipeline and no library allocation; one set
// of intermediates serves both eyes. What one API alone has: tests/gl/stereo_test.cpp (the caller's
// array bindings, multisampled depth arrays, refusals) and tests/vulkan/stereo_test.cpp (both eyes
// in one command buffer, fixed costs with the ring, a layer beyond maxImageArrayLayers).
#include <algorithm>
#include <cstdio>

#include "harness.h"
#include "api_allocations.h"
#include "sao/frame.h"
#include "sao/presets.h"

namespace sao::exectest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8, kEyes = 2;
constexpr int kFrames = 8;  // after the first stereo frame, which may allocate

// GL's old case (OpenGL depth, estimator 0) and Vulkan's (Vulkan depth, both estimators), on both.
struct StereoCase {
  std::string name;
  Camera camera;
  int estimator;  // 1: the visibility estimator, with thickness from width
};
std::string caseName(const StereoCase& c) { return c.name; }
void PrintTo(const StereoCase& c, std::ostream* os) { *os << c.name; }
const std::vector<StereoCase> kCases = {{"opengl_camera", test::openglCamera(kW, kH, kGuard), 0},
                                        {"opengl_camera_visibility", test::openglCamera(kW, kH, kGuard), 1},
                                        {"vulkan_camera", test::vulkanCamera(kW, kH, kGuard), 0},
                                        {"vulkan_camera_visibility", test::vulkanCamera(kW, kH, kGuard), 1}};

using Stereo = ApiCaseTest<StereoCase>;
TEST_P(Stereo, OneEffectRendersEachLayerAsASingleEyeEffect) {
  ASSERT_TRUE(watchApiLibrary(api()));
  Settings settings = presetSettings(Preset::Medium);
  settings.estimator = settings.thickness_model = param().estimator;
  Camera eyes[kEyes] = {param().camera, param().camera};
  eyes[0].projection[2 * 4 + 0] += 0.04;  // projection row 0, column 2: the left frustum shifted right
  eyes[1].projection[2 * 4 + 0] -= 0.04;
  DepthImage depth[kEyes];
  for (std::uint32_t eye = 0; eye < kEyes; ++eye)
    depth[eye] = test::renderDepth(test::sphereOnPlaneScene(), eyes[eye], DepthFormat::D32F);

  // What lets one effect serve both eyes: they plan alike, the effect's output or the caller's.
  for (bool userOutput : {false, true}) {
    PlanInputs inputs;
    inputs.userOutput = userOutput;
    Plan a, b;
    ASSERT_TRUE(plan(settings, eyes[0], inputs, a).ok());
    ASSERT_TRUE(plan(settings, eyes[1], inputs, b).ok());
    EXPECT_EQ(a.describe(), b.describe()) << "mirrored eyes plan alike";
    EXPECT_EQ(a.totalBytes, b.totalBytes);
    EXPECT_EQ(a.cszLevels, b.cszLevels);
  }
  EXPECT_TRUE(cameraKeepsPlan(settings, eyes[0], eyes[1]));
  EXPECT_NE(eyes[0].projection, eyes[1].projection) << "the eyes must differ";

  auto stereo = make();
  Frame f;
  f.settings = settings;
  f.camera = eyes[0];
  f.depthLayers = {&depth[0], &depth[1]};
  f.output.callerOwned = true;  // one layer per eye
  ASSERT_TRUE(stereo->upload(f).ok());
  std::uint64_t images = 0, pipelines = 0;
  FloatImage first[kEyes];
  long counted = 0;
  for (int frame = 0; frame <= kFrames; ++frame) {
    for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
      f.camera = eyes[eye];
      f.layer = eye;
      if (frame > 0) test::startCountingAllocations();
      const Status st = stereo->run(f);
      if (frame > 0) test::stopCountingAllocations();
      counted += frame > 0 ? test::countedAllocations() : 0;
      ASSERT_TRUE(st.ok()) << "frame " << frame << " eye " << eye << ": " << st.message;
      if (frame == 0 && eye == 0) {
        images = stereo->imageAllocations();
        pipelines = stereo->pipelines();
      }
      const FloatImage layer = stereo->output();
      if (frame == 0) first[eye] = layer;
      else EXPECT_EQ(test::differingValues(layer, first[eye]), 0u) << "frame " << frame << " eye " << eye;
    }
  }
  // The fixed costs, paid once: one plan, one set of pipelines and intermediate images.
  EXPECT_EQ(stereo->plans(), 1u) << "the second eye and later frames plan nothing";
  EXPECT_EQ(stereo->imageAllocations(), images);
  EXPECT_EQ(stereo->pipelines(), pipelines);
  EXPECT_EQ(counted, 0) << "library allocations in " << kEyes * kFrames << " per-eye calls";

  std::uint64_t singleBytes = 0;
  for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
    const std::string name = "stereo_" + param().name + (eye == 0 ? "_left" : "_right");
    SCOPED_TRACE(name);
    Frame m;  // the single-eye effect: a plain 2D depth, its own output
    m.settings = settings;
    m.camera = eyes[eye];
    m.depth = &depth[eye];
    auto single = make();
    const Status st = single->render(m);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(test::differingValues(first[eye], single->output()), 0u) << "bit for bit the single-eye effect's";
    EXPECT_EQ(single->pipelines(), stereo->pipelines());
    singleBytes += single->plan().totalBytes;
    cpu::Result ref;
    const Status cs = runCpu(m, ref);
    ASSERT_TRUE(cs.ok()) << cs.message;
    std::string note;
    const Agreement a = compare(api(), first[eye], ref.ao, 0, kWithin, kNever, name, &note);
    EXPECT_TRUE(acceptable(a)) << a.fractionWithin * 100 << "% within 2/255, " << a.beyond << " beyond 4/255, max "
                               << a.maxAbs * 255 << "/255. " << note;
    std::printf("STEREO %-6s %-36s vs CPU max %.4f/255, p999 %.4f/255, %.3f%% within 2/255\n", toString(api()),
                name.c_str(), a.maxAbs * 255, a.p999 * 255, a.fractionWithin * 100);
    EXPECT_LT(*std::min_element(first[eye].data.begin(), first[eye].data.end()), 0.5f) << "no occlusion: proves little";
  }
  // The caller's output is not in the stereo plan's bytes; each single-eye effect's own output is.
  std::printf("STEREO %-6s one effect %llu bytes; two single-eye effects %llu bytes\n", toString(api()),
              (unsigned long long)stereo->plan().totalBytes, (unsigned long long)singleBytes);
  EXPECT_LE(2 * stereo->plan().totalBytes, singleBytes) << "one set of intermediates for both eyes";
  EXPECT_GT(test::differingValues(first[0], first[1]), 0u) << "the eyes gave the same image: proves nothing";
}
SAO_INSTANTIATE_API_CASES(Stereo, kCases);

}  // namespace
}  // namespace sao::exectest
