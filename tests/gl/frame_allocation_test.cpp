// render() allocates nothing per frame: 100 frames with one configuration (effect-owned output,
// the caller's output, timed frames), counting every operator new called from libsao_gl.so's code
// (tests/common/library_allocations.h). A changed setting makes the next render() plan again and
// allocate, which shows the counter sees the library. Supplied normals (checked every frame) too.
#include <epoxy/gl.h>

#include <cstdio>
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
  gl::Inputs inputs(GLuint output = 0) const {
    gl::Inputs in;
    in.depth = {texture, gl::kDepthComponent24};
    in.output = output;
    in.normals = normals;
    return in;
  }
  // Renders once (the configuration's first frame), then counts the library allocations of kFrames.
  long steadyFrames(gl::Effect& e, const Settings& settings, GLuint output, bool timed) {
    gl::RenderOptions options;
    options.measureTime = timed;
    EXPECT_TRUE(e.render(cam, settings, inputs(output), options).ok());
    long counted = 0;
    for (int f = 0; f < kFrames; ++f) {
      test::startCountingAllocations();
      const Status st = e.render(cam, settings, inputs(output), options);
      test::stopCountingAllocations();
      counted += test::countedAllocations();
      EXPECT_TRUE(st.ok()) << st.message;
    }
    return counted;
  }

  Camera cam;
  DepthImage depth;
  GLuint texture = 0;
  GLuint normals = 0;  // passed by inputs() when set
};

TEST_F(FrameAllocations, RenderAllocatesNothingPerFrame) {
  auto e = makeEffect();
  ASSERT_TRUE(e);
  Settings settings;
  EXPECT_EQ(steadyFrames(*e, settings, 0, false), 0) << "library allocations in " << kFrames << " render() calls";
  EXPECT_EQ(steadyFrames(*e, settings, 0, true), 0) << "timed frames";

  settings.blur_radius = 0;  // another plan: one render() plans, schedules and allocates
  test::startCountingAllocations();
  ASSERT_TRUE(e->render(cam, settings, inputs()).ok());
  test::stopCountingAllocations();
  const long replanned = test::countedAllocations();
  EXPECT_GT(replanned, 0);
  EXPECT_EQ(steadyFrames(*e, settings, 0, false), 0) << "after the new configuration";
  std::printf("a new configuration: %ld library allocations; %d steady render() calls: none\n", replanned,
              3 * kFrames);
}

TEST_F(FrameAllocations, RenderIntoTheCallersOutputAllocatesNothing) {
  auto e = makeEffect();
  ASSERT_TRUE(e);
  const GLuint output = makeTexture(GL_R16F, {cam.width, cam.height});
  EXPECT_EQ(steadyFrames(*e, Settings{}, output, false), 0);
  deleteTexture(output);
}

// Supplied normals are checked on every render() (their format against the camera's encoding):
// an accepted texture costs no allocation either, two-channel octahedral or four-channel xyz.
TEST_F(FrameAllocations, RenderWithSuppliedNormalsAllocatesNothing) {
  auto e = makeEffect();
  ASSERT_TRUE(e);
  for (auto [format, encoding] : {std::pair{GLenum(GL_RG16F), NormalsEncoding::CameraOctahedral},
                                  std::pair{GLenum(GL_RGBA16F), NormalsEncoding::CameraXyz}}) {
    normals = makeTexture(format, depth.extent);
    const float facing[4] = {0, 0, 1, 0};  // +z either way: octahedral (0, 0) in RG, xyz (0, 0, 1)
    glClearTexImage(normals, 0, format == GL_RG16F ? GL_RG : GL_RGBA, GL_FLOAT, facing);
    cam.normalsEncoding = encoding;
    EXPECT_EQ(steadyFrames(*e, Settings{}, 0, false), 0) << "internal format " << format;
    deleteTexture(normals);
    normals = 0;
  }
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
