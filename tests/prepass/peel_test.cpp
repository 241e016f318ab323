// The second layer (depth peeling with a minimum separation) on sphere-plane against a ray cast
// continued past the first hit: behind the sphere the floor (back faces culled, the default) or
// the sphere's own far side (no culling); sky behind the floor and behind the sky.
#include <cmath>
#include <cstdio>
#include <ostream>

#include "prepass_support.h"

namespace sao::prepasstest {
namespace {

// +1 when RayScene::Hit::normal is the counter-clockwise (right-hand) normal of the triangle as
// wound, -1 when it is the opposite: measured on one triangle rather than assumed.
double embreeWindingSign() {
  scenes::Mesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // counter-clockwise seen from +z
  tri.indices = {0, 1, 2};
  std::unique_ptr<raytrace::RayScene> rs;
  if (!raytrace::RayScene::create(tri, rs)) return 0;
  const auto h = rs->intersect({0.2, 0.2, 1.0}, {0, 0, -1}, 10.0);
  return h.hit ? (h.normal.z > 0 ? 1.0 : -1.0) : 0.0;
}

struct PeelTruth {
  bool first = false, second = false;
  double z1 = 0, z2 = 0;  // camera space
  double firstWorldY = 0;
};

// The ray through texel (x, y) as castPrimary casts it; the first hit nearer than the far plane and
// beyond the near plane, then the nearest hit more than `minSep` behind it, skipping back faces when
// `cull` is set.
PeelTruth peelTruth(const raytrace::RayScene& rs, const scenes::View& view, const Camera& c, std::uint32_t x,
                    std::uint32_t y, double minSep, bool cull, double windingSign) {
  PeelTruth t;
  const double ndcX = 2.0 * (double(x) - c.guardBand + 0.5) / c.width - 1.0;
  const double ndcY = 2.0 * (double(y) - c.guardBand + 0.5) / c.height - 1.0;
  const glm::dvec3 dirCam((ndcX + c.projection[8]) / c.projection[0], (ndcY + c.projection[9]) / c.projection[5], -1.0);
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(view));
  const glm::dvec3 dir = glm::dvec3(toWorld * glm::dvec4(dirCam, 0.0));
  const auto h1 = rs.intersect(view.eye, dir, 1e30);
  if (!h1.hit || h1.t < view.nearDistance) return t;
  t.first = true;
  t.z1 = -h1.t;
  t.firstWorldY = (view.eye + dir * h1.t).y;
  double from = h1.t;
  for (int step = 0; step < 64; ++step) {
    const double start = from + 1e-5 * std::max(1.0, from);
    const auto h = rs.intersect(view.eye + dir * start, dir, 1e30);
    if (!h.hit) return t;
    const double tt = start + h.t;
    from = tt;
    if (!(tt - h1.t > minSep)) continue;
    if (cull && glm::dot(windingSign * h.normal, dir) > 0) continue;  // faces away from the camera
    t.second = true;
    t.z2 = -tt;
    return t;
  }
  return t;
}

struct Case {
  std::string backend;
  bool cull;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.backend << (c.cull ? " culling" : " no culling"); }

class Peeling : public PrepassTest, public ::testing::WithParamInterface<Case> {};

TEST_P(Peeling, SpherePlaneSecondLayer) {
  const Case& c = GetParam();
  prepass::Prepass& prepass = backend(c.backend);
  const double sign = embreeWindingSign();
  ASSERT_NE(sign, 0.0);
  const LoadedScene& ls = loadScene("sphere-plane");
  const scenes::View& view = ls.scene.views.front();
  struct Setup {
    DepthFormat format;
    bool reversed;
    double far;
    double relTolerance;  // |z2 raster - z2 ray| / |z2| allowed on agreeing pixels
  };
  for (const Setup& setup : {Setup{DepthFormat::D32F, true, INFINITY, 1e-5}, Setup{DepthFormat::D24, false, 1000.0, 1e-3},
                             Setup{DepthFormat::D16, true, INFINITY, 1e-2}}) {
    SCOPED_TRACE(toString(setup.format));
    const Camera camera = scenes::makeCamera(view, 160, 90, setup.far, ClipDepth::ZeroToOne, setup.reversed, 8);
    prepass::PrepassOptions options;
    options.format = setup.format;
    options.secondLayer = true;
    options.minSeparation = 0.1;
    options.cullBackFacesInSecondLayer = c.cull;
    prepass::PrepassResult r;
    const Status s = prepass.render(ls.scene.mesh, view, camera, options, r);
    ASSERT_TRUE(s) << s.message;
    ASSERT_EQ(r.depth2.extent, r.depth.extent);
    ASSERT_EQ(r.depth2.format, setup.format);
    ASSERT_EQ(r.position2.extent, r.depth.extent);
    DepthModel model;
    ASSERT_TRUE(analyze(camera, model));
    const std::uint32_t clear = encodeDepth(setup.format, setup.reversed ? 0.0 : 1.0);
    std::size_t sphere = 0, sphereAgree = 0, sphereBoth = 0, sphereZ = 0, behindAsExpected = 0, floor = 0, floorAgree = 0,
                skyFirst = 0, skyBad = 0, encodingBad = 0;
    const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(view));
    double worstRel = 0;
    for (std::uint32_t y = 0; y < r.depth.extent.height; ++y)
      for (std::uint32_t x = 0; x < r.depth.extent.width; ++x) {
        const std::size_t i = std::size_t(y) * r.depth.extent.width + x;
        const bool raster1 = r.position.data[4 * i + 3] != 0, raster2 = r.position2.data[4 * i + 3] != 0;
        // The second layer's depth and its position tell the same story.
        if (raster2 != (r.depth2.texels[i] != clear)) ++encodingBad;
        if (raster2) {
          const double zd = linearZ(model, camera.kind, r.depth2.value(x, y));
          if (std::abs(zd - r.position2.data[4 * i + 2]) > 1e-2 * std::abs(zd) + 1e-3) ++encodingBad;
        }
        const PeelTruth t = peelTruth(*ls.rays, view, camera, x, y, options.minSeparation, c.cull, sign);
        if (!raster1) {  // nothing in front: nothing behind
          ++skyFirst;
          skyBad += raster2 || r.depth2.texels[i] != clear;
          continue;
        }
        if (!t.first) continue;
        if (t.firstWorldY > 1e-3) {  // the first layer is the sphere
          ++sphere;
          if (raster2 == t.second) ++sphereAgree;
          if (raster2) {
            // Behind the sphere: the floor (y = 0) with culling, the sphere's far side without.
            const glm::dvec3 p2 = glm::dvec3(toWorld * glm::dvec4(r.position2.data[4 * i], r.position2.data[4 * i + 1],
                                                                  r.position2.data[4 * i + 2], 1.0));
            behindAsExpected += c.cull ? std::abs(p2.y) < 1e-3 : std::abs(glm::length(p2 - glm::dvec3(0, 1, 0)) - 1.0) < 2e-3;
          }
          if (raster2 && t.second) {
            ++sphereBoth;
            const double rel = std::abs(double(r.position2.data[4 * i + 2]) - t.z2) / std::abs(t.z2);
            worstRel = std::max(worstRel, rel);
            sphereZ += rel <= setup.relTolerance;
          }
        } else {  // the first layer is the floor
          ++floor;
          floorAgree += raster2 == t.second;
        }
      }
    std::printf("[peel %s cull %d %s] sphere pixels %zu: layer-2 coverage agrees on %.2f%%, z within %.0e on %zu "
                "of %zu (worst rel %.2e), on the %s: %zu; floor pixels %zu: agree %.2f%%; sky %zu (bad %zu)\n",
                c.backend.c_str(), int(c.cull), toString(setup.format), sphere, 100.0 * double(sphereAgree) / double(sphere),
                setup.relTolerance, sphereZ, sphereBoth, worstRel, c.cull ? "floor" : "sphere's far side", behindAsExpected, floor, 100.0 * double(floorAgree) / double(floor), skyFirst, skyBad);
    EXPECT_EQ(encodingBad, 0u);
    EXPECT_EQ(skyBad, 0u);
    EXPECT_GT(sphere, 1000u);
    EXPECT_GT(skyFirst, 100u);
    // Disagreement only where a surface lies within rounding of the separation or on an edge.
    EXPECT_GE(double(sphereAgree), 0.99 * double(sphere));
    EXPECT_GE(double(floorAgree), 0.99 * double(floor));
    EXPECT_GE(double(sphereZ), 0.99 * double(sphereBoth));
    EXPECT_GT(sphereBoth, sphere / 2);
    EXPECT_GE(double(behindAsExpected), 0.99 * double(sphereBoth));
  }
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const auto& b : backendNames())
    for (bool cull : {true, false}) out.push_back({b, cull});
  return out;
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Peeling);  // a build without GL and Vulkan
INSTANTIATE_TEST_SUITE_P(Backends, Peeling, ::testing::ValuesIn(cases()), [](const auto& info) {
  return info.param.backend + (info.param.cull ? "_cull" : "_nocull");
});

}  // namespace
}  // namespace sao::prepasstest
