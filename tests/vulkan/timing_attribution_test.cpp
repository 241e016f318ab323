// Per-pass timings of the Vulkan backend land on the pass that did the work (issue 19), by every
// way the backend times: record() with Config::timestamps then timings(), measure() with
// MeasureMethod::Auto (timestamps where the queue family has them) and measure() with
// MeasureMethod::FenceClock (one fenced submission per pass). lavapipe has timestamps, and they
// bracket each pass's work (the added time lands in the right pass, as with the fence). Why these
// checks cannot flake: tests/common/timing_attribution.h.
#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "analytic_scenes.h"
#include "timing_attribution.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

enum class Way { RecordAndTimings, MeasureAuto, MeasureFence };

const char* name(Way w) {
  switch (w) {
    case Way::RecordAndTimings: return "RecordAndTimings";
    case Way::MeasureAuto: return "MeasureAuto";
    case Way::MeasureFence: return "MeasureFence";
  }
  return "?";
}
void PrintTo(Way w, std::ostream* os) { *os << name(w); }

Settings with(int samples, int blurRadius, int blurStride) {
  Settings s;
  s.samples = samples;
  s.blur_radius = blurRadius;
  s.blur_stride = blurStride;
  return s;
}

class TimingAttribution : public VkTest, public ::testing::WithParamInterface<Way> {
 protected:
  // 640x360: large enough that the heavy pass's work dwarfs a submission and the per-dispatch cost.
  void SetUp() override {
    VkTest::SetUp();
    cam = vulkanCamera(640, 360, 8);
    depth = test::renderDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
    const Status st = context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, image);
    ASSERT_TRUE(st.ok()) << st.message;
  }
  void TearDown() override {
    context().destroy(image);
    VkTest::TearDown();
  }

  std::unique_ptr<vk::Effect> makeEffect() {
    vk::Config c;
    c.timestamps = GetParam() == Way::RecordAndTimings;
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_TRUE(st.ok()) << st.message;
    return e;
  }

  // One frame of `e` with settings `s` (the first one plans: measurePair's warm-up).
  Status frame(vk::Effect& e, const Settings& s, Timings& out) {
    vk::Inputs in;
    in.depth = {image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
    switch (GetParam()) {
      case Way::RecordAndTimings: {
        Status recorded;
        const Status st = context().submit([&](VkCommandBuffer cmd) { recorded = e.record(cmd, cam, s, in); });
        if (!st) return st;
        if (!recorded) return recorded;
        return e.timings(out);
      }
      case Way::MeasureAuto: return e.measure(context().queue(), cam, s, in, nullptr, out, vk::MeasureMethod::Auto);
      case Way::MeasureFence:
        return e.measure(context().queue(), cam, s, in, nullptr, out, vk::MeasureMethod::FenceClock);
    }
    return Status::error(StatusCode::InvalidInput, "unknown way");
  }

  void measure(const Settings& light, const Settings& heavy, int runs, test::PassTimes& a, test::PassTimes& b) {
    // One effect per configuration: each keeps its plan from frame to frame.
    std::unique_ptr<vk::Effect> effects[] = {makeEffect(), makeEffect()};
    const Settings* settings[] = {&light, &heavy};
    ASSERT_TRUE(effects[0] && effects[1]);
    if (GetParam() != Way::MeasureFence && !effects[0]->timestampsSupported())
      GTEST_SKIP() << "the queue family has no timestamps: " << context().description();
    test::measurePair(
        [&](int config, Timings& out) {
          const Status st = frame(*effects[config], *settings[config], out);
          EXPECT_TRUE(st.ok()) << st.message;
          return st.ok();
        },
        runs, a, b);
    // Every timed frame ran on its effect's one plan (no planning inside a measured frame).
    EXPECT_EQ(effects[0]->plans(), 1u);
    EXPECT_EQ(effects[1]->plans(), 1u);
    const TimingMethod expected =
        GetParam() == Way::MeasureFence ? TimingMethod::FinishAndClock : TimingMethod::GpuTimestamps;
    EXPECT_EQ(a.method, expected);
    EXPECT_EQ(b.method, expected);
    std::printf("device: %s, %s\n", context().description().c_str(), name(GetParam()));
    test::print("light", a);
    test::print("heavy", b);
  }

  Camera cam;
  DepthImage depth;
  vk::headless::Image image;
};

// 64 taps and no blur: ao_sample does nearly all the work (measured 38x to 110x the next slowest
// pass, by every way), and the tap count changes nothing else.
TEST_P(TimingAttribution, TapsGoToAoSample) {
  test::PassTimes light, heavy;
  measure(with(1, 0, 1), with(64, 0, 1), 5, light, heavy);
  if (IsSkipped() || HasFatalFailure()) return;
  test::expectDominates(heavy, "ao_sample", 5.0);
  test::expectIncreaseIn(light, heavy, {"ao_sample"}, 0.75, 0.75);
}

// One tap; a wide blur (8 taps each side, 4 px apart) against none (then the plan has no blur pass
// and upsample reads ao_raw): the time added goes to the blur pass. The blur adds only about twice
// ao_sample's time here, so this takes the fastest of 15 runs (tens of ms each) rather than 5.
TEST_P(TimingAttribution, BlurTapsGoToTheBlurs) {
  test::PassTimes light, heavy;
  measure(with(1, 0, 1), with(1, 8, 4), 15, light, heavy);
  if (IsSkipped() || HasFatalFailure()) return;
  test::expectIncreaseIn(light, heavy, {"blur"}, 0.5, 0.5);
}

INSTANTIATE_TEST_SUITE_P(Ways, TimingAttribution,
                         ::testing::Values(Way::RecordAndTimings, Way::MeasureAuto, Way::MeasureFence),
                         [](const ::testing::TestParamInfo<Way>& info) { return std::string(name(info.param)); });

}  // namespace
}  // namespace sao::vktest
