// World scale: metersToViewUnits and a physically scaled scene leave A unchanged; the units sweep
// finds the supported range and everything outside it is rejected.
#include <algorithm>
#include <cmath>
#include <string>

#include "extremes_support.h"

namespace sao::stability {
namespace {

// The sphere-on-plane scene at metersToViewUnits = u: geometry, near and far in view units.
struct ScaleSetup {
  const char* name;
  DepthFormat fm;
  ClipDepth clip;
  bool reversed;
  double far;  // metres
  bool ortho;
};
const ScaleSetup kScaleSetups[] = {
    {"D24 standard [-1,1] far 1e4", DepthFormat::D24, ClipDepth::NegativeOneToOne, false, 1e4, false},
    {"D32F reversed [0,1] infinite", DepthFormat::D32F, ClipDepth::ZeroToOne, true, kInf, false},
    {"R32F linear z", DepthFormat::LinearZ, ClipDepth::ZeroToOne, true, kInf, false},
    {"orthographic D24 standard [0,1]", DepthFormat::D24, ClipDepth::ZeroToOne, false, 100.0, true},
};

Camera scaleCamera(const ScaleSetup& su, double u) {
  Camera c = su.ortho ? orthoCamera(64, 48, 0.1 * u, su.far * u, su.clip, su.reversed, 8, 3.0 * u)
                      : camera(64, 48, 0.1 * u, su.far * u, su.clip, su.reversed, 8);
  c.metersToViewUnits = u;
  return c;
}

// Finding F2 (docs/STABILITY.md, fixed): eq. 1's term max(0, v·n + z_C·β) / (v·v + ε) has the
// unit 1/length, so A is unit-free only if the block multiplies it by a length in view units:
// intensity_div_s = 2·σ·r/s with r = radius·u. True when intensity_div_s scales with the units.
bool intensityScalesWithUnits() {
  Camera c1 = camera(16, 16, 0.1, kInf, ClipDepth::ZeroToOne, true), c2 = c1;
  c2.metersToViewUnits = 1000.0;
  ParamBlock p1, p2;
  EXPECT_TRUE(computeConstants(fullResolution(), c1, DepthEncoding::Hardware, p1).ok());
  EXPECT_TRUE(computeConstants(fullResolution(), c2, DepthEncoding::Hardware, p2).ok());
  return std::fabs(double(p2.intensity_div_s) / p1.intensity_div_s - 1000.0) < 1e-3;
}

TEST(WorldScale, MilliAndKiloUnitsLeaveAUnchanged) {
  // The same scene in metres (u = 1), in km (u = 1e-3: 1 m = 0.001 view units) and in mm
  // (u = 1e3): geometry, near and far in view units, the settings (defaults) in metres as always.
  // The block converts the radius, ε (m²), the quad threshold, the blur sharpness and σ, so A must
  // not change. The same settings at both scales: no compensation in the test, so that an F2
  // regression fails here.
  EXPECT_TRUE(intensityScalesWithUnits()) << "intensity_div_s does not scale with metersToViewUnits (finding F2)";
  std::string measured;
  for (const ScaleSetup& su : kScaleSetups) {
    // Orthographic views along -z see the floor edge-on: they look at the 90° crease instead.
    const test::Scene scene = su.ortho ? test::creaseScene(5.0) : test::sphereOnPlaneScene();
    const SceneRun r1 = runScene(fmt("world scale 1, %s", su.name), fullResolution(), scaleCamera(su, 1.0), scene, su.fm);
    for (double u : {1e-3, 1e3}) {
      const SceneRun ru = runScene(fmt("world scale %g, %s", u, su.name), fullResolution(), scaleCamera(su, u),
                                   scaledScene(scene, u), su.fm);
      double worst = 0;
      std::size_t compared = 0;
      for (const BackendRun& b : ru.runs.runs)
        if (const BackendRun* b1 = r1.runs.find(b.name)) {
          const double d = maxAbsDiff(b.out.ao, b1->out.ao);
          EXPECT_LE(d, k255) << su.name << " u = " << u << " on " << b.name;
          worst = std::max(worst, d);
          ++compared;
        }
      EXPECT_GT(compared, 0u) << su.name << " u = " << u << ": no backend ran both scales";
      measured += fmt("%s%s u=%g: %.2g", measured.empty() ? "" : "; ", su.name, u, worst);
    }
  }
  report("world scale x1e-3 / x1e3 (metersToViewUnits; D24 std, D32F rev, R32F, ortho D24; default settings)",
         "max |A(u) - A(1)| <= 1/255 on every backend", measured);
}

TEST(WorldScale, HalfIntermediatesKeepTheirKeysInAnyUnit) {
  // half_intermediates stores the (A, key) images' key as binary16 of z in metres (key_scale =
  // 1/metersToViewUnits, docs/effect-math.md 6.5), so binary16's range (65504) holds a crease 70 m
  // away in millimetres (z = -70000 view units), and the same scene in other units rounds its keys
  // alike: A within 1/255 of the metres run, as with rg32f, and within 2/255 of rg32f's A.
  Settings half;  // the defaults: half resolution, blur 1, rg16f intermediates
  half.half_intermediates = true;
  Settings full = half;
  full.half_intermediates = false;
  for (double u : {1.0, 1e3, 1e-3, 39.37}) {
    Camera c = camera(16, 16, 0.1 * u, kInf, ClipDepth::ZeroToOne, true);
    c.metersToViewUnits = u;
    ParamBlock p, plain;
    ASSERT_TRUE(computeConstants(half, c, DepthEncoding::Hardware, p).ok());
    ASSERT_TRUE(computeConstants(full, c, DepthEncoding::Hardware, plain).ok());
    EXPECT_EQ(p.key_scale, float(1.0 / u)) << "u = " << u;
    EXPECT_EQ(p.key_to_view, float(u)) << "u = " << u;
    EXPECT_EQ(p.blur_edge_sharpness, half.blur_edge_sharpness) << "sharpness per metre, u = " << u;
    EXPECT_EQ(plain.key_scale, 1.0f);
    EXPECT_EQ(plain.key_to_view, 1.0f);
    EXPECT_EQ(plain.blur_edge_sharpness, float(full.blur_edge_sharpness / u));
  }
  std::string measured;
  for (const test::Scene& scene : {test::sphereOnPlaneScene(), test::creaseScene(70.0)})
    for (const ScaleSetup& su : {kScaleSetups[1], kScaleSetups[2]}) {
      const SceneRun h1 = runScene("half keys u=1, " + scene.name + ", " + su.name, half, scaleCamera(su, 1.0), scene, su.fm);
      for (double u : {1.0, 1e-3, 1e3}) {
        const std::string what = scene.name + ", " + su.name + fmt(", u=%g", u);
        const Camera cu = scaleCamera(su, u);
        const test::Scene scaled = scaledScene(scene, u);
        const SceneRun h = u == 1.0 ? h1 : runScene("half keys, " + what, half, cu, scaled, su.fm);
        const SceneRun f = runScene("float keys, " + what, full, cu, scaled, su.fm);
        double worstFormat = 0, worstUnit = 0;
        std::size_t compared = 0;
        for (const BackendRun& b : h.runs.runs)
          if (const BackendRun* bf = f.runs.find(b.name)) {
            const double d = maxAbsDiff(b.out.ao, bf->out.ao);
            EXPECT_LE(d, 2 * k255) << what << " on " << b.name << ": rg16f vs rg32f";
            const double du = maxAbsDiff(b.out.ao, h1.runs.find(b.name)->out.ao);
            EXPECT_LE(du, k255) << what << " on " << b.name << ": rg16f in these units vs in metres";
            worstFormat = std::max(worstFormat, d);
            worstUnit = std::max(worstUnit, du);
            ++compared;
            const FloatImage* raw = b.intermediate("ao_raw");
            if (raw == nullptr) continue;
            float farthest = 0.0f;  // keys are <= 0, +0 = sky
            for (std::size_t k = 1; k < raw->data.size(); k += 2) {
              ASSERT_TRUE(std::isfinite(raw->data[k])) << what << " on " << b.name << ": key " << raw->data[k];
              farthest = std::min(farthest, raw->data[k]);
            }
            // The deepest key in metres: the crease's far corner lies beyond 70 m, the sphere
            // scene's floor within 10 m.
            EXPECT_GT(-farthest, scene.name == "crease" ? 70.0f : 1.0f) << what << " on " << b.name;
            EXPECT_LT(-farthest, scene.name == "crease" ? 1000.0f : 20.0f) << what << " on " << b.name;
          }
        EXPECT_GT(compared, 0u) << what << ": no backend ran both formats";
        measured += fmt("%s%s: vs rg32f %.2g, vs metres %.2g", measured.empty() ? "" : "; ", what.c_str(), worstFormat,
                        worstUnit);
      }
    }
  report("half_intermediates at world scale x1, x1e-3, x1e3 (key z in metres; sphere-plane and a crease 70 m away, "
         "D32F rev and R32F)",
         "max |A(rg16f) - A(rg32f)| <= 2/255, |A(u) - A(1)| <= 1/255 on every backend; keys finite, in metres", measured);
}

// The same geometry k times larger in metres: the settings with a length (radius, epsilon in m²,
// the quad threshold) scaled alike, and the camera's near plane with them.
Settings scaledLengths(Settings s, double k) {
  s.radius = float(1.0 * k);
  s.epsilon = float(1e-4 * k * k);
  s.quad_edge_threshold = float(0.02 * k);
  return s;
}
Camera physicalScaleCamera(double k) { return camera(64, 48, 0.1 * k, kInf, ClipDepth::ZeroToOne, true, 8); }

TEST(WorldScale, PhysicalScaleWithTheRadiusLeavesAUnchanged) {
  // The same geometry made k times larger in metres (u = 1), with radius, ε, the quad threshold
  // and the blur sharpness scaled alike. Eq. 1's sum has the unit 1/length; σ is unitless because
  // the block multiplies the sum by the radius (intensity_div_s = 2·σ·r/s), so A must not change
  // with σ fixed. The run with σ·k (what a σ in metres needed) must differ: it shows the test can
  // tell the two apart.
  const test::Scene scene = test::sphereOnPlaneScene();
  const SceneRun r1 = runScene("physical scale 1", fullResolution(), physicalScaleCamera(1.0), scene, DepthFormat::D32F);
  std::string measured;
  for (double k : {0.1, 10.0}) {
    Settings s = scaledLengths(fullResolution(), k);
    s.blur_edge_sharpness = float(10.0 / k);
    const Camera ck = physicalScaleCamera(k);
    const test::Scene sk = scaledScene(scene, k);
    const SceneRun plain = runScene(fmt("physical scale %g, sigma 1", k), s, ck, sk, DepthFormat::D32F);
    s.intensity = float(k);
    const SceneRun scaled = runScene(fmt("physical scale %g, sigma %g", k, k), s, ck, sk, DepthFormat::D32F);
    for (const BackendRun& b : plain.runs.runs)
      if (const BackendRun* b1 = r1.runs.find(b.name)) {
        const double d = maxAbsDiff(b.out.ao, b1->out.ao);
        EXPECT_LE(d, k255) << "k = " << k << " on " << b.name;
        const double ds = maxAbsDiff(scaled.runs.find(b.name)->out.ao, b1->out.ao);
        EXPECT_GT(ds, k255) << "k = " << k << " on " << b.name << ": sigma*k should change A";
        if (b.name == "cpu") measured += fmt("%sk=%g: sigma fixed %.2g, sigma·k %.2g", measured.empty() ? "" : "; ", k, d, ds);
      }
  }
  report("scene scaled x0.1 / x10 in metres with radius, epsilon, thresholds scaled alike",
         "A unchanged within 1/255 with sigma fixed (sigma is unitless: the sum is scaled by r)", measured);
}

TEST(WorldScale, ARelativeBlurEdgeNeedsNoRescaling) {
  // blur_edge_relative weighs a blur tap by |dz| / |z|, which no unit and no physical scale
  // changes: it is uploaded as it is for any metersToViewUnits (either key), and the scene k
  // times larger in metres (radius, epsilon and the quad threshold scaled, as above) keeps A with
  // blur_edge_sharpness 0 and blur_edge_relative fixed. With the sharpness fixed at its 10/m
  // instead, A must change: the test tells the two apart. rg32f keys: binary16 keys round z to
  // 2^-11 of itself, a change of |dz| / |z| that is not the same at both scales (measured with
  // rg16f keys: up to 2/255 apart).
  Settings rel = fullResolution();
  rel.half_intermediates = false;
  rel.blur_radius = 2;
  rel.blur_edge_sharpness = 0.0f;
  rel.blur_edge_relative = 200.0f;
  for (bool halfKeys : {false, true})
    for (double u : {1.0, 1e3, 1e-3}) {
      Settings s = rel;
      s.half_intermediates = halfKeys;
      Camera c = camera(16, 16, 0.1 * u, kInf, ClipDepth::ZeroToOne, true);
      c.metersToViewUnits = u;
      ParamBlock p;
      ASSERT_TRUE(computeConstants(s, c, DepthEncoding::Hardware, p).ok());
      EXPECT_EQ(p.blur_edge_relative, rel.blur_edge_relative) << "u = " << u << ", half keys " << halfKeys;
      EXPECT_EQ(p.blur_edge_sharpness, 0.0f) << "u = " << u;
    }
  const test::Scene scene = test::sphereOnPlaneScene();
  const Camera cam = physicalScaleCamera(1.0);
  Settings absolute = rel;
  absolute.blur_edge_sharpness = 10.0f;
  absolute.blur_edge_relative = 0.0f;
  const SceneRun r1 = runScene("relative blur edge, scale 1", rel, cam, scene, DepthFormat::D32F);
  const SceneRun a1 = runScene("absolute blur edge, scale 1", absolute, cam, scene, DepthFormat::D32F);
  std::string measured;
  for (double k : {0.1, 10.0}) {
    const Camera ck = physicalScaleCamera(k);
    const test::Scene sk = scaledScene(scene, k);
    const SceneRun r = runScene(fmt("relative blur edge, scale %g", k), scaledLengths(rel, k), ck, sk, DepthFormat::D32F);
    const SceneRun a = runScene(fmt("absolute blur edge, scale %g", k), scaledLengths(absolute, k), ck, sk, DepthFormat::D32F);
    for (const BackendRun& b : r.runs.runs)
      if (const BackendRun* b1 = r1.runs.find(b.name)) {
        const double d = maxAbsDiff(b.out.ao, b1->out.ao);
        EXPECT_LE(d, k255) << "k = " << k << " on " << b.name << ": the relative edge at another scale";
        const double da = maxAbsDiff(a.runs.find(b.name)->out.ao, a1.runs.find(b.name)->out.ao);
        EXPECT_GT(da, k255) << "k = " << k << " on " << b.name << ": a sharpness in 1/m should change A";
        if (b.name == "cpu") measured += fmt("%sk=%g: relative %.2g, absolute %.2g", measured.empty() ? "" : "; ", k, d, da);
      }
  }
  report("scene scaled x0.1 / x10 in metres, blur radius 2, rg32f keys: blur_edge_relative 200 fixed against "
         "blur_edge_sharpness 10/m fixed",
         "A unchanged within 1/255 with the relative edge; the absolute one changes it", measured);
}

TEST(WorldScale, UnitsSweepFindsTheRangeThatHolds) {
  // metersToViewUnits = 10^k, k = -20 .. 20, on the float and double references, compared with
  // u = 1 (default settings: the block converts them, finding F2). The supported range is
  // [1e-6, 1e6] (camera.cpp; below it the normal reconstruction underflows in float, finding F3):
  // A must hold to 1/255 at every u inside it, and every u outside must be rejected with
  // InvalidCamera naming the range.
  EXPECT_TRUE(intensityScalesWithUnits()) << "finding F2 regressed";
  const test::Scene scene = test::sphereOnPlaneScene();
  const ScaleSetup& su = kScaleSetups[1];
  constexpr double kLo = 1e-6, kHi = 1e6;
  const char* kRangeText = "[1e-6, 1e6]";
  std::string measured;
  double okLo = 1, okHi = 1, dALo = -1, dAHi = -1;
  bool lowBroken = false, highBroken = false;
  std::size_t rejected = 0;
  CaseOptions refs;
  refs.only = {"cpu-double", "cpu"};
  const SceneRun b1 = runScene("units sweep base", fullResolution(), scaleCamera(su, 1.0), scene, su.fm, refs);
  for (int sign : {-1, 1})
    for (int e = 1; e <= 20; ++e) {
      const int k = sign * e;
      const double u = std::pow(10.0, k);
      const bool supported = u >= kLo * (1 - 1e-12) && u <= kHi * (1 + 1e-12);
      const Camera cu = scaleCamera(su, u);
      DepthModel m;
      const Status ast = analyze(cu, m);
      if (!supported) {
        EXPECT_EQ(ast.code, StatusCode::InvalidCamera) << "u = 1e" << k << ": '" << ast.message << "'";
        EXPECT_NE(ast.message.find(kRangeText), std::string::npos) << "u = 1e" << k << ": '" << ast.message << "'";
        rejected += ast.code == StatusCode::InvalidCamera;
        (sign < 0 ? lowBroken : highBroken) = true;
        continue;
      }
      ASSERT_TRUE(ast.ok()) << "u = 1e" << k << " is inside " << kRangeText << " but rejected: " << ast.message;
      const SceneRun r = runScene(fmt("units sweep u=1e%d", k), fullResolution(), cu, scaledScene(scene, u), su.fm, refs);
      double worst = 0;
      for (const BackendRun& b : r.runs.runs)
        if (const BackendRun* x = b1.runs.find(b.name)) worst = std::max(worst, maxAbsDiff(b.out.ao, x->out.ao));
      EXPECT_LE(worst, k255) << "u = 1e" << k;
      measured += fmt("%s1e%d: %.2g", measured.empty() ? "" : "; ", k, worst);
      if (k == -6) dALo = worst;
      if (k == 6) dAHi = worst;
      if (worst <= k255) {
        if (sign < 0 && !lowBroken) okLo = u;
        if (sign > 0 && !highBroken) okHi = u;
      } else {
        (sign < 0 ? lowBroken : highBroken) = true;
      }
    }
  EXPECT_LE(okLo, kLo);
  EXPECT_GE(okHi, kHi);
  // Both ends measured (a dA of -1 means the end was never run).
  EXPECT_GE(dALo, 0.0);
  EXPECT_LE(dALo, k255);
  EXPECT_GE(dAHi, 0.0);
  EXPECT_LE(dAHi, k255);
  EXPECT_EQ(rejected, 28u) << "1e-20 .. 1e-7 and 1e7 .. 1e20 must all be rejected";
  // Just outside, through every backend's own validation, not only analyze().
  const DepthImage probe = renderGpuDepth(scene, scaleCamera(su, 1.0), su.fm);
  std::string messages;
  for (double u : {1e-7, 1e7}) {
    const std::string msg = expectRejected(fmt("metersToViewUnits %g", u), fullResolution(), scaleCamera(su, u),
                                           {&probe, nullptr, nullptr}, StatusCode::InvalidCamera);
    EXPECT_NE(msg.find(kRangeText), std::string::npos) << "u = " << u << ": '" << msg << "'";
    messages += fmt("%s'%s'", messages.empty() ? "" : "; ", msg.c_str());
  }
  report("world scale sweep metersToViewUnits = 1e-20 .. 1e20 (D32F reversed, cpu and cpu-double)",
         "A within 1/255 of u = 1 over [1e-6, 1e6]; every u outside rejected with InvalidCamera naming the range",
         fmt("holds for %g .. %g (max dA %.2g at 1e-6, %.2g at 1e6); %zu u outside rejected (%s); per u: %s", okLo, okHi,
             dALo, dAHi, rejected, messages.c_str(), measured.c_str()));
}

}  // namespace
}  // namespace sao::stability
