// The radius at both extremes: projecting to less than a pixel (A fades smoothly to 1, no false
// occlusion) and far beyond the screen (clamped, finite, the expected csz levels).
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "extremes_support.h"

namespace sao::stability {
namespace {

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
  Settings s = fullResolution();
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
    ASSERT_TRUE(computeConstants(fullResolution(), cam, DepthEncoding::Hardware, pb).ok());
    std::map<std::string, double> prevDark;
    std::string measured;
    std::size_t falseOcclusion = 0;
    for (double r : su.radii) {
      Settings s = fullResolution();
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
          Settings s = fullResolution();
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
    Settings s = fullResolution();
    s.radius = 100.0f;
    runScene("radius 100 m, orthographic 4 cm view of a crease 5 cm away", s, cam, test::creaseScene(0.05), DepthFormat::D32F);
  }
  report("radius projecting beyond the screen (radius 100 m, near 1e-2 / 1e-4, 64x48+g8 and 641x479, hierarchy on/off, ortho)",
         "finite A in [0,1]; csz levels = 1 + min(7, floor(log2 size0)); no integer overflow (see the UBSan test)", measured);
}

}  // namespace
}  // namespace sao::stability
