// Temporal accumulation on OpenGL (the `temporal` setting): a camera strafing past a sphere on a
// plane, six frames rendered by one effect against the CPU reference (Float, the history carried
// from run to run) to the reference tests' bounds; the per-frame camera plans nothing and
// allocates no texture; Inputs::resetHistory gives the frame without history bit for bit.
#include <epoxy/gl.h>

#include <cstdio>
#include <string>

#include "cpu_frames.h"
#include "gl_support.h"
#include "moving_camera.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

class Temporal : public GlTest {};

Settings temporalMedium() {
  Settings s = presetSettings(Preset::Medium);
  s.temporal = true;
  return s;
}

TEST_F(Temporal, EveryFrameOfAStrafeMatchesTheCpuReference) {
  const Camera base = camera(160, 90, 8);
  const test::Scene world = test::sphereOnPlaneScene();
  const Settings settings = temporalMedium();
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  test::CpuFrames reference(settings);
  gl::Stats afterFirst;
  for (std::uint32_t frame = 0; frame < 6; ++frame) {
    const std::string name = "gl_temporal" + std::to_string(frame);
    const test::Vec3 eye{0.03 * frame, 0.0, 0.0};
    const Camera cam = test::movedCamera(base, eye);
    const DepthImage depth = test::renderDepth(test::seenFrom(world, eye), cam, DepthFormat::D32F);
    const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
    gl::Inputs gi;
    gi.depth = {depthTex, gl::kDepthComponent32F};
    gi.frameIndex = frame;
    const Status st = effect->render(cam, settings, gi);
    ASSERT_TRUE(st.ok()) << st.message;
    const FloatImage actual = readTexture(effect->aoTexture(), 1);
    deleteTexture(depthTex);
    EXPECT_EQ(effect->params().history_valid, frame > 0 ? 1 : 0);
    cpu::Inputs ci;
    ci.depth = &depth;
    ci.frameIndex = frame;
    const cpu::Result ref = reference.run(cam, ci);
    const Agreement a = compare(actual, ref.ao, 0, 2.0 / 255.0, 4.0 / 255.0, name);
    EXPECT_TRUE(acceptable(a)) << name << ": max " << a.maxAbs * 255 << "/255, p99.9 " << a.p999 * 255 << "/255";
    // The history this frame wrote: its frame counts and packed normals as the CPU's, texel for texel.
    const FloatImage history = readTexture(effect->texture(gen::ResourceId::history), 4);
    const FloatImage& cpuHistory = reference.history();
    ASSERT_EQ(history.data.size(), cpuHistory.data.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < history.data.size(); i += 4)
      differ += history.data[i + 2] != cpuHistory.data[i + 2] || history.data[i + 3] != cpuHistory.data[i + 3];
    EXPECT_LE(differ, history.data.size() / 4 / 1000) << name << ": history frames or normals differ";
    std::printf("TEMPORAL %-14s vs CPU: max %.3f/255, p99.9 %.3f/255; history texels with other frames or normals: "
                "%zu of %zu\n", name.c_str(), a.maxAbs * 255, a.p999 * 255, differ, history.data.size() / 4);
    if (frame == 0) afterFirst = effect->stats();
  }
  EXPECT_EQ(effect->stats().textureAllocations, afterFirst.textureAllocations) << "a moving camera allocated";
  EXPECT_EQ(effect->stats().plans, afterFirst.plans) << "a moving camera planned again";
  EXPECT_EQ(effect->stats().programsCompiled, afterFirst.programsCompiled);
}

TEST_F(Temporal, ResetHistoryGivesTheFrameWithoutHistory) {
  const Camera cam = test::movedCamera(camera(96, 64, 4), {});
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  const Settings settings = temporalMedium();
  auto render = [&](gl::Effect& e, std::uint32_t frame, bool reset) {
    gl::Inputs gi;
    gi.depth = {depthTex, gl::kDepthComponent32F};
    gi.frameIndex = frame;
    gi.resetHistory = reset;
    const Status st = e.render(cam, settings, gi);
    EXPECT_TRUE(st.ok()) << st.message;
    return readTexture(e.aoTexture(), 1);
  };
  auto accumulating = makeEffect();
  auto fresh = makeEffect();
  ASSERT_TRUE(accumulating && fresh);
  render(*accumulating, 0, false);
  const FloatImage second = render(*accumulating, 1, false);
  const FloatImage reset = render(*accumulating, 2, true);
  EXPECT_EQ(accumulating->params().history_valid, 0);
  const FloatImage alone = render(*fresh, 2, false);
  std::size_t differ = 0, moved = 0;
  for (std::size_t i = 0; i < alone.data.size(); ++i) {
    differ += reset.data[i] != alone.data[i];
    moved += second.data[i] != alone.data[i];
  }
  EXPECT_EQ(differ, 0u) << "a reset frame must not read the history";
  EXPECT_GT(moved, alone.data.size() / 20) << "frame 1 with history looks like frame 2 without";
  // A settings change starts again too.
  Settings other = settings;
  other.radius = 0.9f;
  gl::Inputs gi;
  gi.depth = {depthTex, gl::kDepthComponent32F};
  ASSERT_TRUE(accumulating->render(cam, other, gi).ok());
  EXPECT_EQ(accumulating->params().history_valid, 0);
  ASSERT_TRUE(accumulating->render(cam, other, gi).ok());
  EXPECT_EQ(accumulating->params().history_valid, 1);
  deleteTexture(depthTex);
}

// Motion vectors (MOTION_VECTORS) with supplied normals (the normal test): a still camera and a
// motion field of (1.5, -0.75) pixels everywhere (as if the whole picture moved), uploaded as
// GL_RGBA16F; four frames against the CPU reference given the same field and normals.
TEST_F(Temporal, MotionVectorsMatchTheCpuReference) {
  const Camera cam = test::movedCamera(camera(96, 64, 4), {});
  const DepthImage depth = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  FloatImage motion(depth.extent, 4);
  for (std::size_t i = 0; i < motion.data.size(); i += 4) {
    motion.data[i] = 1.5f;
    motion.data[i + 1] = -0.75f;
  }
  const GLuint motionTex = uploadNormals(motion);
  const FloatImage normals = test::renderNormals(test::sphereOnPlaneScene(), cam);
  const GLuint normalsTex = uploadNormals(normals);
  const Settings settings = temporalMedium();
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  test::CpuFrames reference(settings);
  for (std::uint32_t frame = 0; frame < 4; ++frame) {
    const std::string name = "gl_temporal_motion" + std::to_string(frame);
    gl::Inputs gi;
    gi.depth = {depthTex, gl::kDepthComponent32F};
    gi.motion = motionTex;
    gi.normals = normalsTex;
    gi.frameIndex = frame;
    const Status st = effect->render(cam, settings, gi);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(effect->plan().variants[std::size_t(gen::VariantId::MOTION_VECTORS)], 1);
    EXPECT_EQ(effect->plan().variants[std::size_t(gen::VariantId::NORMALS_SUPPLIED)], 1);
    const FloatImage actual = readTexture(effect->aoTexture(), 1);
    cpu::Inputs ci;
    ci.depth = &depth;
    ci.motion = &motion;
    ci.normals = &normals;
    ci.frameIndex = frame;
    const cpu::Result ref = reference.run(cam, ci);
    const Agreement a = compare(actual, ref.ao, 0, 2.0 / 255.0, 4.0 / 255.0, name);
    EXPECT_TRUE(acceptable(a)) << name << ": max " << a.maxAbs * 255 << "/255, p99.9 " << a.p999 * 255 << "/255";
    std::printf("TEMPORAL %-20s vs CPU: max %.3f/255, p99.9 %.3f/255\n", name.c_str(), a.maxAbs * 255, a.p999 * 255);
  }
  // A motion input without the temporal setting: refused by name, as on every backend.
  gl::Inputs gi;
  gi.depth = {depthTex, gl::kDepthComponent32F};
  gi.motion = motionTex;
  const Status refused = effect->render(cam, presetSettings(Preset::Medium), gi);
  EXPECT_EQ(refused.code, StatusCode::InvalidInput);
  EXPECT_NE(refused.message.find("motion vectors serve temporal accumulation only"), std::string::npos)
      << refused.message;
  deleteTexture(normalsTex);
  deleteTexture(motionTex);
  deleteTexture(depthTex);
}

}  // namespace
}  // namespace sao::gltest
