// Inputs::frameIndex on OpenGL (sao::frameSpiral): frames 0, 7 and 1000 against the CPU reference
// (Float) to the reference tests' bounds, and frame 7 differs from frame 0, with no re-plan.
#include <epoxy/gl.h>

#include <cstdio>
#include <string>

#include "gl_support.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"

namespace sao::gltest {
namespace {

class FrameIndex : public GlTest {};

TEST_F(FrameIndex, EveryFrameMatchesTheCpuReference) {
  const Camera cam = camera(160, 90, 8);
  const DepthImage depth = test::renderDepth(sceneByName("sphere"), cam, DepthFormat::D32F);
  const GLuint depthTex = uploadDepth(depth, GlDepth::D32F);
  auto effect = makeEffect();
  ASSERT_TRUE(effect);
  const Settings settings = presetSettings(Preset::Medium);
  FloatImage frame0;
  gl::Stats afterFirst;
  for (std::uint32_t frame : {0u, 7u, 1000u}) {
    const std::string name = "gl_frame" + std::to_string(frame);
    gl::Inputs gi;
    gi.depth = {depthTex, gl::kDepthComponent32F};
    gi.frameIndex = frame;
    ASSERT_TRUE(effect->render(cam, settings, gi).ok());
    const FloatImage actual = readTexture(effect->aoTexture(), 1);
    cpu::Inputs ci;
    ci.depth = &depth;
    ci.frameIndex = frame;
    cpu::Result ref;
    ASSERT_TRUE(cpu::run(settings, cam, ci, cpu::Options{cpu::Precision::Float, 2}, ref).ok());
    const Agreement a = compare(actual, ref.ao, 0, 2.0 / 255.0, 4.0 / 255.0, name);
    EXPECT_TRUE(acceptable(a)) << name << ": max " << a.maxAbs * 255 << "/255, p99.9 " << a.p999 * 255 << "/255";
    std::printf("FRAME %-14s vs CPU: max %.3f/255, p99.9 %.3f/255\n", name.c_str(), a.maxAbs * 255, a.p999 * 255);
    if (frame == 0) {
      frame0 = actual;
      afterFirst = effect->stats();
    } else {
      std::size_t changed = 0;
      for (std::size_t i = 0; i < actual.data.size(); ++i) changed += actual.data[i] != frame0.data[i];
      EXPECT_GT(changed, actual.data.size() / 10) << name << " looks like frame 0";
    }
  }
  EXPECT_EQ(effect->stats().textureAllocations, afterFirst.textureAllocations) << "a new frame is not a new plan";
  EXPECT_EQ(effect->stats().programsCompiled, afterFirst.programsCompiled) << "a new frame is not a new plan";
  deleteTexture(depthTex);
}

}  // namespace
}  // namespace sao::gltest
