// render() allocates nothing per frame, what only GL has (the shared cases, the effect's own
// output, the caller's output and supplied normals, are tests/executors/frame_allocation_test.cpp):
// timed frames (RenderOptions::measureTime) and jittered stereo layers of array textures, counting
// every operator new called from libsao_gl.so's code (tests/common/library_allocations.h).
#include <epoxy/gl.h>

#include <vector>

#include "analytic_scenes.h"
#include "gl_support.h"
#include "library_allocations.h"

namespace sao::gltest {
namespace {

constexpr int kFrames = 100;

class FrameAllocations : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&gl::Effect::create)));
    cam = camera(48, 27, 4);
    depth = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D24);
    texture = uploadDepth(depth, GlDepth::D24);
  }
  void TearDown() override {
    deleteTexture(texture);
    GlTest::TearDown();
  }
  gl::Inputs inputs() const {
    gl::Inputs in;
    in.depth = {texture, gl::kDepthComponent24};
    return in;
  }

  Camera cam;
  DepthImage depth;
  GLuint texture = 0;
};

// Timed frames (RenderOptions::measureTime): the first makes the queries, the next kFrames nothing.
TEST_F(FrameAllocations, TimedRenderAllocatesNothingPerFrame) {
  auto e = makeEffect();
  ASSERT_TRUE(e);
  gl::RenderOptions options;
  options.measureTime = true;
  ASSERT_TRUE(e->render(cam, Settings{}, inputs(), options).ok());
  long counted = 0;
  for (int f = 0; f < kFrames; ++f) {
    test::startCountingAllocations();
    const Status st = e->render(cam, Settings{}, inputs(), options);
    test::stopCountingAllocations();
    counted += test::countedAllocations();
    EXPECT_TRUE(st.ok()) << st.message;
  }
  EXPECT_EQ(counted, 0) << "library allocations in " << kFrames << " timed render() calls";
}

// Stereo with TAA jitter: each frame renders two layers of array textures (Inputs::layer), each
// eye's camera jittered; no library allocation and no new plan after the first frame.
TEST_F(FrameAllocations, JitteredStereoLayersAllocateNothing) {
  const GLuint depthArray = uploadDepthArray(GL_DEPTH_COMPONENT24, {&depth, &depth});
  const GLuint outArray = makeTextureArray(GL_R16F, {cam.width, cam.height}, 2);
  auto e = makeEffect();
  ASSERT_TRUE(e);
  const Settings settings;
  long counted = 0;
  for (int f = 0; f <= kFrames; ++f)
    for (std::uint32_t eye = 0; eye < 2; ++eye) {
      Camera c = cam;
      c.projection[2 * 4 + 0] += (eye == 0 ? 0.04 : -0.04) + 0.0005 * (f % 8);
      gl::Inputs in;
      in.depth = {depthArray, gl::kDepthComponent24};
      in.output = outArray;
      in.layer = eye;
      if (f > 0) test::startCountingAllocations();  // frame 0 plans
      const Status st = e->render(c, settings, in);
      if (f > 0) {
        test::stopCountingAllocations();
        counted += test::countedAllocations();
      }
      ASSERT_TRUE(st.ok()) << st.message;
    }
  EXPECT_EQ(counted, 0) << "library allocations in " << 2 * kFrames << " jittered stereo render() calls";
  EXPECT_EQ(e->stats().plans, 1u);
  glDeleteTextures(1, &depthArray);
  glDeleteTextures(1, &outArray);
}

}  // namespace
}  // namespace sao::gltest
