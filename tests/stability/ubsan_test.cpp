// The CPU reference (backends/cpu/src/reference.cpp, compiled into this test again with
// -fsanitize=undefined,float-cast-overflow -fno-sanitize-recover=all) on the extreme cases: any
// signed overflow, out-of-range float -> int conversion (the tap offsets int(h·u), findMSB(int(h))),
// bad shift or out-of-bounds index aborts the test. Both precisions. This is how "no integer
// overflow" is checked rather than argued.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "analytic_scenes.h"
#include "refused_settings.h"
#include "sao/cpu/reference.h"

namespace sao {
namespace {

constexpr double kInf = INFINITY;

Camera cam(std::uint32_t w, std::uint32_t h, double n, double f, ClipDepth clip, bool rev, std::uint32_t g) {
  Camera c = perspectiveCamera(3.14159265358979323846 / 3.0, w, h, n, f, clip, rev);
  c.guardBand = g;
  c.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // every setting runs (temporal)
  return c;
}

test::Scene scaled(test::Scene s, double k) {
  for (auto& p : s.planes) {
    p.point = {p.point.x * k, p.point.y * k, p.point.z * k};
    for (auto& hs : p.keep) hs.point = {hs.point.x * k, hs.point.y * k, hs.point.z * k};
  }
  for (auto& sp : s.spheres) sp.centre = {sp.centre.x * k, sp.centre.y * k, sp.centre.z * k}, sp.radius *= k;
  return s;
}

std::size_t runs = 0;

void runBoth(const std::string& label, const Settings& s, const Camera& c, const DepthImage& d) {
  for (cpu::Precision p : {cpu::Precision::Float, cpu::Precision::Double}) {
    cpu::Result r;
    const Status st = cpu::run(s, c, {&d}, {p, 2}, r);
    ASSERT_TRUE(st.ok()) << label << ": " << st.message;
    for (float a : r.ao.data) ASSERT_TRUE(std::isfinite(a) && a >= 0.0f && a <= 1.0f) << label << " A = " << a;
    ++runs;
  }
}

TEST(UBSan, HugeRadiusAtTheNearPlane) {
  for (double n : {1e-2, 1e-4})
    for (bool hierarchy : {true, false})
      for (const auto& [w, h, g] : {std::tuple{64u, 48u, 8u}, std::tuple{321u, 239u, 0u}}) {
        const Camera c = cam(w, h, n, kInf, ClipDepth::ZeroToOne, true, g);
        Settings s;
        s.radius = 100.0f;
        s.use_z_hierarchy = hierarchy;
        s.samples = 64;
        s.mip_switch_log2 = 0;
        runBoth("huge radius", s, c, test::renderDepth(scaled(test::sphereOnPlaneScene(), n), c, DepthFormat::D32F));
      }
  // Orthographic: r' = 100 m · S' beyond the clamp.
  Camera o = orthographicCamera(0.02, 64, 48, 0.01, 10.0, ClipDepth::ZeroToOne, true);
  o.guardBand = 8;
  Settings s;
  s.radius = 100.0f;
  runBoth("ortho huge radius", s, o, test::renderDepth(test::creaseScene(0.05), o, DepthFormat::D32F));
}

TEST(UBSan, ExtremeDepthValuesAndSettings) {
  const Camera c = cam(40, 30, 0.1, kInf, ClipDepth::ZeroToOne, true, 2);
  DepthImage base = test::renderDepth(test::sphereOnPlaneScene(), c, DepthFormat::D32F);
  const float vals[] = {NAN, INFINITY, -INFINITY, -0.0f, -1e30f, std::numeric_limits<float>::max(),
                        -std::numeric_limits<float>::max(), 1.5f, 0x1p-149f, 1e-40f, 0x1p-126f, 1.0f - 0x1p-24f, 1.0f, 0.0f};
  for (float v : vals) {
    DepthImage d = base;
    for (std::size_t i = 0; i < d.texels.size(); i += 3) d.texels[i] = std::bit_cast<std::uint32_t>(v);
    for (const Settings& s : [] {
           Settings lo, hi;
           for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
             gen::setSettingValue(lo, gen::SettingId(i), gen::kSettings[i].minValue);
             gen::setSettingValue(hi, gen::SettingId(i), gen::kSettings[i].maxValue);
           }
           // clamped(): fade_start = fade_end (both at their max) breaks their rule; start just below.
           // bent_normals at its max is refused with the r16f output: back at its default.
           return std::vector<Settings>{Settings{}, lo, test::withoutRefusedSettings(clamped(hi))};
         }())
      runBoth("extreme depth " + std::to_string(v), s, c, d);
  }
}

TEST(UBSan, TinySizesAndExtremeUnits) {
  for (std::uint32_t w : {1u, 2u, 3u})
    for (std::uint32_t g : {0u, 5u}) {
      const Camera c = cam(w, w, 0.1, 1e4, ClipDepth::NegativeOneToOne, false, g);
      runBoth("tiny", Settings{}, c, test::renderDepth(test::sphereOnPlaneScene(), c, DepthFormat::D24));
    }
  // The ends of the supported unit range run; beyond it the camera is rejected with a clear error.
  for (double u : {1e-6, 1e6}) {
    Camera c = cam(64, 48, 0.1 * u, kInf, ClipDepth::ZeroToOne, true, 8);
    c.metersToViewUnits = u;
    runBoth("units", Settings{}, c, test::renderDepth(scaled(test::sphereOnPlaneScene(), u), c, DepthFormat::D32F));
  }
  for (double u : {1e-20, 1e-12, 1e12, 1e20}) {
    Camera c = cam(64, 48, 0.1 * u, kInf, ClipDepth::ZeroToOne, true, 8);
    c.metersToViewUnits = u;
    cpu::Result r;
    const DepthImage d = test::renderDepth(scaled(test::sphereOnPlaneScene(), u), c, DepthFormat::D32F);
    const Status st = cpu::run(Settings{}, c, {&d}, {cpu::Precision::Float, 2}, r);
    EXPECT_EQ(st.code, StatusCode::InvalidCamera) << "u = " << u;
    EXPECT_NE(st.message.find("outside the supported range"), std::string::npos) << st.message;
  }
  std::printf("[stability] UBSan: %zu runs of the sanitized CPU reference\n", runs);
  ::testing::Test::RecordProperty("stability_ubsan_runs", std::to_string(runs));
}

}  // namespace
}  // namespace sao
