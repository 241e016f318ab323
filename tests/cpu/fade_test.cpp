// The distance fade (settings fade_start / fade_end, sao_fade in ao_sample) on the CPU reference:
// A is untouched up to fade_start, exactly 1 from fade_end on, and fades linearly in between, and
// a fade that is off (fade_end = 0) changes no bit. The 2x2 reconstruction and the blur are turned
// off (quad_edge_threshold 0, blur_radius 0) so that each pixel's A is its own ao_sample value
// (written into the output by ao_sample_output: in Double unrounded, in Float rounded to binary16).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "sao/constants.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::Precision;

Settings unmixed() {
  Settings s;
  s.quad_edge_threshold = 0.0f;  // |dz| < 0 never holds: no quad averaging
  s.blur_radius = 0;             // the blur passes copy
  s.resolution_divisor = 1;      // no upsample mixing neighbours either
  return s;
}

struct Scenario {
  Camera camera = testCamera();
  DepthImage depth;
  Scenario() { depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D32F); }
  cpu::Result run(const Settings& s, Precision p = Precision::Float) const {
    cpu::Inputs in;
    in.depth = &depth;
    return runOrFail(s, camera, in, p);
  }
};

TEST(Fade, OffByDefaultAndFadeStartIgnoredWhileOff) {
  const Scenario sc;
  const cpu::Result base = sc.run(Settings{});
  EXPECT_EQ(base.params.fade_end, 0.0f);
  EXPECT_EQ(base.params.fade_inv_range, 0.0f);
  Settings s;
  s.fade_start = 2.0f;  // no effect while fade_end = 0
  const cpu::Result r = sc.run(s);
  EXPECT_TRUE(sameBits(r.aoRaw, base.aoRaw));
  EXPECT_TRUE(sameBits(r.ao, base.ao));
}

// The floor of sphereOnPlaneScene recedes from the near plane to the wall at 8 m, so every part of
// the fade holds many pixels.
TEST(Fade, UntouchedBeforeStartOneBeyondEndLinearBetween) {
  const Scenario sc;
  Settings s = unmixed();
  const cpu::Result base = sc.run(s);
  s.fade_start = 3.0f;
  s.fade_end = 6.0f;
  for (Precision p : {Precision::Float, Precision::Double}) {
    SCOPED_TRACE(cpu::toString(p));
    const cpu::Result noFade = p == Precision::Float ? base : sc.run(unmixed(), p);
    const cpu::Result r = sc.run(s, p);
    EXPECT_EQ(r.params.fade_start, 3.0f);
    EXPECT_EQ(r.params.fade_end, 6.0f);
    EXPECT_EQ(r.params.fade_inv_range, float(1.0 / 3.0));
    std::size_t before = 0, beyond = 0, between = 0, occludedBetween = 0;
    std::vector<std::pair<double, double>> ramp;  // (distance, estimated t) of occluded pixels between
    // Each pixel's z from csz level 0, its A from the output (r16f: rounded to binary16 in Float, so
    // a and a0 are each within half a step, 2^-12 below 1, of the values the fade computed).
    ASSERT_FALSE(r.csz.empty());
    const FloatImage& ao = r.ao;
    const double rounding = p == Precision::Float ? 2.0 * 0x1p-12 : 0.0;
    for (std::uint32_t y = 0; y < ao.extent.height; ++y)
      for (std::uint32_t x = 0; x < ao.extent.width; ++x) {
        const float z = r.csz[0].at(x + std::uint32_t(r.params.guard.x), y + std::uint32_t(r.params.guard.y));
        if (!(z < 0.0f)) continue;  // sky
        const float d = -z;
        const float a = ao.at(x, y, 0), a0 = noFade.ao.at(x, y, 0);
        if (d <= 3.0f) {
          ++before;
          EXPECT_EQ(a, a0) << x << "," << y << " before fade_start";
        } else if (d >= 6.0f) {
          ++beyond;
          EXPECT_EQ(a, 1.0f) << x << "," << y << " beyond fade_end";
        } else {
          ++between;
          EXPECT_GE(a, a0) << x << "," << y << ": the fade only brightens";
          EXPECT_LE(a, 1.0f);
          if (1.0f - a0 > 0.05f) {
            ++occludedBetween;
            const double t = (double(a) - a0) / (1.0 - a0);
            EXPECT_NEAR(t, (double(d) - 3.0) / 3.0, 1e-4 + rounding / (1.0 - a0))
                << x << "," << y << " at " << d << " m: linear in distance";
            ramp.emplace_back(d, t);
          }
        }
      }
    std::printf("FADE %-6s pixels: %zu up to 3 m (unchanged), %zu from 6 m (A = 1), %zu between (%zu occluded, "
                "linear to 1e-4)\n",
                cpu::toString(p), before, beyond, between, occludedBetween);
    EXPECT_GT(before, 1000u);
    EXPECT_GT(beyond, 1000u);
    EXPECT_GT(between, 1000u);
    EXPECT_GT(occludedBetween, 20u) << "occluded pixels inside the fade to measure it on";
    // Monotone: ordered by distance, the fraction faded never decreases (beyond float rounding, and
    // in Float the output's: each t within rounding / (1 - a0) <= rounding / 0.05 of the fade's).
    std::sort(ramp.begin(), ramp.end());
    for (std::size_t i = 1; i < ramp.size(); ++i)
      EXPECT_GE(ramp[i].second, ramp[i - 1].second - 1e-4 - 2.0 * rounding / 0.05) << "at " << ramp[i].first << " m";
  }
}

// fade lengths are metres, converted with metersToViewUnits like the radius: the same scene in
// centimetres with the fade in metres gives the same block in view units.
TEST(Fade, MetresBecomeViewUnits) {
  Camera cm = testCamera();
  cm.metersToViewUnits = 100.0;
  Settings s;
  s.fade_start = 3.0f;
  s.fade_end = 6.0f;
  ParamBlock p;
  ASSERT_TRUE(computeConstants(s, cm, DepthEncoding::Hardware, p).ok());
  EXPECT_EQ(p.fade_start, 300.0f);
  EXPECT_EQ(p.fade_end, 600.0f);
  EXPECT_EQ(p.fade_inv_range, float(1.0 / 300.0));
}

TEST(Fade, BadRangeRefusedByTheReference) {
  const Scenario sc;
  Settings s;
  s.fade_start = 6.0f;
  s.fade_end = 6.0f;
  cpu::Inputs in;
  in.depth = &sc.depth;
  cpu::Result r;
  const Status st = cpu::run(s, sc.camera, in, cpu::Options{Precision::Float, 1}, r);
  EXPECT_EQ(st.code, StatusCode::InvalidSetting);
  EXPECT_NE(st.message.find("'fade_start'"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("'fade_end'"), std::string::npos) << st.message;
}

}  // namespace
}  // namespace sao::test
