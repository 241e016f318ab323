// Every setting at both ends of its range keeps A finite and in [0, 1]; values outside the ranges
// are rejected, not clamped.
#include <algorithm>
#include <string>
#include <vector>

#include "extremes_support.h"
#include "refused_settings.h"

namespace sao::stability {
namespace {

double settingMin(SettingId id) { return gen::kSettings[std::size_t(id)].minValue; }
double settingMax(SettingId id) { return gen::kSettings[std::size_t(id)].maxValue; }

TEST(Settings, BothEndsOfEveryRangeStayInZeroOne) {
  const test::Scene scene = test::sphereOnPlaneScene();
  const Camera persp = camera(64, 48, 0.1, 1e4, ClipDepth::NegativeOneToOne, false, 8);
  const Camera ortho = orthoCamera(64, 48, 0.1, 100.0, ClipDepth::ZeroToOne, true, 8, 3.0);
  double lo = 1, hi = 0;
  std::size_t runs = 0;
  auto check = [&](const std::string& label, const Settings& s, const Camera& cam, DepthFormat fm) {
    const bool isOrtho = cam.kind == ProjectionKind::Orthographic;
    const SceneRun r = runScene(label, s, cam, isOrtho ? test::creaseScene(5.0) : scene, fm);
    for (const BackendRun& b : r.runs.runs) {
      ++runs;
      const Range a = range(b.out.ao);
      lo = std::min(lo, a.min);
      hi = std::max(hi, a.max);
      if (s.intensity == 0.0f) {
        EXPECT_EQ(a.min, 1.0) << label << " on " << b.name << ": intensity 0 gives A = 1";
      }
    }
  };
  // The grid: samples, blur radius, intensity and contrast at both ends, all 16 combinations.
  for (double sm : {settingMin(SettingId::samples), settingMax(SettingId::samples)})
    for (double br : {settingMin(SettingId::blur_radius), settingMax(SettingId::blur_radius)})
      for (double in : {settingMin(SettingId::intensity), settingMax(SettingId::intensity)})
        for (double ct : {settingMin(SettingId::contrast), settingMax(SettingId::contrast)})
          for (bool o : {false, true}) {
            Settings s = fullResolution();
            gen::setSettingValue(s, SettingId::samples, sm);
            gen::setSettingValue(s, SettingId::blur_radius, br);
            gen::setSettingValue(s, SettingId::intensity, in);
            gen::setSettingValue(s, SettingId::contrast, ct);
            ASSERT_TRUE(validate(s).ok());
            check(fmt("s=%g R=%g sigma=%g k=%g %s", sm, br, in, ct, o ? "ortho" : "persp"), s, o ? ortho : persp,
                  o ? DepthFormat::D32F : DepthFormat::D24);
          }
  // Every setting alone at its min and max (the rest at defaults), and all at their max at once.
  Settings allMax, allMin;
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
    const auto id = SettingId(i);
    gen::setSettingValue(allMax, id, settingMax(id));
    gen::setSettingValue(allMin, id, settingMin(id));
    for (double v : {settingMin(id), settingMax(id)}) {
      Settings s = fullResolution();
      gen::setSettingValue(s, id, v);
      ASSERT_TRUE(validate(s).ok()) << gen::kSettings[i].name << " = " << v;
      if (test::refused(s)) continue;  // bent_normals alone (estimator 0, r16f): tests/vulkan/bent_normal_test.cpp
      check(fmt("%s = %g", std::string(gen::kSettings[i].name).c_str(), v), s, persp, DepthFormat::D24);
    }
  }
  // fade_start = fade_end (both at their max) breaks the rule between them: start just below the end.
  // bent_normals at its max is refused with a blur and the r16f output: back at its default.
  allMax = test::withoutRefusedSettings(clamped(allMax));
  ASSERT_TRUE(validate(allMax).ok()) << validate(allMax).message;
  check("every setting at its max", allMax, persp, DepthFormat::D24);
  check("every setting at its min", allMin, persp, DepthFormat::D24);
  report("settings at both ends (samples 1/64 x blur 0/8 x intensity 0/10 x contrast 0.1/8, persp+ortho; each setting alone; all min; all max)",
         "A finite and in [0,1]; intensity 0 gives A = 1", fmt("%zu runs: A in [%.4f, %.4f]", runs, lo, hi));
}

TEST(Settings, OutOfRangeIsRejectedNotClamped) {
  // Validation rejects (no silent clamping): just outside each range, NaN and infinities.
  const Camera cam = camera(16, 16, 0.1, kInf, ClipDepth::ZeroToOne, true);
  DepthImage depth;
  depth.extent = {16, 16};
  depth.format = DepthFormat::D32F;
  depth.texels.assign(256, storeDepth(DepthFormat::D32F, 0.5f));
  std::size_t cases = 0;
  std::string example;
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
    const auto& info = gen::kSettings[i];
    if (info.type == gen::SettingType::Bool) continue;
    const double step = info.type == gen::SettingType::Int ? 1.0 : std::max(1e-3 * (info.maxValue - info.minValue), 1e-7);
    std::vector<double> bad = {info.minValue - step, info.maxValue + step};
    if (info.type == gen::SettingType::Float) bad.insert(bad.end(), {double(NAN), kInf, -kInf});
    for (double v : bad) {
      Settings s = fullResolution();
      gen::setSettingValue(s, SettingId(i), v);
      const std::string msg = expectRejected(fmt("%s = %g", std::string(info.name).c_str(), v), s, cam,
                                             {&depth, nullptr, nullptr}, StatusCode::InvalidSetting);
      EXPECT_NE(msg.find(info.name), std::string::npos) << msg;
      if (example.empty()) example = msg;
      ++cases;
    }
  }
  report("settings outside their ranges, NaN, +-Inf", "rejected with InvalidSetting naming the setting",
         fmt("%zu values rejected on every backend, e.g. '%s'", cases, example.c_str()));
}

}  // namespace
}  // namespace sao::stability
