// The visibility estimator (setting estimator = 1, variant ESTIMATOR; effect/include/sao_visibility.glsl,
// effect/cpu/sao_visibility.h) on the CPU reference: the setting selects the variant and fills the
// block; an open plane is exactly 1 at every pixel in double (no sample of a plane lies in front of
// it: the slab starts behind the stored depth); occluders occlude, and more with a thicker slab;
// float mimics the GPU within the agreement bounds of double; the estimator does not change
// estimator 0's block.
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
