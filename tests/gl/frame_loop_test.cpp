// The frame loop holds on OpenGL too (issue 19): 2000 frames of one effect, render() then glFinish()
// per frame, with timed frames (GL_TIMESTAMP queries) as in an engine's profiling build. Host memory
// in use (mallinfo2) after a 100-frame warm-up may grow by less than 1 KB per frame, amortised.
#include <epoxy/gl.h>
#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "analytic_scenes.h"
#include "gl_support.h"

namespace sao::gltest {
namespace {

constexpr int kFrames = 2000;
constexpr int kWarmUp = 100;
constexpr double kAllowedBytesPerFrame = 1024;

// Under AddressSanitizer the allocator quarantines freed blocks: mallinfo2 says nothing there
// (ci/sanitize.sh sets SAO_SANITIZED for the uninstrumented-compiler case too).
bool sanitized() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#else
  return std::getenv("SAO_SANITIZED") != nullptr;
#endif
}

class GlFrameLoop : public GlTest {};

TEST_F(GlFrameLoop, Render2000FramesHoldsHostMemory) {
  if (sanitized()) GTEST_SKIP() << "heap figures are meaningless under the sanitizers' allocator";
  const Camera cam = camera(64, 64, 4);
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D24);
  const GLuint texture = uploadDepth(depth, GlDepth::D24);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  gl::Inputs in;
  in.depth = {texture, gl::kDepthComponent24};
  gl::RenderOptions options;
  options.measureTime = true;
  const Settings settings;

  std::size_t warm = 0;
  for (int f = 0; f < kFrames; ++f) {
    if (f == kWarmUp) warm = mallinfo2().uordblks;
    const Status st = effect->render(cam, settings, in, options);
    ASSERT_TRUE(st.ok()) << "frame " << f << ": " << st.message;
    glFinish();
  }
  const double perFrame = (double(mallinfo2().uordblks) - double(warm)) / (kFrames - kWarmUp);
  effect.reset();
  deleteTexture(texture);
  std::printf("[frame loop] OpenGL (%s): %+.1f heap bytes/frame over %d frames after %d\n",
              reinterpret_cast<const char*>(glGetString(GL_RENDERER)), perFrame, kFrames - kWarmUp, kWarmUp);
  EXPECT_LT(perFrame, kAllowedBytesPerFrame) << "host memory grows with rendered frames";
}

// Temporal accumulation in the loop: the camera moves every frame (Camera::view), the frame index
// counts up and the history images trade places; still no host memory per frame.
TEST_F(GlFrameLoop, TemporalMovingCameraHoldsHostMemory) {
  if (sanitized()) GTEST_SKIP() << "heap figures are meaningless under the sanitizers' allocator";
  const Camera base = camera(64, 64, 4);
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), base, DepthFormat::D24);
  const GLuint texture = uploadDepth(depth, GlDepth::D24);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  gl::Inputs in;
  in.depth = {texture, gl::kDepthComponent24};
  Settings settings;
  settings.temporal = true;
  std::size_t warm = 0;
  for (int f = 0; f < kFrames; ++f) {
    if (f == kWarmUp) warm = mallinfo2().uordblks;
    Camera cam = base;
    cam.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -0.001 * (f % 100), 0, 0, 1};
    in.frameIndex = std::uint32_t(f);
    const Status st = effect->render(cam, settings, in);
    ASSERT_TRUE(st.ok()) << "frame " << f << ": " << st.message;
    ASSERT_EQ(effect->params().history_valid, f > 0 ? 1 : 0) << "frame " << f;
    glFinish();
  }
  const double perFrame = (double(mallinfo2().uordblks) - double(warm)) / (kFrames - kWarmUp);
  EXPECT_EQ(effect->stats().plans, 1u);
  effect.reset();
  deleteTexture(texture);
  std::printf("[frame loop] OpenGL temporal: %+.1f heap bytes/frame over %d frames after %d\n", perFrame,
              kFrames - kWarmUp, kWarmUp);
  EXPECT_LT(perFrame, kAllowedBytesPerFrame) << "host memory grows with accumulated frames";
}

// A stereo engine's loop: per frame two renders of one effect, one per layer of 2-layer arrays
// (Inputs::layer: a texture view per input made and deleted in each render), each eye's camera
// jittered per frame as TAA does. Neither plans again (one plan in all) nor grows host memory.
TEST_F(GlFrameLoop, StereoJitteredFramesHoldHostMemoryAndPlanOnce) {
  if (sanitized()) GTEST_SKIP() << "heap figures are meaningless under the sanitizers' allocator";
  const Camera base = camera(64, 64, 4);
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), base, DepthFormat::D32F);
  const GLuint depthArray = uploadDepthArray(GL_DEPTH_COMPONENT32F, {&depth, &depth});
  const GLuint outArray = makeTextureArray(GL_R16F, {base.width, base.height}, 2);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  const Settings settings;
  const int frames = kFrames / 2;  // two renders per frame: kFrames renders in all
  std::size_t warm = 0;
  for (int f = 0; f < frames; ++f) {
    if (f == kWarmUp) warm = mallinfo2().uordblks;
    for (std::uint32_t eye = 0; eye < 2; ++eye) {
      Camera c = base;
      c.projection[2 * 4 + 0] += (eye == 0 ? 0.04 : -0.04) + 0.001 * ((f * 7) % 16 - 8) / 8.0;  // eye + jitter
      c.projection[2 * 4 + 1] += 0.001 * ((f * 5) % 16 - 8) / 8.0;
      gl::Inputs in;
      in.depth = {depthArray, gl::kDepthComponent32F};
      in.output = outArray;
      in.layer = eye;
      const Status st = effect->render(c, settings, in);
      ASSERT_TRUE(st.ok()) << "frame " << f << " eye " << eye << ": " << st.message;
    }
    glFinish();
  }
  const double perFrame = (double(mallinfo2().uordblks) - double(warm)) / (frames - kWarmUp);
  EXPECT_EQ(effect->stats().plans, 1u) << "jittered eyes plan alike";
  effect.reset();
  glDeleteTextures(1, &depthArray);
  glDeleteTextures(1, &outArray);
  std::printf("[frame loop] OpenGL stereo: %+.1f heap bytes/frame (2 renders each) over %d frames after %d\n", perFrame,
              frames - kWarmUp, kWarmUp);
  EXPECT_LT(perFrame, kAllowedBytesPerFrame) << "host memory grows with rendered stereo frames";
}

}  // namespace
}  // namespace sao::gltest
