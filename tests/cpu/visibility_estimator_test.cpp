// The visibility estimator (setting estimator = 1, variant ESTIMATOR; effect/include/sao_visibility.glsl,
// effect/cpu/sao_visibility.h) on the CPU reference: the setting selects the variant and fills the
// block; an open plane is exactly 1 at every pixel in double (no sample of a plane lies in front of
// it: the slab starts behind the stored depth); occluders occlude, and more with a thicker slab;
// float mimics the GPU within the agreement bounds of double; the slices' weights integrate the
// hemisphere; the estimator does not change estimator 0's block.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "sao/settings.h"
#include "sao_visibility.h"
#include "test_support.h"

namespace sao::test {
namespace {

Settings visibilitySettings() {
  Settings s;
  s.estimator = 1;
  return s;
}

// A floor y = -1 under sky (camera level: each row of the floor has one z).
Scene floorScene() {
  Scene s{"floor", {}, {}, {}, {}};
  s.planes.push_back({{0, -1, 0}, {0, 1, 0}, {}});
  return s;
}

std::size_t pixelsNotOne(const FloatImage& ao) {
  std::size_t n = 0;
  for (float v : ao.data) n += v != 1.0f;
  return n;
}

double meanOf(const FloatImage& ao) {
  double m = 0;
  for (float v : ao.data) m += v;
  return m / double(ao.data.size());
}

TEST(VisibilityEstimator, SettingSelectsTheVariantAndFillsTheBlock) {
  const Camera cam = testCamera();
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), cam, DepthFormat::D32F);
  cpu::Inputs in;
  in.depth = &depth;
  Settings s = visibilitySettings();
  s.intensity = 0.75f;
  s.thickness = 0.5f;
  s.depth_tolerance = 0.01f;
  s.slices = 3;
  const cpu::Result r = runOrFail(s, cam, in, cpu::Precision::Float);
  EXPECT_EQ(r.plan.variants[std::size_t(gen::VariantId::ESTIMATOR)], 1);
  EXPECT_EQ(r.params.intensity_div_s, 0.75f) << "sigma itself: A = max(0, 1 - sigma (1 - V))^k";
  EXPECT_EQ(r.params.thickness, 0.5f);
  EXPECT_EQ(r.params.depth_tolerance, 0.01f);
  EXPECT_EQ(r.params.slices, 3);
  EXPECT_EQ(r.params.slice_turn, 715827883u) << "half a turn over 3 slices, 2^-32 turns";

  // Estimator 0: the variant is 0 and the new members are not uploaded (the inert rules).
  Settings a;
  a.thickness = 0.5f;
  a.slices = 3;
  const cpu::Result r0 = runOrFail(a, cam, in, cpu::Precision::Float);
  EXPECT_EQ(r0.plan.variants[std::size_t(gen::VariantId::ESTIMATOR)], 0);
  EXPECT_EQ(r0.params.thickness, 0.0f);
  EXPECT_EQ(r0.params.slices, 0);
  EXPECT_EQ(r0.params.slice_turn, 0u);
}

struct PlaneCase {
  std::string name;
  Scene scene;
  Camera camera;
  bool normals;
  int divisor;
  float tolerance;
};

TEST(VisibilityEstimator, OpenPlaneIsExactlyOneInDouble) {
  Camera ortho = orthographicCamera(2.0, 160, 90, 0.1, 20.0, ClipDepth::NegativeOneToOne, false);
  ortho.guardBand = 8;
  const std::vector<PlaneCase> cases = {
      {"facing_plane", planeScene(3.0), testCamera(), false, 2, 0.003f},
      {"facing_plane_tolerance_0", planeScene(3.0), testCamera(), false, 1, 0.0f},
      {"floor", floorScene(), testCamera(), false, 1, 0.003f},
      {"floor_normals_half_res", floorScene(), testCamera(), true, 2, 0.003f},
      {"floor_tolerance_0", floorScene(), testCamera(), true, 1, 0.0f},
      {"ortho_plane", planeScene(3.0), ortho, false, 1, 0.003f},
  };
  for (const PlaneCase& c : cases) {
    SCOPED_TRACE(c.name);
    const DepthImage depth = renderDepth(c.scene, c.camera, DepthFormat::D32F);
    const FloatImage n = renderNormals(c.scene, c.camera);
    cpu::Inputs in;
    in.depth = &depth;
    if (c.normals) in.normals = &n;
    for (int slices : {1, 2, 5}) {
      for (int samples : {4, 48}) {
        for (int model : {0, 1}) {  // thickness_model 1: a plane is one run, wide
          Settings s = visibilitySettings();
          s.thickness_model = model;
          s.slices = slices;
          s.samples = samples;
          s.resolution_divisor = c.divisor;
          s.depth_tolerance = c.tolerance;
          s.radius = 2.0f;
          const cpu::Result r = runOrFail(s, c.camera, in, cpu::Precision::Double);
          ASSERT_FALSE(r.ao.data.empty());
          EXPECT_EQ(pixelsNotOne(r.ao), 0u) << slices << " slices, " << samples << " samples, thickness_model " << model
                                            << ": mean A " << meanOf(r.ao);
        }
      }
    }
  }
}

TEST(VisibilityEstimator, OccludersOccludeAndThicknessAddsToIt) {
  // The crease (a 90-degree concave corner 2 m away) and the rods in front of a wall: A < 1 near
  // them; a thicker slab blocks at least as many directions, so A can only go down.
  for (const Scene& scene : {creaseScene(2.0), rodsScene(), sphereOnPlaneScene()}) {
    SCOPED_TRACE(scene.name);
    const Camera cam = testCamera();
    const DepthImage depth = renderDepth(scene, cam, DepthFormat::D32F);
    cpu::Inputs in;
    in.depth = &depth;
    Settings thin = visibilitySettings();
    thin.thickness = 0.01f;
    Settings thick = visibilitySettings();
    thick.thickness = 10.0f;
    const cpu::Result a = runOrFail(thin, cam, in, cpu::Precision::Double);
    const cpu::Result b = runOrFail(thick, cam, in, cpu::Precision::Double);
    EXPECT_LT(*std::min_element(b.ao.data.begin(), b.ao.data.end()), 0.75f);
    std::printf("%s: mean A %.4f (thickness 0.01 m) %.4f (10 m)\n", scene.name.c_str(), meanOf(a.ao), meanOf(b.ao));
    EXPECT_LE(meanOf(b.ao), meanOf(a.ao) + 1e-12);
    EXPECT_FALSE(sameBits(a.ao, b.ao)) << "thickness changes nothing";
  }
}

TEST(VisibilityEstimator, FloatFollowsDouble) {
  // Float (the GPU's arithmetic) against double: the bitmask turns a tiny angle difference into a
  // bit now and then, so this bounds the share of pixels, like the GPU agreement tests.
  for (const Scene& scene : {creaseScene(2.0), stairsScene(), sphereOnPlaneScene()}) {
    SCOPED_TRACE(scene.name);
    const Camera cam = testCamera();
    const DepthImage depth = renderDepth(scene, cam, DepthFormat::D32F);
    cpu::Inputs in;
    in.depth = &depth;
    const Settings s = visibilitySettings();
    const cpu::Result f = runOrFail(s, cam, in, cpu::Precision::Float);
    const cpu::Result d = runOrFail(s, cam, in, cpu::Precision::Double);
    ASSERT_EQ(f.ao.data.size(), d.ao.data.size());
    std::size_t within = 0;
    double maxAbs = 0;
    for (std::size_t i = 0; i < f.ao.data.size(); ++i) {
      const double e = std::fabs(double(f.ao.data[i]) - double(d.ao.data[i]));
      within += e <= 2.0 / 255.0;
      maxAbs = std::max(maxAbs, e);
    }
    EXPECT_GE(double(within) / double(f.ao.data.size()), 0.999) << "max " << maxAbs * 255 << "/255";
    EXPECT_TRUE(allFinite(f.ao));
  }
}

// The slices' weights integrate the cosine-weighted hemisphere as reference (d) does: over a half
// turn of screen angles, the mean of L (G(hi) - G(lo)) times the azimuth rate d(psi)/d(phi) is 1
// for any normal facing the eye, at the image's corners too and with non-square pixels. Without the
// rate (uniform screen angles taken as uniform azimuths about V) the mean is off the image centre.
TEST(VisibilityEstimator, SliceWeightsIntegrateTheHemisphere) {
  using cpu::detail::Block;
  using cpu::detail::Vec3;
  struct Lens {
    const char* name;
    double ax, ay;  // proj_info.xy: 90 degrees across 1280 pixels; the second with 1.3:1 pixels
  };
  const Lens lenses[] = {{"square pixels", -1.0 / 640.0, -1.0 / 640.0}, {"1.3:1 pixels", -1.0 / 640.0, -1.3 / 640.0}};
  const double pixels[][2] = {{640.5, 360.5}, {0.5, 0.5}, {1279.5, 200.5}, {900.5, 719.5}};
  constexpr int kAngles = 4096;
  for (const Lens& lens : lenses) {
    gen::SaoParams p{};
    p.proj_info = {float(lens.ax), float(lens.ay), float(-lens.ax * 640.0), float(-lens.ay * 360.0)};
    const Block<double> P(p);
    for (const auto& px : pixels) {
      const Vec3<double> C = cpu::detail::position(px[0], px[1], -5.0, P);
      const Vec3<double> V = cpu::detail::normalize(Vec3<double>{-C.x, -C.y, -C.z});
      // The normal: V itself (every slice weighs 1, with or without the rate), and tilted from V by
      // 60 and 80 degrees (t1, t2: unit, perpendicular to V).
      const Vec3<double> t1 = cpu::detail::normalize(cross(V, Vec3<double>{0, 1, 0}));
      const Vec3<double> t2 = cpu::detail::normalize(t1 - cpu::detail::scale(cross(V, t1), 1.5));
      const double c80 = std::cos(80.0 * 3.14159265358979323846 / 180.0), s80 = std::sqrt(1.0 - c80 * c80);
      const auto tilted = [&](const Vec3<double>& t, double c, double s) {
        return Vec3<double>{c * V.x + s * t.x, c * V.y + s * t.y, c * V.z + s * t.z};
      };
      const Vec3<double> normals[] = {V, tilted(t1, 0.5, std::sqrt(0.75)), tilted(t2, c80, s80)};
      const double rateScale = cpu::detail::azimuthRateScale(V, P);
      for (const Vec3<double>& n : normals) {
        double withRate = 0, withoutRate = 0;
        for (int k = 0; k < kAngles; ++k) {
          const double phi = 3.14159265358979323846 * (k + 0.5) / kAngles;
          const auto sl = cpu::detail::sliceSetup(std::cos(phi), std::sin(phi), V, n, P, rateScale);
          const Vec3<double> D{std::cos(phi) * P.proj_info.x, std::sin(phi) * P.proj_info.y, 0.0};
          const Vec3<double> f = D - cpu::detail::scale(V, cpu::detail::dot(D, V));
          withRate += sl.weight;
          withoutRate += sl.weight / (rateScale / cpu::detail::dot(f, f));
        }
        withRate /= kAngles;
        withoutRate /= kAngles;
        SCOPED_TRACE(std::string(lens.name) + " at (" + std::to_string(px[0]) + ", " + std::to_string(px[1]) + ")");
        EXPECT_NEAR(withRate, 1.0, 1e-6);
        const bool centre = px[0] == 640.5 && px[1] == 360.5 && lens.ax == lens.ay;
        if (!centre && &n != &normals[0]) {
          EXPECT_GT(std::fabs(withoutRate - 1.0), 1e-3) << "the rate should matter off the centre";
        }
      }
    }
  }
}

// sao_mip_source's closed form is the rotated-grid walk it replaces, on every texel of every level
// where both sides are at least 2^m texels; on a narrower side (the walk's clamp) it stays inside
// the image and within 2^m texels of the texel's own corner.
TEST(VisibilityEstimator, MipSourceClosedFormIsTheWalk) {
  const int sizes[][2] = {{640, 360}, {641, 359}, {129, 1000}, {128, 128}, {3, 700}, {1, 1}, {1280, 720}};
  std::size_t checked = 0, clamped = 0;
  for (const auto& sz : sizes) {
    const int w0 = sz[0], h0 = sz[1];
    for (int m = 0; m < gen::SAO_MAX_MIP_LEVELS; ++m) {
      const int w = std::max(w0 >> m, 1), h = std::max(h0 >> m, 1);
      const bool exact = w0 >= (1 << m) && h0 >= (1 << m);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          int cx = x, cy = y, wx = x, wy = y;
          cpu::detail::mipSource(cx, cy, m, w0, h0);
          cpu::detail::mipSourceWalk(wx, wy, m, w0, h0);
          const std::string where = std::to_string(w0) + "x" + std::to_string(h0) + " level " + std::to_string(m) +
                                    " texel " + std::to_string(x) + "," + std::to_string(y);
          if (exact) {
            ASSERT_EQ(cx, wx) << where;
            ASSERT_EQ(cy, wy) << where;
            ++checked;
          } else {
            ASSERT_TRUE(cx >= 0 && cx < w0 && cy >= 0 && cy < h0) << where;
            ASSERT_TRUE(cx >= std::min(x << m, w0 - 1) && cx < (x + 1) << m) << where;
            ASSERT_TRUE(cy >= std::min(y << m, h0 - 1) && cy < (y + 1) << m) << where;
            ++clamped;
          }
        }
    }
  }
  EXPECT_GT(clamped, std::size_t(100));
  EXPECT_GT(checked, std::size_t(1000000));
}

}  // namespace
}  // namespace sao::test
