// Reference (c), the converged screen-space estimator (raytrace::convergedEstimator), against
// closed forms computed from the analytic geometry, never from a depth buffer:
//  - an open plane, any orientation, perspective: every tap lies on the plane, so v.n = 0 and the
//    bias z_C*beta < 0 leaves every term 0: A = 1 exactly;
//  - a 90-degree crease: the same estimator's expectation by another method, a sum over every texel
//    of the disk with weights integrated per texel (the spiral's density 1/(2 pi r' rho), cut by the
//    disk, over the strip of offsets that int() truncates to that texel) and terms from ray-plane
//    intersections at the texel centres.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "sao/raytrace/converged.h"

namespace sao {
namespace {

constexpr std::uint32_t kGuard = 24;  // beyond every projected radius below: no tap is clamped

// Planes n.p = c in camera space; the camera sits where every n.p < c (in front of each), so a
// view ray leaves that region through the first plane it meets.
struct Plane {
  glm::dvec3 n;
  double c;
};

struct Scene {
  Camera camera;
  std::vector<Plane> planes;
};

// Camera-space direction (z = -1) through input texel coordinate (x, y) (viewport + guard band).
glm::dvec3 rayThrough(const Camera& cam, double x, double y) {
  const double W = cam.width, H = cam.height, g = cam.guardBand;
  const double ndcX = 2.0 * (x - g) / W - 1.0, ndcY = 2.0 * (y - g) / H - 1.0;
  return {ndcX / cam.projection[0], ndcY / cam.projection[5], -1.0};
}

// The nearest hit along the ray through (x, y) and the plane it is on.
std::optional<std::pair<glm::dvec3, int>> hit(const Scene& s, double x, double y) {
  const glm::dvec3 d = rayThrough(s.camera, x, y);
  std::optional<std::pair<glm::dvec3, int>> best;
  double tBest = INFINITY;
  for (int i = 0; i < int(s.planes.size()); ++i) {
    const double nd = glm::dot(s.planes[i].n, d);
    if (nd <= 0) continue;  // moving away from the plane (or along it)
    const double t = s.planes[i].c / nd;
    if (t > 0 && t < tBest) tBest = t, best = std::pair{t * d, i};
  }
  return best;
}

// The depth input, D32F reversed-Z (the camera's own convention) or camera-space LinearZ.
DepthImage depthOf(const Scene& s, DepthFormat format) {
  const Camera& cam = s.camera;
  DepthImage d;
  d.extent = {cam.width + 2 * cam.guardBand, cam.height + 2 * cam.guardBand};
  d.format = format;
  for (std::uint32_t y = 0; y < d.extent.height; ++y)
    for (std::uint32_t x = 0; x < d.extent.width; ++x) {
      const auto h = hit(s, x + 0.5, y + 0.5);
      const double z = h ? h->first.z : 0.0;
      double v = z;  // LinearZ: +0.0 is sky
      if (format != DepthFormat::LinearZ)  // window depth = clip z / clip w; sky = the clear value 0
        v = h ? (cam.projection[10] * z + cam.projection[14]) / -z : 0.0;
      d.texels.push_back(encodeDepth(format, v));
    }
  return d;
}

Camera camera(std::uint32_t w, std::uint32_t h) {
  Camera c = perspectiveCamera(1.0, w, h, 0.1, INFINITY, ClipDepth::ZeroToOne, true);
  c.guardBand = kGuard;
  return c;
}

// World planes through the origin seen from `eye`, as camera-space planes.
Scene lookAt(glm::dvec3 eye, glm::dvec3 target, std::vector<glm::dvec3> worldNormals, Camera cam) {
  const glm::dmat4 view = glm::lookAt(eye, target, glm::dvec3(0, 1, 0));
  Scene s{cam, {}};
  for (const glm::dvec3& nw : worldNormals) {
    // Solid behind the plane: the outward normal -nw, so that the eye (nw.eye > 0) has n.p < c.
    const glm::dvec3 n = -glm::dvec3(view * glm::dvec4(nw, 0));
    const glm::dvec3 o = glm::dvec3(view * glm::dvec4(0, 0, 0, 1));
    s.planes.push_back({n, glm::dot(n, o)});
  }
  return s;
}

raytrace::ConvergedOptions fewTaps(std::uint64_t seed = 1) {
  raytrace::ConvergedOptions o;
  o.rings = 32;
  o.taps = 1024;
  o.seed = seed;
  return o;
}

TEST(Converged, OpenPlaneIsUnoccludedAtAnyOrientation) {
  Settings s;
  s.radius = 0.25f;  // r' <= 12 px at the nearest visible point: inside the 24-px guard band
  const glm::dvec3 eyes[] = {{0, 2, 0.01}, {0, 1.5, 4}, {3, 0.3, 1}};  // from above to grazing
  for (const glm::dvec3& eye : eyes)
    for (DepthFormat f : {DepthFormat::D32F, DepthFormat::LinearZ})
      for (bool normals : {false, true}) {
        const Scene scene = lookAt(eye, {0, 0, 0}, {{0, 1, 0}}, camera(40, 24));
        const DepthImage depth = depthOf(scene, f);
        FloatImage n(depth.extent, 4, 0.0f);
        for (std::uint32_t y = 0; y < depth.extent.height; ++y)
          for (std::uint32_t x = 0; x < depth.extent.width; ++x)
            for (int c = 0; c < 3; ++c) n.at(x, y, c) = float(-scene.planes[0].n[c]);
        FloatImage ao;
        ASSERT_TRUE(raytrace::convergedEstimator(s, scene.camera, {&depth, nullptr, normals ? &n : nullptr},
                                                 fewTaps(), ao)
                        .ok());
        std::size_t geometry = 0;
        for (std::uint32_t y = 0; y < ao.extent.height; ++y)
          for (std::uint32_t x = 0; x < ao.extent.width; ++x) {
            EXPECT_NEAR(ao.at(x, y), 1.0, 1e-6) << "eye " << eye.y << " pixel " << x << "," << y;
            geometry += hit(scene, x + kGuard + 0.5, y + kGuard + 0.5).has_value();
          }
        EXPECT_GT(geometry, ao.data.size() / 3) << "the plane must fill much of the view";
      }
}

// Sum over texel offsets d of w(d) term(d), w(d) = (1/(2 pi r')) Integral of 1/rho over the offsets
// that int() truncates to d (d_i > 0: [d_i, d_i + 1); d_i < 0: (d_i - 1, d_i]; d_i = 0: (-1, 1)),
// within rho <= r'. Each strip integrated with kSub x kSub midpoints per unit square.
double expectedTerm(const Scene& s, int cx, int cy, glm::dvec3 C, glm::dvec3 n, double rPx, const Settings& st) {
  constexpr int kSub = 12;
  const double r = st.radius, eps = st.epsilon;
  const int reach = int(std::ceil(rPx)) + 1;
  double sum = 0;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx) {
      if (dx == 0 && dy == 0) continue;  // v = 0: the term is max(0, z_C beta) / eps = 0
      const auto h = hit(s, cx + dx + 0.5, cy + dy + 0.5);
      if (!h) continue;
      const glm::dvec3 v = h->first - C;
      const double vv = glm::dot(v, v);
      if (vv > r * r) continue;
      const double term = std::max(0.0, glm::dot(v, n) + C.z * st.bias) / (vv + eps);
      if (term == 0) continue;
      auto lo = [](int d) { return d > 0 ? double(d) : d < 0 ? d - 1.0 : -1.0; };
      auto hi = [](int d) { return d > 0 ? d + 1.0 : d < 0 ? double(d) : 1.0; };
      const int nx = dx == 0 ? 2 * kSub : kSub, ny = dy == 0 ? 2 * kSub : kSub;
      const double hx = (hi(dx) - lo(dx)) / nx, hy = (hi(dy) - lo(dy)) / ny;
      double w = 0;
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const double x = lo(dx) + (i + 0.5) * hx, y = lo(dy) + (j + 0.5) * hy;
          const double rho = std::hypot(x, y);
          if (rho <= rPx) w += hx * hy / rho;
        }
      sum += w * term;
    }
  return sum / (2.0 * std::numbers::pi * rPx);
}

TEST(Converged, CreaseMatchesTheTexelSumOfTheSameEstimator) {
  // Floor and wall meeting at 90 degrees along z, seen from the corner view the truth tests use.
  const Scene scene = lookAt({2.0, 1.5, 1.0}, {0, 0, 0}, {{0, 1, 0}, {1, 0, 0}}, camera(48, 32));
  Settings st;
  st.radius = 0.8f;  // r' of 6-16 px here, inside the 24-px guard band
  const DepthImage depth = depthOf(scene, DepthFormat::D32F);
  FloatImage c1, c2;
  raytrace::ConvergedOptions o1, o2;  // the bench's 4096 taps, two seeds
  o2.seed = 2;
  ASSERT_TRUE(raytrace::convergedEstimator(st, scene.camera, {&depth}, o1, c1).ok());
  ASSERT_TRUE(raytrace::convergedEstimator(st, scene.camera, {&depth}, o2, c2).ok());

  const Camera& cam = scene.camera;
  const double projScale = 0.5 * cam.height * cam.projection[5];
  double noise2 = 0, error2 = 0, bias = 0, minA = 1;
  std::size_t count = 0;
  for (std::uint32_t y = 0; y < cam.height; ++y)
    for (std::uint32_t x = 0; x < cam.width; ++x) {
      const int cx = int(x + kGuard), cy = int(y + kGuard);
      const auto h = hit(scene, cx + 0.5, cy + 0.5);
      ASSERT_TRUE(h.has_value());
      // Only where the normal rebuilt from depth is this plane's: all four neighbours on it.
      bool onePlane = true;
      for (auto [ox, oy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        onePlane = onePlane && hit(scene, cx + ox + 0.5, cy + oy + 0.5)->second == h->second;
      if (!onePlane) continue;
      const glm::dvec3 n = -scene.planes[h->second].n;  // facing the camera
      const double rPx = st.radius * projScale / -h->first.z;
      ASSERT_LT(rPx + 2, double(kGuard));
      const double expected = std::pow(std::max(0.0, 1.0 - 2.0 * st.intensity * st.radius *
                                                                expectedTerm(scene, cx, cy, h->first, n, rPx, st)),
                                       double(st.contrast));
      const double d1 = c1.at(x, y) - expected, d2 = c2.at(x, y) - expected;
      noise2 += 0.5 * (c1.at(x, y) - c2.at(x, y)) * (c1.at(x, y) - c2.at(x, y));
      error2 += 0.5 * (d1 * d1 + d2 * d2);
      bias += 0.5 * (d1 + d2);
      minA = std::min(minA, expected);
      ++count;
    }
  ASSERT_GT(count, cam.width * cam.height / 2);
  // (c)'s own noise: E[(c1 - c2)^2 / 2] is its per-pixel variance, averaged over the pixels.
  const double noise = std::sqrt(noise2 / count), error = std::sqrt(error2 / count);
  bias /= count;
  EXPECT_LT(minA, 0.6) << "the crease must occlude, or the comparison says nothing";
  EXPECT_LT(noise, 3e-3) << "4096 taps: about 1e-3";
  // Unbiased, (c) differs from the texel sum by its noise alone: E[(c - sum)^2] = noise^2 +
  // systematic^2. The sum's own error is its 12x12 midpoint weights (~1e-3 relative on the
  // disk-edge texels, < 3e-4 of A here) and D32F z (~1e-7). The RMS of (c) - sum may exceed the
  // noise by 20% (over ~1500 pixels the two RMS estimates scatter by a few %) plus that 3e-4; a
  // wrong weight or term (say the texel centre off by half a pixel, or no truncation) adds 1e-2.
  EXPECT_LT(error, 1.2 * noise + 3e-4) << "noise " << noise;
  EXPECT_LT(std::fabs(bias), 4 * noise / std::sqrt(double(count)) + 3e-4) << "noise " << noise << " error " << error;
}

// TWO_LAYER takes the larger term of the two layers: a floor as the first layer and the wall
// behind it as the second occlude every floor pixel exactly as the crease (floor and wall in one
// layer) does. Floor taps give 0 either way (v.n = 0), the wall behind the floor lies below it
// (v.n < 0), and the wall where it is visible is the same point; same seed, same taps.
TEST(Converged, SecondLayerOccludesAsTheFirst) {
  const glm::dvec3 eye{2.0, 1.5, 1.0};
  const Scene crease = lookAt(eye, {0, 0, 0}, {{0, 1, 0}, {1, 0, 0}}, camera(48, 32));
  const Scene floor = lookAt(eye, {0, 0, 0}, {{0, 1, 0}}, camera(48, 32));
  const Scene wall = lookAt(eye, {0, 0, 0}, {{1, 0, 0}}, camera(48, 32));
  const DepthImage dc = depthOf(crease, DepthFormat::D32F), df = depthOf(floor, DepthFormat::D32F),
                   dw = depthOf(wall, DepthFormat::D32F);
  Settings st;
  st.radius = 0.8f;
  FloatImage one, two, floorOnly;
  ASSERT_TRUE(raytrace::convergedEstimator(st, crease.camera, {&dc}, fewTaps(), one).ok());
  ASSERT_TRUE(raytrace::convergedEstimator(st, crease.camera, {&df, &dw}, fewTaps(), two).ok());
  ASSERT_TRUE(raytrace::convergedEstimator(st, crease.camera, {&df}, fewTaps(), floorOnly).ok());
  std::size_t compared = 0;
  double minA = 1;
  for (std::uint32_t y = 0; y < one.extent.height; ++y)
    for (std::uint32_t x = 0; x < one.extent.width; ++x) {
      EXPECT_EQ(floorOnly.at(x, y), 1.0f);
      const double cx = x + kGuard + 0.5, cy = y + kGuard + 0.5;
      bool floorAround = true;  // the rebuilt normal is the floor's in both
      for (auto [ox, oy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        floorAround = floorAround && hit(crease, cx + ox, cy + oy)->second == 0;
      if (!floorAround) continue;
      EXPECT_NEAR(two.at(x, y), one.at(x, y), 1e-6) << x << "," << y;
      minA = std::min(minA, double(two.at(x, y)));
      ++compared;
    }
  EXPECT_GT(compared, one.data.size() / 4);
  EXPECT_LT(minA, 0.6) << "the second layer must occlude";
}

TEST(Converged, RejectsBadInput) {
  const Scene scene = lookAt({0, 2, 0.01}, {0, 0, 0}, {{0, 1, 0}}, camera(8, 6));
  const DepthImage depth = depthOf(scene, DepthFormat::D32F);
  Settings st;
  FloatImage ao;
  EXPECT_EQ(raytrace::convergedEstimator(st, scene.camera, {}, fewTaps(), ao).code, StatusCode::InvalidInput);
  DepthImage small = depth;
  small.extent.width -= 1;
  small.texels.resize(std::size_t(small.extent.width) * small.extent.height);
  const Status s = raytrace::convergedEstimator(st, scene.camera, {&small}, fewTaps(), ao);
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_NE(s.message.find("guard band"), std::string::npos) << s.message;
  DepthImage linear = depth;
  linear.format = DepthFormat::LinearZ;
  EXPECT_EQ(raytrace::convergedEstimator(st, scene.camera, {&depth, &linear}, fewTaps(), ao).code,
            StatusCode::InvalidInput);
  FloatImage twoChannels(depth.extent, 2);
  EXPECT_EQ(raytrace::convergedEstimator(st, scene.camera, {&depth, nullptr, &twoChannels}, fewTaps(), ao).code,
            StatusCode::InvalidInput);
  raytrace::ConvergedOptions none = fewTaps();
  none.taps = 0;
  EXPECT_EQ(raytrace::convergedEstimator(st, scene.camera, {&depth}, none, ao).code, StatusCode::InvalidInput);
  st.radius = -1;
  EXPECT_FALSE(raytrace::convergedEstimator(st, scene.camera, {&depth}, fewTaps(), ao).ok());
  EXPECT_TRUE(ao.data.empty());
}

}  // namespace
}  // namespace sao
