// The whole effect at the extremes of cameras, units, settings and inputs, on every backend:
// sky frames, sub-pixel and off-screen radii, world scale, every setting at both ends of its
// range, NaN / Inf / out-of-range / denormal depth, walls facing the camera and at grazing
// incidence, depth discontinuities, and the near / far grid. Every run is checked by runCase
// (finite, in [0, 1], sky = 1, GL = Vulkan within 1/255); each test adds its own bound.
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "sao/cpu/reference.h"
#include "stability_support.h"

namespace sao::stability {
namespace {

constexpr double kInf = INFINITY;
constexpr double k255 = 1.0 / 255.0;

struct Conv {
  const char* name;
  ClipDepth clip;
  bool reversed;
  double far;
};
const Conv kConvs[] = {
    {"standard [-1,1] far 1e4", ClipDepth::NegativeOneToOne, false, 1e4},
    {"standard [-1,1] infinite", ClipDepth::NegativeOneToOne, false, kInf},
    {"standard [0,1] infinite", ClipDepth::ZeroToOne, false, kInf},
    {"reversed [0,1] far 1e4", ClipDepth::ZeroToOne, true, 1e4},
    {"reversed [0,1] infinite", ClipDepth::ZeroToOne, true, kInf},
    {"reversed [-1,1] infinite (no clip control)", ClipDepth::NegativeOneToOne, true, kInf},
};

// A camera for a convention: perspective 60°, near 0.1 m (or orthographic over 0.1 .. 100 m when
// `ortho`; an orthographic camera has no infinite far plane, so 1e4 is used there).
Camera convCamera(const Conv& cv, std::uint32_t w, std::uint32_t h, std::uint32_t guard, bool ortho = false,
                  double orthoHalfHeight = 3.0) {
  if (ortho) return orthoCamera(w, h, 0.1, std::isinf(cv.far) ? 1e4 : cv.far, cv.clip, cv.reversed, guard, orthoHalfHeight);
  return camera(w, h, 0.1, cv.far, cv.clip, cv.reversed, guard);
}

struct SceneRun {
  DepthImage depth;
  std::vector<bool> sky;
  std::vector<double> z;  // analytic z per AO pixel (0 = sky)
  CaseRuns runs;
};

SceneRun runScene(const std::string& label, const Settings& settings, const Camera& cam, const test::Scene& scene,
                  DepthFormat format, CaseOptions opt = {}) {
  SceneRun r;
  r.depth = renderGpuDepth(scene, cam, format);
  r.z = aoPixelZ(scene, cam);
  r.sky.resize(r.z.size());
  for (std::size_t i = 0; i < r.z.size(); ++i) r.sky[i] = r.z[i] == 0.0;
  opt.skyMask = &r.sky;
  r.runs = runCase(label, settings, cam, {&r.depth, nullptr, nullptr}, opt);
  return r;
}

std::vector<bool> notMask(const std::vector<bool>& m) {
  std::vector<bool> o(m.size());
  for (std::size_t i = 0; i < m.size(); ++i) o[i] = !m[i];
  return o;
}

// ================================================================================================
// Sky

TEST(Sky, AllSkyFrameIsOneEverywhere) {
  std::size_t runs = 0;
  for (const Conv& cv : kConvs)
    for (bool ortho : {false, true})
      for (DepthFormat fm : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ}) {
        const Camera cam = convCamera(cv, 64, 48, 4, ortho);
        CaseOptions o;
        o.dumpPasses = true;
        const SceneRun r = runScene(fmt("all sky, %s %s", describe(cam).c_str(), toString(fm)), Settings{}, cam,
                                    test::skyScene(), fm, o);
        for (const BackendRun& b : r.runs.runs) {
          ++runs;
          EXPECT_EQ(range(b.out.ao).min, 1.0) << b.name;
          if (const FloatImage* raw = b.intermediate("ao_raw")) {
            std::size_t nonZeroKeys = 0;
            for (std::size_t i = 0; i < raw->data.size(); i += 2)
              nonZeroKeys += std::bit_cast<std::uint32_t>(raw->data[i + 1]) != 0u;
            EXPECT_EQ(nonZeroKeys, 0u) << b.name << ": sky keys must be +0.0";
          }
        }
      }
  report("all-sky frame (6 conventions x persp/ortho x D16/D24/D32F/R32F)", "A = 1 on every pixel, keys +0.0",
         fmt("A = 1 exactly in all %zu backend runs", runs));
}

TEST(Sky, SkyNextToGeometryWithInfiniteFar) {
  // A floor to the horizon and a sphere, nothing behind: half the frame is sky, and the floor
  // pixels next to the horizon hold the largest finite depths the format can store.
  test::Scene scene = test::sphereOnPlaneScene();
  scene.planes.pop_back();  // no wall
  double minGeom = 1;
  std::size_t runs = 0;
  for (const Conv& cv : kConvs) {
    if (!std::isinf(cv.far)) continue;
    for (DepthFormat fm : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ}) {
      const Camera cam = convCamera(cv, 64, 48, 4);
      CaseOptions o;
      o.dumpPasses = true;
      const SceneRun r = runScene(fmt("sky next to geometry, %s %s", describe(cam).c_str(), toString(fm)), Settings{}, cam,
                                  scene, fm, o);
      const std::vector<bool> geom = notMask(r.sky);
      for (const BackendRun& b : r.runs.runs) {
        ++runs;
        for (const auto& [name, img] : b.out.intermediates)
          EXPECT_TRUE(allFinite(img)) << b.name << ": intermediate " << name << " holds NaN or Inf";
        minGeom = std::min(minGeom, range(b.out.ao, &geom).min);
      }
    }
  }
  // The same with every other texel sky (a checkerboard): every geometry pixel borders sky.
  for (bool reversed : {false, true}) {
    const Camera cam = camera(64, 48, 0.1, kInf, ClipDepth::ZeroToOne, reversed, 4);
    DepthImage depth = renderGpuDepth(test::sphereOnPlaneScene(), cam, DepthFormat::D32F);
    std::vector<bool> sky(std::size_t(cam.width) * cam.height);
    for (std::uint32_t y = 0; y < depth.extent.height; ++y)
      for (std::uint32_t x = 0; x < depth.extent.width; ++x)
        if ((x + y) & 1) depth.texels[std::size_t(y) * depth.extent.width + x] = storeDepth(DepthFormat::D32F, reversed ? 0.0f : 1.0f);
    for (std::uint32_t y = 0; y < cam.height; ++y)
      for (std::uint32_t x = 0; x < cam.width; ++x) sky[std::size_t(y) * cam.width + x] = ((x + 4 + y + 4) & 1) != 0;
    CaseOptions o;
    o.skyMask = &sky;
    o.dumpPasses = true;
    const CaseRuns runsCb = runCase(fmt("sky checkerboard, %s", describe(cam).c_str()), Settings{}, cam, {&depth, nullptr, nullptr}, o);
    for (const BackendRun& b : runsCb.runs) {
      ++runs;
      for (const auto& [name, img] : b.out.intermediates) EXPECT_TRUE(allFinite(img)) << b.name << " " << name;
    }
  }
  report("sky next to geometry, infinite far (4 conventions x D16/D24/D32F/R32F; sky checkerboard)",
         "A = 1 on sky; every intermediate finite; A in [0,1]",
         fmt("%zu runs: sky exactly 1, no NaN/Inf in csz/ao_raw/ao_blur_h/ao; lowest A on geometry %.3f", runs, minGeom));
}

// ================================================================================================
// Radius projecting to less than a pixel

// Pixels of the sphere-on-plane scene scaled by k whose surface point lies farther than `radius`
// from every other surface of the scene: nothing can occlude them within the ball, so A must be 1
// there; a dark pixel there is false occlusion ("speckle"). Pixels whose taps may leave the depth
// input (r' > distance to its border) are left out: past the border the effect reads the edge
// texel at constant depth, a screen-space limit of its own (design-notes §4, guard band).
using OtherDistance = double (*)(const test::Vec3& p, double k);

// Sphere-on-plane x k: the distance from a point of one surface to the other two.
double sphereOnPlaneOthers(const test::Vec3& p, double k) {
  const double cy = -0.5 * k, cz = -3.0 * k, R = 0.5 * k;
  const double dFloor = p.y + k, dWall = p.z + 8.0 * k;
  const double dSphere = std::sqrt(p.x * p.x + (p.y - cy) * (p.y - cy) + (p.z - cz) * (p.z - cz)) - R;
  const double eps = 1e-6 * k;
  if (std::fabs(dFloor) < eps) return std::min(dWall, dSphere);
  if (std::fabs(dWall) < eps) return std::min(dFloor, dSphere);
  return std::min(dFloor, dWall);
}

// The 90° crease (creaseScene): from a point of one face, the other face is |x|·√2 away.
double creaseOthers(const test::Vec3& p, double) { return std::fabs(p.x) * std::sqrt(2.0); }

std::vector<bool> unoccludedMask(const Camera& cam, const std::vector<double>& z, double k, double radius,
                                 OtherDistance others) {
  std::vector<bool> m(z.size(), false);
  ParamBlock pb;
  Settings s;
  s.radius = float(radius);
  EXPECT_TRUE(computeConstants(s, cam, DepthEncoding::Hardware, pb).ok());
  const int W = int(cam.width), H = int(cam.height), g = int(cam.guardBand);
    for (std::uint32_t y = 0; y < cam.height; ++y)
    for (std::uint32_t x = 0; x < cam.width; ++x) {
      const std::size_t i = std::size_t(y) * cam.width + x;
      if (z[i] == 0) continue;
      const double rpx = cam.kind == ProjectionKind::Orthographic ? double(pb.radius) * pb.proj_scale
                                                                  : double(pb.radius) * pb.proj_scale / -z[i];
      const int border = std::min({int(x) + g, W + g - 1 - int(x), int(y) + g, H + g - 1 - int(y)});
      if (rpx + 1 > border) continue;
      test::Vec3 o, d;
      test::viewRay(cam, x + cam.guardBand, y + cam.guardBand, o, d);
      const double t = (z[i] - o.z) / d.z;
      const test::Vec3 p{o.x + t * d.x, o.y + t * d.y, z[i]};
      m[i] = others(p, k) > radius;
    }
  return m;
}

TEST(Radius, SubPixelRadiusFadesSmoothlyToOne) {
  // The sphere-on-plane scene (sphere 3 m away; x30: 90 m away, with the intensity at its maximum
  // so that the occlusion stays visible), radius swept from ~20 px down to ~0.01 px at the nearest
  // geometry.
  // Orthographic: the 90° crease 5 m away (an orthographic view along -z sees the floor edge-on).
  struct Setup {
    double k;
    float intensity;
    bool ortho;
    std::vector<double> radii;
  };
  const Setup setups[] = {
      {1.0, 1.0f, false, {1, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01}},
      {30.0, 10.0f, false, {30, 15, 6, 3, 1.5, 0.6, 0.3, 0.1, 0.01}},
      {1.0, 1.0f, true, {1, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01}},
  };
  for (const Setup& su : setups) {
    const test::Scene scene = su.ortho ? test::creaseScene(5.0) : scaledScene(test::sphereOnPlaneScene(), su.k);
    const OtherDistance others = su.ortho ? creaseOthers : sphereOnPlaneOthers;
    const Camera cam = su.ortho ? orthoCamera(64, 48, 0.1, 100.0, ClipDepth::ZeroToOne, true, 8, 2.0)
                                : camera(64, 48, 0.1, kInf, ClipDepth::ZeroToOne, true, 8);
    ParamBlock pb;
    ASSERT_TRUE(computeConstants(Settings{}, cam, DepthEncoding::Hardware, pb).ok());
    std::map<std::string, double> prevDark;
    std::string measured;
    std::size_t falseOcclusion = 0;
    for (double r : su.radii) {
      Settings s;
      s.radius = float(r);
      s.intensity = su.intensity;
      const SceneRun run = runScene(fmt("radius %g, scene x%g, %s", r, su.k, describe(cam).c_str()), s, cam, scene, DepthFormat::D32F);
      const std::vector<bool> geom = notMask(run.sky);
      const std::vector<bool> free = unoccludedMask(cam, run.z, su.k, r, others);
      double zMin = INFINITY;
      for (double z : run.z)
        if (z != 0) zMin = std::min(zMin, -z);
      const double rPxMax = su.ortho ? r * pb.proj_scale : r * pb.proj_scale / zMin;
      for (const BackendRun& b : run.runs.runs) {
        const Range a = range(b.out.ao, &geom);
        const double dark = 1.0 - a.mean;
        // False occlusion is judged before the blur (the blur legitimately spreads nearby AO over
        // up to R·stride pixels): ao_raw, on pixels whose whole 2x2 quad is unoccluded.
        std::size_t speckles = 0;
        const FloatImage& raw = b.out.aoRaw;
        ASSERT_EQ(raw.extent, b.out.ao.extent) << b.name << " gives no ao_raw";
        for (std::uint32_t y = 0; y < cam.height; ++y)
          for (std::uint32_t x = 0; x < cam.width; ++x) {
            auto f = [&](std::uint32_t xx, std::uint32_t yy) {
              return xx >= cam.width || yy >= cam.height || free[std::size_t(yy) * cam.width + xx];
            };
            if (f(x, y) && f(x ^ 1u, y) && f(x, y ^ 1u) && f(x ^ 1u, y ^ 1u) && raw.at(x, y, 0) < 1.0 - k255) ++speckles;
          }
        falseOcclusion += speckles;
        if (rPxMax < 1.0) {
          EXPECT_EQ(a.min, 1.0) << b.name << ": r' < 1 px everywhere must give A = 1 exactly";
        }
        if (prevDark.count(b.name)) {
          EXPECT_LE(dark, prevDark[b.name] + 1e-4) << b.name << ": darkening must not grow as the radius shrinks (r = " << r << ")";
        }
        EXPECT_EQ(speckles, 0u) << b.name << " r = " << r << ": pixels with nothing within the radius are darkened before the blur";
        prevDark[b.name] = dark;
        if (b.name == "cpu")
          measured += fmt("%sr'max %.2g px: mean 1-A %.4f, min A %.3f", measured.empty() ? "" : "; ", rPxMax, dark, a.min);
      }
    }
    report(fmt("radius projecting below 1 px (%s, intensity %g)",
               su.ortho ? "orthographic, crease 5 m" : fmt("perspective, sphere-on-plane x%g", su.k).c_str(), su.intensity),
           "mean darkening non-increasing as r' shrinks; A = 1 exactly once r' < 1 px; no dark pixel (ao_raw < 1-1/255) "
           "where nothing lies within the radius (speckle)",
           measured + fmt("; false-occlusion pixels: %zu", falseOcclusion));
  }
}

// ================================================================================================
// Radius projecting beyond the screen

TEST(Radius, HugeRadiusAtTheNearPlaneIsClampedAndFinite) {
  std::string measured;
  for (double n : {1e-2, 1e-4}) {
    // Floor, sphere and wall scaled so that the floor reaches the near plane and the sphere is at
    // 3 near: r' = 100 m · S' / near ~ 4e5 .. 4e7 px before the clamp.
    const test::Scene scene = scaledScene(test::sphereOnPlaneScene(), n);
    for (const auto& [w, h, g] : {std::tuple{64u, 48u, 8u}, std::tuple{641u, 479u, 0u}})
      for (const Conv& cv : {kConvs[1], kConvs[4]})
        for (bool hierarchy : {true, false}) {
          Camera cam = camera(w, h, n, cv.far, cv.clip, cv.reversed, g);
          Settings s;
          s.radius = 100.0f;
          s.use_z_hierarchy = hierarchy;
          ParamBlock pb;
          ASSERT_TRUE(computeConstants(s, cam, DepthEncoding::Hardware, pb).ok());
          const std::uint32_t size0 = std::max(w, h) + 2 * g;
          const int expectLevels = hierarchy ? 1 + std::min<int>(gen::SAO_MAX_MIP_LEVELS - 1, int(std::floor(std::log2(double(size0))))) : 1;
          EXPECT_EQ(pb.max_mip + 1, expectLevels) << describe(cam);
          const SceneRun r = runScene(fmt("radius 100 m, near %g, %s%s", n, describe(cam).c_str(), hierarchy ? "" : " no hierarchy"),
                                      s, cam, scene, cv.reversed ? DepthFormat::D32F : DepthFormat::D24);
          for (const BackendRun& b : r.runs.runs) EXPECT_EQ(int(b.out.plan.cszLevels), expectLevels) << b.name;
          if (hierarchy && w == 641 && n == 1e-4 && cv.reversed && !r.runs.runs.empty()) {
            const Range a = range(r.runs.runs.front().out.ao);
            measured = fmt("r'max = %.3g px unclamped -> 65536; %d csz levels (max_mip %d) for %ux%u; A in [%.3f, %.3f]",
                           100.0 * pb.proj_scale / n, expectLevels, pb.max_mip, w, h, a.min, a.max);
          }
        }
  }
  // Orthographic: r' = r·S' = 100 m · 1200 px/m = 1.2e5 px, clamped as well.
  {
    const Camera cam = orthoCamera(64, 48, 0.01, 10.0, ClipDepth::ZeroToOne, true, 8, 0.02);
    Settings s;
    s.radius = 100.0f;
    runScene("radius 100 m, orthographic 4 cm view of a crease 5 cm away", s, cam, test::creaseScene(0.05), DepthFormat::D32F);
  }
  report("radius projecting beyond the screen (radius 100 m, near 1e-2 / 1e-4, 64x48+g8 and 641x479, hierarchy on/off, ortho)",
         "finite A in [0,1]; csz levels = 1 + min(7, floor(log2 size0)); no integer overflow (see the UBSan test)", measured);
}

// ================================================================================================
// World scale

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
  EXPECT_TRUE(computeConstants(Settings{}, c1, DepthEncoding::Hardware, p1).ok());
  EXPECT_TRUE(computeConstants(Settings{}, c2, DepthEncoding::Hardware, p2).ok());
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
    const SceneRun r1 = runScene(fmt("world scale 1, %s", su.name), Settings{}, scaleCamera(su, 1.0), scene, su.fm);
    for (double u : {1e-3, 1e3}) {
      const SceneRun ru = runScene(fmt("world scale %g, %s", u, su.name), Settings{}, scaleCamera(su, u),
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

TEST(WorldScale, PhysicalScaleWithTheRadiusLeavesAUnchanged) {
  // The same geometry made k times larger in metres (u = 1), with radius, ε, the quad threshold
  // and the blur sharpness scaled alike. Eq. 1's sum has the unit 1/length; σ is unitless because
  // the block multiplies the sum by the radius (intensity_div_s = 2·σ·r/s), so A must not change
  // with σ fixed. The run with σ·k (what a σ in metres needed) must differ: it shows the test can
  // tell the two apart.
  const test::Scene scene = test::sphereOnPlaneScene();
  const Camera cam = camera(64, 48, 0.1, kInf, ClipDepth::ZeroToOne, true, 8);
  const SceneRun r1 = runScene("physical scale 1", Settings{}, cam, scene, DepthFormat::D32F);
  std::string measured;
  for (double k : {0.1, 10.0}) {
    Settings s;
    s.radius = float(1.0 * k);
    s.epsilon = float(1e-4 * k * k);
    s.quad_edge_threshold = float(0.02 * k);
    s.blur_edge_sharpness = float(10.0 / k);
    Camera ck = camera(64, 48, 0.1 * k, kInf, ClipDepth::ZeroToOne, true, 8);
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
  const SceneRun b1 = runScene("units sweep base", Settings{}, scaleCamera(su, 1.0), scene, su.fm, refs);
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
      const SceneRun r = runScene(fmt("units sweep u=1e%d", k), Settings{}, cu, scaledScene(scene, u), su.fm, refs);
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
    const std::string msg = expectRejected(fmt("metersToViewUnits %g", u), Settings{}, scaleCamera(su, u),
                                           {&probe, nullptr, nullptr}, StatusCode::InvalidCamera);
    EXPECT_NE(msg.find(kRangeText), std::string::npos) << "u = " << u << ": '" << msg << "'";
    messages += fmt("%s'%s'", messages.empty() ? "" : "; ", msg.c_str());
  }
  report("world scale sweep metersToViewUnits = 1e-20 .. 1e20 (D32F reversed, cpu and cpu-double)",
         "A within 1/255 of u = 1 over [1e-6, 1e6]; every u outside rejected with InvalidCamera naming the range",
         fmt("holds for %g .. %g (max dA %.2g at 1e-6, %.2g at 1e6); %zu u outside rejected (%s); per u: %s", okLo, okHi,
             dALo, dAHi, rejected, messages.c_str(), measured.c_str()));
}

// ================================================================================================
// Settings at both ends of their ranges

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
            Settings s;
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
      Settings s;
      gen::setSettingValue(s, id, v);
      ASSERT_TRUE(validate(s).ok()) << gen::kSettings[i].name << " = " << v;
      check(fmt("%s = %g", std::string(gen::kSettings[i].name).c_str(), v), s, persp, DepthFormat::D24);
    }
  }
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
      Settings s;
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

// ================================================================================================
// NaN, Inf, negative and > 1 depth; denormal and extreme depth

// The linear_z pass as docs/effect-math.md §3 specifies it, in float with the block's constants:
// the value csz must hold.
float specZ(float d, const ParamBlock& p) {
  auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
  const bool finite = (bits(d) & 0x7F800000u) != 0x7F800000u;
  if (!finite || d * p.far_dir >= p.far_lim) return 0.0f;
  if (p.depth_mode != gen::SAO_DEPTH_MODE_LINEAR && (d < 0.0f || d > 1.0f)) return 0.0f;  // no hardware depth
  const float z = p.depth_mode == gen::SAO_DEPTH_MODE_PERSPECTIVE ? p.clip_info.x / (d * p.clip_info.y + p.clip_info.z)
                                                                  : d * p.clip_info.y + p.clip_info.z;
  const std::uint32_t b = bits(z);
  return (b > 0x80000000u && b < 0xFF800000u) ? z : 0.0f;
}

double specZDouble(double d, const ParamBlock& p) {
  if (!std::isfinite(d) || d * double(p.far_dir) >= double(p.far_lim)) return 0.0;
  if (p.depth_mode != gen::SAO_DEPTH_MODE_LINEAR && (d < 0.0 || d > 1.0)) return 0.0;
  const double c0 = p.clip_info.x, c1 = p.clip_info.y, c2 = p.clip_info.z;
  const double z = p.depth_mode == gen::SAO_DEPTH_MODE_PERSPECTIVE ? c0 / (d * c1 + c2) : d * c1 + c2;
  return (std::isfinite(z) && z < 0) ? z : 0.0;
}

std::string valueName(float v) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(v);
  if (std::isnan(v)) return fmt("NaN(0x%08X)", b);
  if (v == 0) return std::signbit(v) ? "-0" : "+0";
  return fmt("%.9g", double(v));
}

std::string zName(float z) { return z == 0.0f ? "sky" : fmt("%.4g", double(z)); }

// Runs frames of a plane at 2 m with `values` planted every 5th texel (and the same frame filled
// with a single value), on every backend; checks csz against the specification and A.
struct ValueCase {
  std::string convention;
  std::vector<std::string> zOfValue;  // csz per value (cpu)
  std::vector<std::string> zDouble;   // csz per value (cpu-double)
  std::vector<std::string> glHeld;    // whether GL's texture could hold the value
};
std::string joinRow(const std::string& head, const std::vector<std::string>& cells) {
  std::string row = head;
  for (const std::string& c : cells) row += " | " + c;
  return row;
}
std::size_t doubleOverflow = 0;  // csz texels the double reference stores as -Inf (F4)

ValueCase runValues(const std::string& what, const Camera& cam, DepthFormat fm, const std::vector<std::uint32_t>& texels,
                    bool gpuMayReject) {
  ValueCase vc;
  vc.convention = describe(cam);
  ParamBlock p;
  EXPECT_TRUE(computeConstants(Settings{}, cam, fm == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware, p).ok());
  const test::Scene plane = test::planeScene(2.0);
  for (int mode = 0; mode < 2; ++mode) {  // 0: planted in a plane; 1: per value, a whole frame
    const std::size_t frames = mode == 0 ? 1 : texels.size();
    for (std::size_t f = 0; f < frames; ++f) {
      DepthImage depth = renderGpuDepth(plane, cam, fm);
      const Extent e = depth.extent;
      std::vector<int> valueAt(depth.texels.size(), -1);
      if (mode == 0) {
        std::size_t k = 0;
        for (std::uint32_t y = 2; y < e.height; y += 5)
          for (std::uint32_t x = 2; x < e.width; x += 5, ++k) {
            const std::size_t i = std::size_t(y) * e.width + x;
            valueAt[i] = int(k % texels.size());
            depth.texels[i] = texels[std::size_t(valueAt[i])];
          }
      } else {
        for (std::size_t i = 0; i < depth.texels.size(); ++i) depth.texels[i] = texels[f], valueAt[i] = int(f);
      }
      // Expected csz per texel (spec) and the AO pixels that are sky.
      std::vector<float> expect(depth.texels.size());
      std::vector<bool> sky(std::size_t(cam.width) * cam.height);
      for (std::size_t i = 0; i < depth.texels.size(); ++i) {
        const std::uint32_t t = depth.texels[i];
        float d;
        switch (fm) {
          case DepthFormat::D16: d = float(t & 0xFFFFu) * float(1.0 / 65535.0); break;
          case DepthFormat::D24: d = float(t & 0xFFFFFFu) * float(1.0 / 16777215.0); break;
          default: d = std::bit_cast<float>(t);
        }
        expect[i] = specZ(d, p);
      }
      for (std::uint32_t y = 0; y < cam.height; ++y)
        for (std::uint32_t x = 0; x < cam.width; ++x)
          sky[std::size_t(y) * cam.width + x] = expect[std::size_t(y + cam.guardBand) * e.width + x + cam.guardBand] == 0.0f;
      CaseOptions o;
      o.dumpPasses = true;
      o.gpuMayRejectInput = gpuMayReject;
      // A sky pixel is exactly 1; a pixel whose z is geometry may have any A in [0, 1].
      o.skyMask = &sky;
      const std::string label = fmt("%s, %s %s, %s", what.c_str(), vc.convention.c_str(), toString(fm),
                                    mode == 0 ? "planted" : valueName(std::bit_cast<float>(texels[f])).c_str());
      const CaseRuns runs = runCase(label, Settings{}, cam, {&depth, nullptr, nullptr}, o);
      for (const BackendRun& b : runs.runs) {
        const FloatImage* csz = b.intermediate("csz_level0");
        if (!csz) continue;
        if (b.name != "cpu-double") {
          for (const auto& [name, img] : b.out.intermediates) EXPECT_TRUE(allFinite(img)) << label << " " << b.name << " " << name;
        }
        std::size_t mism = 0;
        for (std::size_t i = 0; i < expect.size(); ++i) {
          const float got = csz->data[i];
          bool ok;
          if (b.name == "cpu-double") {
            // The double reference: the same rules in double on the exact texel value (D16/D24:
            // v / (2^n - 1), so D24 code 2^24 - 2 is geometry there and sky in float, as
            // docs/effect-math.md §1 says). Where |z| > FLT_MAX (reversed-Z, infinite far, d
            // denormal) the double z is geometry and Result stores it as -Inf (finding F4): counted.
            const double zd = specZDouble(depth.value(std::uint32_t(i % e.width), std::uint32_t(i / e.width)), p);
            if (zd != 0 && std::fabs(zd) > double(std::numeric_limits<float>::max())) {
              if (std::isinf(got)) ++doubleOverflow;
              else ADD_FAILURE() << label << ": double z " << zd << " beyond float range stored as " << got;
              continue;
            }
            ok = (got == 0.0f) == (zd == 0.0) && (got == 0.0f || std::fabs(double(got) - zd) <= 1e-6 * std::fabs(zd) + 0x1p-149);
          } else
            ok = std::bit_cast<std::uint32_t>(got) == std::bit_cast<std::uint32_t>(expect[i]);
          if (!ok && mism++ < 3)
            ADD_FAILURE() << label << " on " << b.name << ": texel " << i << " depth bits 0x" << std::hex << depth.texels[i]
                          << std::dec << " gave csz " << got << ", the specification says " << expect[i];
        }
        if (mode == 1 && b.name == "cpu") vc.zOfValue.push_back(zName(csz->data[0]));
        if (mode == 1 && b.name == "cpu-double") vc.zDouble.push_back(zName(csz->data[0]));
      }
      if (mode == 1) {
        const BackendRun* gl = runs.find("gl");
        vc.glHeld.push_back(!backend("gl") ? "-" : gl ? "held" : "refused");
      }
    }
  }
  return vc;
}

TEST(DepthInput, NaNInfNegativeAndAboveOne) {
  const float vals[] = {std::bit_cast<float>(0x7FC00000u), std::bit_cast<float>(0x7F800001u),
                        std::bit_cast<float>(0xFFC00000u), INFINITY, -INFINITY, -0.0f, -0.5f, -1e30f,
                        -std::numeric_limits<float>::max(), 1.5f, 1e30f, std::numeric_limits<float>::max()};
  std::vector<std::uint32_t> texels;
  for (float v : vals) texels.push_back(std::bit_cast<std::uint32_t>(v));
  std::string header = "value";
  for (float v : vals) header += " | " + valueName(v);
  std::printf("[stability] D32F input values -> csz (cpu):\n[stability]   %s\n", header.c_str());
  for (const Conv& cv : kConvs)
    for (bool ortho : {false, true}) {
      const Camera cam = convCamera(cv, 40, 30, 2, ortho);
      const ValueCase vc = runValues("D32F special values", cam, DepthFormat::D32F, texels, true);
      std::printf("[stability]   %s\n", joinRow(vc.convention + " (cpu)", vc.zOfValue).c_str());
      if (vc.zDouble != vc.zOfValue)
        std::printf("[stability]   %s\n", joinRow(vc.convention + " (cpu-double)", vc.zDouble).c_str());
      if (!ortho && cv.reversed && std::isinf(cv.far))
        std::printf("[stability]   %s\n", joinRow("GL texture", vc.glHeld).c_str());
    }
  // R32F linear z: everything that is not a finite negative non-zero z is sky.
  const float lin[] = {std::bit_cast<float>(0x7FC00000u), INFINITY, -INFINITY, 0.0f, -0.0f, 5.0f,
                       std::bit_cast<float>(0x80000001u), -1e30f, -std::numeric_limits<float>::max()};
  std::vector<std::uint32_t> lt;
  std::string lh;
  for (float v : lin) lt.push_back(std::bit_cast<std::uint32_t>(v)), lh += " | " + valueName(v);
  const ValueCase vl = runValues("R32F special values", camera(40, 30, 0.1, kInf, ClipDepth::ZeroToOne, true, 2),
                                 DepthFormat::LinearZ, lt, false);
  std::string row;
  for (const std::string& z : vl.zOfValue) row += " | " + z;
  std::printf("[stability] R32F linear z values%s\n[stability]   -> csz%s\n", lh.c_str(), row.c_str());
  report("NaN (quiet, signalling, negative), +-Inf, -0, negative, > 1 and +-FLT_MAX in D32F (6 conventions, persp+ortho) and R32F",
         "csz as docs/effect-math.md §3 specifies (bit-exact in float); sky -> A = 1; everything finite",
         "as specified on every backend that accepts the input; table in docs/STABILITY.md");
}

TEST(DepthInput, DenormalAndExtremeValues) {
  const float vals[] = {0.0f,
                        1.0f,
                        1.0f - 0x1p-24f,
                        0x1p-24f,
                        std::bit_cast<float>(0x00000001u),  // smallest denormal 1.4e-45
                        1e-40f,
                        std::bit_cast<float>(0x007FFFFFu),  // largest denormal
                        0x1p-126f,                          // smallest normal
                        0.5f};
  std::vector<std::uint32_t> texels;
  std::string header;
  for (float v : vals) texels.push_back(std::bit_cast<std::uint32_t>(v)), header += " | " + valueName(v);
  std::printf("[stability] D32F extreme values -> csz (cpu)%s\n", header.c_str());
  for (const Conv& cv : kConvs)
    for (bool ortho : {false, true}) {
      const Camera cam = convCamera(cv, 40, 30, 2, ortho);
      const ValueCase vc = runValues("D32F extreme values", cam, DepthFormat::D32F, texels, true);
      std::printf("[stability]   %s\n", joinRow(vc.convention + " (cpu)", vc.zOfValue).c_str());
      if (vc.zDouble != vc.zOfValue)
        std::printf("[stability]   %s\n", joinRow(vc.convention + " (cpu-double)", vc.zDouble).c_str());
      if (!ortho && cv.reversed && std::isinf(cv.far))
        std::printf("[stability]   %s\n", joinRow("GL texture", vc.glHeld).c_str());
    }
  // Integer formats: 0, 1, the last two codes.
  for (DepthFormat fm : {DepthFormat::D16, DepthFormat::D24}) {
    const std::uint32_t top = fm == DepthFormat::D16 ? 0xFFFFu : 0xFFFFFFu;
    const std::vector<std::uint32_t> codes = {0u, 1u, top - 1, top};
    for (const Conv& cv : {kConvs[1], kConvs[2], kConvs[4]}) {
      const Camera cam = convCamera(cv, 40, 30, 2);
      const ValueCase vc = runValues("unorm extreme codes", cam, fm, codes, false);
      const std::string head = vc.convention + " " + toString(fm) + " codes 0, 1, max-1, max";
      std::printf("[stability]   %s\n", joinRow(head + " (cpu)", vc.zOfValue).c_str());
      if (vc.zDouble != vc.zOfValue) std::printf("[stability]   %s\n", joinRow(head + " (cpu-double)", vc.zDouble).c_str());
    }
  }
  report("d = 0, 1, 1-2^-24, 2^-24, denormals, 2^-126 (D32F); codes 0, 1, max-1, max (D16, D24)",
         "finite; csz as specified; sky -> A = 1",
         fmt("as specified on every backend (table in docs/STABILITY.md); final A finite everywhere; cpu-double stores %zu "
             "csz texels beyond FLT_MAX as -Inf in its Result (finding F4)", doubleOverflow));
}

// ================================================================================================
// Walls facing the camera and at grazing incidence: the bias each format needs

struct WallSetup {
  const char* name;
  DepthFormat fm;
  ClipDepth clip;
  bool reversed;
};
const WallSetup kWallSetups[] = {
    {"D16 standard [-1,1]", DepthFormat::D16, ClipDepth::NegativeOneToOne, false},
    {"D24 standard [-1,1]", DepthFormat::D24, ClipDepth::NegativeOneToOne, false},
    {"D32F standard [0,1]", DepthFormat::D32F, ClipDepth::ZeroToOne, false},
    {"D32F reversed [0,1]", DepthFormat::D32F, ClipDepth::ZeroToOne, true},
    {"R32F linear z", DepthFormat::LinearZ, ClipDepth::ZeroToOne, true},
};
const double kBiases[] = {0, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5};

// Min A over the wall pixels whose taps stay inside the depth input (r' <= distance to its border:
// past the border the effect extends the edge texel at constant depth, a screen-space limit that
// is not the bias's business), for one backend.
double wallMinA(const BackendRun& b, const SceneRun& r, const Camera& cam, const ParamBlock& p) {
  double m = 1;
  const int W = int(cam.width), H = int(cam.height), g = int(cam.guardBand);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double z = r.z[std::size_t(y) * W + x];
      if (z == 0) continue;
      const double rpx = std::min(double(p.radius) * p.proj_scale / (p.ortho ? 1.0 : -z), 65536.0);
      const int border = std::min({x + g, W + g - 1 - x, y + g, H + g - 1 - y});
      if (rpx > border) continue;
      m = std::min(m, double(b.out.ao.at(std::uint32_t(x), std::uint32_t(y))));
    }
  return m;
}

TEST(Walls, FacingAndGrazingWallNeedNoMoreThanTheDefaultBias) {
  // A plane through (0, 0, -D) facing the camera, and the same plane turned 89° about the vertical
  // axis (grazing incidence on the centre column; it then spans ~0.02 D .. infinity across the
  // left half of the image). Default radius 1 m, and a radius projecting to 8 px at D. For each
  // format: the smallest bias (of 0, 1e-4, 2e-4, 5e-4, ... 0.5) with min A >= 1 - 1/255 over the
  // wall pixels whose taps stay inside the input. Grazing walls also run without the z hierarchy,
  // which separates depth precision from the MIP approximation (eq. 9-10: a tap at h >= 2^log_q
  // px reads z from a neighbouring texel of a coarser level, while Q keeps the tap pixel's centre).
  const float defaultBias = Settings{}.bias;
  // Per condition (facing; grazing with the z hierarchy; grazing without), over every backend.
  double worstNeeded[3] = {0, 0, 0}, minAtDefaultAll[3] = {1, 1, 1};
  std::string failing;
  std::printf("[stability] bias needed for min A >= 1 - 1/255 (cpu; '>0.5' = none in range)\n");
  for (double angle : {0.0, 89.0})
    for (bool hierarchy : {true, false}) {
      if (angle == 0.0 && !hierarchy) continue;
      std::string table;
      for (const WallSetup& ws : kWallSetups) {
        std::string row = fmt("%-20s", ws.name);
        for (double D : {1.0, 10.0, 100.0})
          for (bool scaledRadius : {false, true}) {
            const Camera cam = camera(64, 48, 0.1, kInf, ws.clip, ws.reversed, 8);
            const test::Scene wall = turnedWall(D, angle);
            const double radius = scaledRadius ? std::clamp(8.0 * D / (0.5 * 48 * std::sqrt(3.0)), 0.01, 100.0) : 1.0;
            std::map<std::string, double> needed, minAtDefault;
            for (double bias : kBiases) {
              Settings s;
              s.radius = float(radius);
              s.bias = float(bias);
              s.use_z_hierarchy = hierarchy;
              ParamBlock p;
              ASSERT_TRUE(computeConstants(s, cam, DepthEncoding::Hardware, p).ok());
              const SceneRun r = runScene(fmt("wall %g deg at %g m, %s, radius %.3g, bias %g%s", angle, D, ws.name, radius, bias,
                                              hierarchy ? "" : ", no hierarchy"),
                                          s, cam, wall, ws.fm);
              bool allPass = true;
              for (const BackendRun& b : r.runs.runs) {
                const double m = wallMinA(b, r, cam, p);
                if (float(bias) == defaultBias) minAtDefault[b.name] = m;
                if (m >= 1.0 - k255) {
                  if (!needed.count(b.name)) needed[b.name] = bias;
                } else {
                  allPass = false;
                }
              }
              if (allPass && float(bias) >= defaultBias) break;
            }
            const int cond = angle == 0.0 ? 0 : hierarchy ? 1 : 2;
            EXPECT_FALSE(minAtDefault.empty()) << ws.name << " D = " << D << ": no backend ran the default bias";
            for (const auto& [name, m] : minAtDefault) {
              const double need = needed.count(name) ? needed[name] : INFINITY;
              // The default bias suffices for every format and distance, facing or grazing, with
              // or without the z hierarchy (the grazing case with it is what set the default).
              EXPECT_GE(m, 1.0 - k255) << ws.name << " " << angle << " deg D = " << D << " radius " << radius
                                       << (hierarchy ? "" : " no hierarchy") << " on " << name << " (needs bias " << need << ")";
              worstNeeded[cond] = std::max(worstNeeded[cond], need);
              minAtDefaultAll[cond] = std::min(minAtDefaultAll[cond], m);
              if (m < 1.0 - k255)
                failing += fmt("%s%s %g deg%s D=%g r=%.3g on %s: min A %.4f (needs %g)", failing.empty() ? "" : "; ",
                               ws.name, angle, hierarchy ? "" : " no hierarchy", D, radius, name.c_str(), m, need);
            }
            const double need = needed.count("cpu") ? needed["cpu"] : INFINITY;
            row += fmt(" | %s (%.4f)", std::isinf(need) ? ">0.5" : fmt("%g", need).c_str(),
                       minAtDefault.count("cpu") ? minAtDefault["cpu"] : -1.0);
          }
        table += "\n[stability]   " + row;
      }
      std::printf("[stability] wall %g deg%s: format | 1 m r=1 | 1 m r'=8px | 10 m r=1 | 10 m r'=8px | 100 m r=1 | 100 m r'=8px"
                  " -- bias needed (min A at the default bias)%s\n",
                  angle, hierarchy ? "" : " without z hierarchy", table.c_str());
    }
  const char* what[3] = {"flat wall facing the camera", "wall at 89° (grazing), z hierarchy on (default)",
                         "wall at 89° (grazing), z hierarchy off"};
  for (int cond = 0; cond < 3; ++cond)
    report(fmt("%s at 1, 10, 100 m (D16/D24 std, D32F std/rev, R32F; every backend)", what[cond]),
           fmt("A >= 1-1/255 at the default bias %g", double(defaultBias)),
           fmt("largest bias needed %g; min A at the default %.4f", worstNeeded[cond], minAtDefaultAll[cond]));
  if (!failing.empty()) std::printf("[stability] walls NOT MET where %s\n", failing.c_str());
}

TEST(Walls, OrthographicFacingAndGrazingWall) {
  // The same walls seen by an orthographic camera 10 cm tall (S' = 480 px/m), radius 1/60 m
  // 0.05 m (r' = 24 px everywhere: taps at h >= 8 px read coarser z levels), near 0.1 m, far 2 D + 10 m.
  std::string measured;
  for (double angle : {0.0, 89.0})
    for (bool hierarchy : {true, false}) {
      if (angle == 0.0 && !hierarchy) continue;
      for (const WallSetup& ws : kWallSetups) {
        if (ws.fm == DepthFormat::D16) continue;
        for (double D : {1.0, 10.0, 100.0}) {
          const Camera cam = orthoCamera(64, 48, 0.1, 2 * D + 10, ws.clip, ws.reversed, 8, 0.05);
          double need = INFINITY, minDefault = 1;
          for (double bias : kBiases) {
            Settings s;
            s.radius = 0.05f;
            s.bias = float(bias);
            s.use_z_hierarchy = hierarchy;
            ParamBlock p;
            ASSERT_TRUE(computeConstants(s, cam, DepthEncoding::Hardware, p).ok());
            const SceneRun r = runScene(fmt("ortho wall %g deg at %g m, %s, bias %g%s", angle, D, ws.name, bias,
                                            hierarchy ? "" : ", no hierarchy"),
                                        s, cam, turnedWall(D, angle), ws.fm);
            double m = 1;
            for (const BackendRun& b : r.runs.runs) m = std::min(m, wallMinA(b, r, cam, p));
            if (s.bias == Settings{}.bias) minDefault = m;
            if (m >= 1.0 - k255 && std::isinf(need)) need = bias;
            if (!std::isinf(need) && s.bias >= Settings{}.bias) break;
          }
          if (angle == 0.0 || !hierarchy) {
            EXPECT_GE(minDefault, 1.0 - k255) << ws.name << " " << angle << " deg D = " << D;
          } else {
            EXPECT_LE(need, 0.02) << ws.name << " D = " << D;
          }
          measured += fmt("%s%g deg%s %s %g m: needs %g (min A %.4f)", measured.empty() ? "" : "; ", angle,
                          hierarchy ? "" : " no-hier", ws.name, D, need, minDefault);
        }
      }
    }
  report("orthographic walls facing / at 89° at 1, 10, 100 m (r' = 24 px; D24 std, D32F std/rev, R32F)",
         "facing, and grazing without the z hierarchy: A >= 1-1/255 at the default bias; grazing with it: bias <= 0.02",
         measured);
}

// ================================================================================================
// Depth discontinuity

TEST(Discontinuity, NoOnePixelLineAfterTheBlur) {
  // A camera-facing card (|x|, |y| <= 0.5 m) at 2 m over a wall at 2.5 m (within the radius: the
  // card really darkens the wall around it) and at 10 m (beyond it: A must stay 1 everywhere).
  double minFar = 1, worstCardAll = 1, worstLineAll = -1;
  for (double wallD : {10.0, 2.5})
    for (bool ortho : {false, true})
      for (const WallSetup& ws : {kWallSetups[1], kWallSetups[3]}) {
        const Camera cam = ortho ? orthoCamera(64, 48, 0.1, 100.0, ws.clip, ws.reversed, 8, 1.0)
                                 : camera(64, 48, 0.1, kInf, ws.clip, ws.reversed, 8);
        const test::Scene scene = cardOverWall(2.0, wallD, 0.5);
        const SceneRun r = runScene(fmt("card at 2 m over wall at %g m, %s", wallD, describe(cam).c_str()), Settings{}, cam,
                                    scene, ws.fm);
        const int W = int(cam.width), H = int(cam.height);
        for (const BackendRun& b : r.runs.runs) {
          const FloatImage& ao = b.out.ao;
          auto A = [&](int x, int y) { return double(ao.at(std::uint32_t(x), std::uint32_t(y))); };
          auto onCard = [&](int x, int y) { return r.z[std::size_t(y) * W + x] > -2.2; };
          if (wallD == 10.0) {
            EXPECT_GE(range(ao).min, 1.0 - k255) << b.name << " " << describe(cam);
            continue;
          }
          // Card pixels (including the edge row/column) are lit: nothing is in front of them.
          double worstCard = 1, worstLine = 0;
          for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
              if (onCard(x, y)) worstCard = std::min(worstCard, A(x, y));
          // The wall next to the card's edges: a one-pixel line is a first step (edge pixel to its
          // wall neighbour) out of line with the steps further out. The 2x2 reconstruction makes
          // pairs of equal values, so the comparison is with the largest of the next five steps.
          auto excess = [&](int e, int dx, int dy) {  // e: first wall pixel, (dx, dy): away from the card
            auto at = [&](int k) { return A(e % W + k * dx, e / W + k * dy); };
            double further = 0;
            for (int k = 1; k <= 5; ++k) further = std::max(further, std::fabs(at(k) - at(k + 1)));
            return std::fabs(at(0) - at(1)) - 2.0 * further;
          };
          for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
              if (onCard(x, y)) continue;
              if (x + 7 < W && x >= 1 && onCard(x - 1, y)) worstLine = std::max(worstLine, excess(y * W + x, 1, 0));
              if (x >= 7 && x + 1 < W && onCard(x + 1, y)) worstLine = std::max(worstLine, excess(y * W + x, -1, 0));
              if (y + 7 < H && y >= 1 && onCard(x, y - 1)) worstLine = std::max(worstLine, excess(y * W + x, 0, 1));
              if (y >= 7 && y + 1 < H && onCard(x, y + 1)) worstLine = std::max(worstLine, excess(y * W + x, 0, -1));
            }
          EXPECT_LE(worstLine, k255) << b.name << " " << describe(cam) << ": a one-pixel line along the card's edge";
          worstLineAll = std::max(worstLineAll, worstLine);
          EXPECT_GE(worstCard, 1.0 - k255) << b.name << " " << describe(cam);
          worstCardAll = std::min(worstCardAll, worstCard);
        }
        if (wallD == 10.0)
          for (const BackendRun& b : r.runs.runs) minFar = std::min(minFar, range(b.out.ao).min);
      }
  report("depth discontinuity: camera-facing card at 2 m over a wall at 10 m (beyond the radius) and 2.5 m (within), "
         "persp + ortho, D24 standard / D32F reversed",
         "wall at 10 m: A >= 1-1/255 everywhere; wall at 2.5 m: card A >= 1-1/255 up to its edge, first wall step "
         "<= 2x the next steps + 1/255 (no dark or white one-pixel line)",
         fmt("10 m: min A %.4f; 2.5 m: min A on the card %.4f, worst first-step excess %.4f", minFar, worstCardAll, worstLineAll));
}

// ================================================================================================
// The near / far grid through the whole effect

TEST(Cameras, NearFarGridThroughTheEffectIsFinite) {
  const double nears[] = {1e-4, 1e-2, 1.0, 10.0};
  const double fars[] = {10.0, 1e4, kInf};
  std::size_t runs = 0;
  for (double n : nears)
    for (double f : fars) {
      if (!(f > n)) continue;
      // The sphere-on-plane scene scaled so that it starts 3 near planes away.
      const test::Scene scene = scaledScene(test::sphereOnPlaneScene(), std::max(1.0, 3.0 * n));
      for (const Conv& cv : kConvs)
        for (DepthFormat fm : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F}) {
          const Camera cam = camera(64, 48, n, f, cv.clip, cv.reversed, 4);
          DepthModel m;
          // Finite far/near >= 1e6 runs as it is (finding F1, fixed).
          ASSERT_TRUE(analyze(cam, m).ok()) << describe(cam);
          const SceneRun r = runScene(fmt("near/far grid %s %s", describe(cam).c_str(), toString(fm)), Settings{}, cam, scene, fm);
          runs += r.runs.runs.size();
        }
    }
  report("near {1e-4,1e-2,1,10} x far {10,1e4,inf} x 6 conventions x D16/D24/D32F through the effect (sphere-on-plane)",
         "no NaN/Inf; A in [0,1]; sky = 1", fmt("%zu runs pass", runs));
}

}  // namespace
}  // namespace sao::stability
