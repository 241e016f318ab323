// The frame loop holds on OpenGL too (issue 19): 2000 frames of one effect, render() then glFinish()
// per frame, with timed frames (GL_TIMESTAMP queries) as in an engine's profiling build. Host memory
// in use (mallinfo2) after a 100-frame warm-up may grow by less than 1 KB per frame, amortised.
#include <epoxy/gl.h>
#include <malloc.h>

#include <cstdio>
#include <cstdlib>

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

}  // namespace
}  // namespace sao::gltest
