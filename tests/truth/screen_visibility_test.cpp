// Reference (d), converged screen-space visibility (raytrace::screenVisibility), against closed
// forms computed from the analytic geometry, never from a depth buffer:
//  - an open plane at any tilt, perspective and orthographic: every sample lies on the tangent plane
//    and the tolerance puts its slab strictly below it: V = 1 exactly;
//  - a 90-degree crease (floor and wall, thickness unbounded), orthographic: a floor point at
//    distance x from the wall sees the wall within r over the cosine-weighted fraction
//    (acos(a) - a sqrt(1 - a^2)) / pi, a = min(1, x / r) (Malley: the directions are uniform points of
//    the unit disk, and those the wall stops are the disk's segment beyond a);
// and its properties: deterministic (seed, threads), the thickness matters (a thin slat before a
// wall), the second layer occludes, bad input is refused.
// The crease is orthographic because (d) marches h <= r' (as the effect does): in perspective a
// point within r of C but nearer the eye projects beyond r' and is not seen, so the closed form
// holds only where no such point blocks. The analytic sphere above a plane (cos(theta) (R/D)^2
// occluded) does not fit the depth-buffer model: a constant T cannot end every sample's slab at the
// sphere's back, and the part behind it (extended along the view rays) blocks directions that pass
// under the sphere from the plane's points unless the view looks along C -> sphere, which hides
// the plane's top; it stays a test of reference (a) (raytrace_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include <glm/glm.hpp>

#include "sao/raytrace/screen_visibility.h"
#include "traced_view.h"

namespace sao::truthtest {
namespace {

// Pixels spanned by one view unit at the pixel's depth: the effect's r' / r (eq. 5).
double pixelsPerUnit(const Camera& camera, double z) {
  const double projScale = camera.kind == ProjectionKind::Orthographic ? 0.5 * camera.height * camera.projection[5]
                                                                       : 0.5 * camera.height * camera.projection[5] / -z;
  return projScale;
}

raytrace::ScreenVisibilityOptions fewSlices(std::uint32_t slices = 16) {
  raytrace::ScreenVisibilityOptions o;
  o.slices = slices;
  o.threads = 2;
  return o;
}

// Camera-space position and world position of AO pixel (x, y) of a traced view (w = 0: sky).
glm::dvec4 cameraPosition(const TracedView& v, std::uint32_t x, std::uint32_t y) {
  const std::uint32_t g = v.camera.guardBand;
  const FloatImage& p = v.primary.position;
  return {p.at(x + g, y + g, 0), p.at(x + g, y + g, 1), p.at(x + g, y + g, 2), p.at(x + g, y + g, 3)};
}

scenes::View view(glm::dvec3 eye, glm::dvec3 target, double orthoHeight, const scenes::Mesh& mesh) {
  scenes::View v{"test", eye, target, {0, 1, 0}, 1.0, 0.05};
  if (orthoHeight > 0) {  // the view plane (through the eye) moved back clear of the scene
    v.eye = target + 20.0 * glm::normalize(eye - target);
    v.orthoHeight = orthoHeight;
    scenes::fitOrthoFar(v, mesh);
  }
  return v;
}

TEST(ScreenVisibility, OpenPlaneIsExactlyOneAtAnyTilt) {
  scenes::MeshBuilder b;
  b.box({-400, -0.1, -400}, {400, 0, 400});
  const scenes::Mesh floor = b.build();
  Settings s;
  s.radius = 0.2f;  // r' up to 15 px inside the 16-px guard band from 0.5 m on
  const glm::dvec3 eyes[] = {{0, 2, 0.01}, {0, 1.5, 4}, {3, 0.3, 1}, {2, 0.08, 0.5}};  // from above to grazing
  for (const glm::dvec3& eye : eyes)
    for (double orthoHeight : {0.0, 3.0}) {
      TracedView v;
      traceFirstView({"plane", floor, {view(eye, {0, 0, 0}, orthoHeight, floor)}}, 64, 40, 16, 1.0, v);
      for (bool normals : {false, true}) {
        FloatImage ao;
        const Status st = raytrace::screenVisibility(
            s, v.camera, {&v.primary.depth, nullptr, normals ? &v.primary.normal : nullptr}, fewSlices(), ao);
        ASSERT_TRUE(st.ok()) << st.message;
        std::size_t checked = 0;
        for (std::uint32_t y = 0; y < v.camera.height; ++y)
          for (std::uint32_t x = 0; x < v.camera.width; ++x) {
            const glm::dvec4 p = cameraPosition(v, x, y);
            // Only where every tap reads its own texel: beyond the guard band a clamped texel's
            // depth at the unclamped position is off the plane (the effect's rule, not an error).
            if (p.w == 0 || s.radius * pixelsPerUnit(v.camera, p.z) + 1 > v.camera.guardBand) continue;
            EXPECT_EQ(ao.at(x, y), 1.0f) << "eye " << eye.x << "," << eye.y << "," << eye.z << " ortho " << orthoHeight
                                          << " normals " << normals << " pixel " << x << "," << y;
            ++checked;
          }
        EXPECT_GT(checked, ao.data.size() / 8) << "the plane must fill much of the view: eye " << eye.x << "," << eye.y << " ortho " << orthoHeight;
      }
    }
}

// Malley: the cosine-weighted fraction of directions that a wall at distance x stops within r.
double creaseVisibility(double x, double r) {
  const double a = std::min(1.0, x / r);
  return 1.0 - (std::acos(a) - a * std::sqrt(1.0 - a * a)) / std::numbers::pi;
}

struct CreaseRun {
  double rms = 0, bias = 0, worst = 0, minV = 1;
  std::size_t pixels = 0;
};

// The crease of traced_view.h (floor y = 0, wall x = 0 facing +x) seen orthographically from above
// the floor and in front of the wall: every point within r of a pixel's point projects within r'
// of it (orthographic), so the screen holds all the wall a floor point's rays can reach.
CreaseRun creaseAgainstMalley(std::uint32_t slices, double orthoHeight, const std::string& what) {
  const scenes::Mesh mesh = creaseMesh(0.0).build();
  TracedView v;
  const std::uint32_t rPx = std::uint32_t(std::lround(96 / orthoHeight));  // r = 1 m
  traceFirstView({"crease", mesh, {view({3, 3.5, 1.5}, {0.7, 0, 0}, orthoHeight, mesh)}}, 128, 96, rPx + 4, 1.0, v);
  EXPECT_EQ(v.camera.kind, ProjectionKind::Orthographic);
  Settings s;
  s.radius = 1.0f;  // r' = 32 px: inside the 36-px guard band
  raytrace::ScreenVisibilityOptions o = fewSlices(slices);
  o.thicknessMeters = std::numeric_limits<double>::infinity();
  o.tolerance = 0;  // relative to a depth of ~20 m here (the view plane is 20 m back): it would move the wall
  o.stride = 2;
  FloatImage ao;
  const Status st = raytrace::screenVisibility(s, v.camera, {&v.primary.depth}, o, ao);
  EXPECT_TRUE(st.ok()) << st.message;
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(v.scene.views[0]));
  CreaseRun r;
  double sum2 = 0;
  for (std::uint32_t y = 0; y < v.camera.height; y += 2)
    for (std::uint32_t x = 0; x < v.camera.width; x += 2) {
      // Floor pixels whose 4 neighbours are floor too (the rebuilt normal is the floor's).
      bool floor = true;
      for (auto [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const glm::dvec4 p = cameraPosition(v, x + dx, y + dy);
        floor = floor && p.w != 0 && std::fabs((toWorld * glm::dvec4(glm::dvec3(p), 1.0)).y) < 1e-4;
      }
      if (!floor) continue;
      const glm::dvec3 world = toWorld * glm::dvec4(glm::dvec3(cameraPosition(v, x, y)), 1.0);
      const double expected = creaseVisibility(world.x, s.radius), d = ao.at(x, y) - expected;
      sum2 += d * d;
      r.bias += d;
      r.worst = std::max(r.worst, std::fabs(d));
      r.minV = std::min(r.minV, expected);
      ++r.pixels;
    }
  r.rms = std::sqrt(sum2 / double(std::max<std::size_t>(r.pixels, 1)));
  r.bias /= double(std::max<std::size_t>(r.pixels, 1));
  std::printf("crease (%s): r' %u px, %u slices, %zu pixels: RMS %.5f, mean %.5f, worst %.5f\n", what.c_str(), rPx, slices,
              r.pixels, r.rms, r.bias, r.worst);
  return r;
}

// The bound, per pixel, is the sum of two terms:
//  - pixels: every tap is a texel centre within sqrt(2) px of the ideal point of its slice (int()
//    truncates each axis, the march steps 1 px), so the last sample within r, which ends the
//    wall's blocked range, sits up to sqrt(2)/r' of r off: the cut acts as r(1 + delta) with
//    |delta| <= sqrt(2)/r'. d(occluded)/dr = (2/pi) a sqrt(1 - a^2) / r <= 1/(pi r), so
//    |error| <= sqrt(2)/(pi r'), 0.014 at r' = 32 px. (The low end of the range, the wall's foot
//    on the floor's horizon, carries no cosine weight to first order.)
//  - slices: one jittered sample per stratum of pi/N errs by at most the total variation of the
//    integrand w(psi) o(psi) over N; w <= pi/2 times its mean (1) for any tilt, o in [0, 1] rises
//    and falls once: TV <= pi, |error| <= pi/N (0.049 at 64; measured: 8 slices to 256 move the
//    worst pixel by 0.006 only, the pixel term dominates).
// Over the pixels the pixel term's sign and size vary from slice to slice and pixel to pixel:
// the RMS is at most that of a uniform error on [-b, b], b/sqrt(3). Measured (r' = 32, 64 slices):
// RMS 0.0031, worst 0.0092, mean +0.0011; RMS 0.0052 at r' = 16 and 0.0017 at r' = 64 (~0.1/r').
TEST(ScreenVisibility, CreaseMatchesTheClosedForm) {
  constexpr std::uint32_t kSlices = 64;
  const CreaseRun r = creaseAgainstMalley(kSlices, 3.0, "r' = 32 px");
  const double pixelTerm = std::sqrt(2.0) / (std::numbers::pi * 32), sliceTerm = std::numbers::pi / kSlices;
  ASSERT_GT(r.pixels, 500u);
  EXPECT_LT(r.minV, 0.6) << "the crease must occlude, or the comparison says nothing";
  EXPECT_LT(r.worst, pixelTerm + sliceTerm);
  EXPECT_LT(r.rms, pixelTerm / std::sqrt(3.0));
  EXPECT_LT(std::fabs(r.bias), pixelTerm / std::sqrt(3.0));
}

// The same closed form in perspective, with a 92-degree field of view looking level at the wall,
// on the pixels where it applies: every wall point within r of C (the upper half of a disk of
// radius sqrt(r^2 - x^2) on the wall) projects within r' - 2 px of C (checked on the disk's rim,
// where a projective map takes its extremes), so the march to r' sees all it must. (Without the
// azimuth weight the mean over these pixels (at stride 1) moves from +0.0030 to +0.0045: real, but
// within the pixel term, so this test cannot tell the two apart.)
TEST(ScreenVisibility, PerspectiveCreaseMatchesTheClosedFormWhereItApplies) {
  const scenes::Mesh mesh = creaseMesh(0.0).build();
  const scenes::View level{"level", {3.0, 0.5, 0.4}, {0.0, 0.5, 0.4}, {0, 1, 0}, 1.6, 0.05};
  TracedView v;
  traceFirstView({"crease", mesh, {level}}, 128, 96, 40, 1.0, v);
  Settings s;
  s.radius = 1.0f;
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(level)), toCamera = scenes::viewMatrix(level);
  const Camera& cam = v.camera;
  auto screen = [&](glm::dvec3 pc) {  // camera space -> AO pixel coordinates
    return glm::dvec2((cam.projection[0] * pc.x / -pc.z + 1.0) * 0.5 * cam.width,
                      (cam.projection[5] * pc.y / -pc.z + 1.0) * 0.5 * cam.height);
  };
  {
    raytrace::ScreenVisibilityOptions o = fewSlices(64);
    o.thicknessMeters = std::numeric_limits<double>::infinity();
    o.tolerance = 0;
    o.stride = 2;  // a quarter of the pixels: enough, and a quarter of the time
    FloatImage ao;
    ASSERT_TRUE(raytrace::screenVisibility(s, cam, {&v.primary.depth}, o, ao).ok());
    double sum2 = 0, bias = 0, minV = 1, rMin = 1e9;
    std::size_t n = 0;
    for (std::uint32_t y = 2; y + 1 < cam.height; y += 2)
      for (std::uint32_t x = 2; x + 1 < cam.width; x += 2) {
        bool floor = true;
        for (auto [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const glm::dvec4 p = cameraPosition(v, x + dx, y + dy);
          floor = floor && p.w != 0 && std::fabs((toWorld * glm::dvec4(glm::dvec3(p), 1.0)).y) < 1e-4;
        }
        if (!floor) continue;
        const glm::dvec3 pc = glm::dvec3(cameraPosition(v, x, y));
        const glm::dvec3 world = toWorld * glm::dvec4(pc, 1.0);
        if (world.x >= s.radius) continue;  // nothing to see: V = 1 trivially
        const double rPx = s.radius * pixelsPerUnit(cam, pc.z);
        const double disk = std::sqrt(s.radius * s.radius - world.x * world.x);
        bool inside = true;
        for (int k = 0; k <= 64 && inside; ++k) {
          const double t = std::numbers::pi * k / 64;
          const glm::dvec3 rim = toCamera * glm::dvec4(0.0, disk * std::sin(t), world.z + disk * std::cos(t), 1.0);
          inside = glm::length(screen(rim) - screen(pc)) <= rPx - 2;
        }
        if (!inside) continue;
        const double d = ao.at(x, y) - creaseVisibility(world.x, s.radius);
        sum2 += d * d, bias += d, ++n;
        minV = std::min(minV, creaseVisibility(world.x, s.radius));
        rMin = std::min(rMin, rPx);
      }
    ASSERT_GT(n, 50u);
    const double rms = std::sqrt(sum2 / n), pixelTerm = std::sqrt(2.0) / (std::numbers::pi * rMin);
    bias /= n;
    std::printf("perspective crease: %zu pixels (r' >= %.0f px): RMS %.4f, mean %+.4f\n", n, rMin, rms, bias);
    EXPECT_LT(minV, 0.9) << "the crease must occlude";
    EXPECT_LT(rms, pixelTerm / std::sqrt(3.0));
    EXPECT_LT(std::fabs(bias), pixelTerm / std::sqrt(3.0));
  }
}

// A pure function of its inputs and options: the same seed gives the same bits on any thread
// count; another seed moves the slices; a stride evaluates its pixels exactly as stride 1 does.
TEST(ScreenVisibility, DeterministicAndStrided) {
  TracedView v;
  traceCrease(1.0, v);
  Settings s;
  s.radius = 0.8f;
  auto run = [&](std::uint64_t seed, unsigned threads, std::uint32_t stride) {
    raytrace::ScreenVisibilityOptions o = fewSlices();
    o.seed = seed;
    o.threads = threads;
    o.stride = stride;
    FloatImage ao;
    EXPECT_TRUE(raytrace::screenVisibility(s, v.camera, {&v.primary.depth}, o, ao).ok());
    return ao;
  };
  const FloatImage a = run(1, 1, 1), b = run(1, 3, 1), c = run(1, 1, 1), d = run(2, 2, 1), e = run(1, 2, 3);
  ASSERT_EQ(a.data.size(), std::size_t(v.camera.width) * v.camera.height);
  EXPECT_EQ(a.data, b.data);
  EXPECT_EQ(a.data, c.data);
  EXPECT_NE(a.data, d.data);
  double minV = 1;
  for (std::uint32_t y = 0; y < v.camera.height; ++y)
    for (std::uint32_t x = 0; x < v.camera.width; ++x) {
      minV = std::min(minV, double(a.at(x, y)));
      if (x % 3 == 0 && y % 3 == 0)
        EXPECT_EQ(e.at(x, y), a.at(x, y)) << x << "," << y;
      else
        EXPECT_TRUE(std::isnan(e.at(x, y))) << x << "," << y;
    }
  EXPECT_LT(minV, 0.8) << "the crease must occlude, or the comparison says nothing";
}

// Thickness: a thin slat (10 cm deep) 0.4 m before a wall. With T = +infinity its slab runs on
// through the wall, and the wall beside and behind it loses every direction that passes behind
// the slat (what a pure heightfield assumes); with T = 0.2 m the slab ends short of the wall. The
// ray-traced reference (a) on the same view sides with the finite thickness.
// A 10 cm slat (10 cm deep) 0.4 m before a wall, seen from 4 m at 96x64.
void traceSlat(TracedView& v) {
  scenes::MeshBuilder b;
  b.box({-10, -10, -0.2}, {10, 10, 0});
  b.box({-0.05, -10, 0.4}, {0.05, 10, 0.5});
  const scenes::Mesh mesh = b.build();
  traceFirstView({"slat", mesh, {view({0.6, 0, 4}, {0, 0, 0}, 0, mesh)}}, 96, 64, 16, 1.0, v);
}

TEST(ScreenVisibility, ThicknessDecidesWhatHidesBehindAThinObject) {
  TracedView v;
  traceSlat(v);
  Settings s;  // radius 1 m: r' about 15 px on the wall
  FloatImage thin, infinite, reference;
  raytrace::ScreenVisibilityOptions o = fewSlices(32);
  o.thicknessMeters = double(0.2f);  // the float setting's value, compared below
  ASSERT_TRUE(raytrace::screenVisibility(s, v.camera, {&v.primary.depth}, o, thin).ok());
  o.thicknessMeters = std::numeric_limits<double>::infinity();
  ASSERT_TRUE(raytrace::screenVisibility(s, v.camera, {&v.primary.depth}, o, infinite).ok());
  // Unset, T and tol are the settings' (the visibility estimator's): thickness 0.2 m gives the same.
  Settings fromSettings = s;
  fromSettings.thickness = 0.2f;
  FloatImage settingsThin;
  o.thicknessMeters.reset();
  ASSERT_TRUE(raytrace::screenVisibility(fromSettings, v.camera, {&v.primary.depth}, o, settingsThin).ok());
  EXPECT_EQ(settingsThin.data, thin.data);
  fromSettings.depth_tolerance = 0.05f;  // a tolerance of 5 % of the depth moves the slabs: another result
  ASSERT_TRUE(raytrace::screenVisibility(fromSettings, v.camera, {&v.primary.depth}, o, settingsThin).ok());
  EXPECT_NE(settingsThin.data, thin.data);
  raytrace::ReferenceOptions ro;
  ro.rays = 256;
  ASSERT_TRUE(raytrace::referenceAmbientOcclusion(*v.rays, v.camera, v.primary, v.scene.views[0], ro, reference).ok());
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(v.scene.views[0]));
  double meanThin = 0, meanInfinite = 0, errThin = 0, errInfinite = 0;
  std::size_t n = 0;
  for (std::uint32_t y = 0; y < v.camera.height; ++y)
    for (std::uint32_t x = 0; x < v.camera.width; ++x) {
      const glm::dvec4 p = cameraPosition(v, x, y);
      const glm::dvec3 w = toWorld * glm::dvec4(glm::dvec3(p), 1.0);
      if (p.w == 0 || std::fabs(w.z) > 1e-4 || std::fabs(w.x) > 0.8) continue;  // the wall near the slat
      meanThin += thin.at(x, y);
      meanInfinite += infinite.at(x, y);
      errThin += std::pow(thin.at(x, y) - reference.at(x, y), 2);
      errInfinite += std::pow(infinite.at(x, y) - reference.at(x, y), 2);
      ++n;
    }
  ASSERT_GT(n, 200u);
  meanThin /= n, meanInfinite /= n;
  errThin = std::sqrt(errThin / n), errInfinite = std::sqrt(errInfinite / n);
  std::printf("wall near the slat, %zu pixels: mean V %.4f (T 0.2 m), %.4f (T inf); RMSE vs (a) %.4f, %.4f\n", n,
              meanThin, meanInfinite, errThin, errInfinite);
  EXPECT_LT(meanThin, 0.99) << "the slat itself occludes the wall";
  EXPECT_GT(meanThin - meanInfinite, 0.05);
  EXPECT_LT(errThin, 0.5 * errInfinite);
}

// TWO_LAYER: a floor as the first layer and a wall (running on below the floor) as the second see
// on the floor exactly what the crease (floor and wall in one layer) does: the wall's visible part
// is the same samples, and everything else lies below the floor's tangent plane.
TEST(ScreenVisibility, SecondLayerOccludesAsTheFirst) {
  scenes::MeshBuilder fb, wb;
  fb.box({-20, -0.1, -20}, {20, 0, 20});
  wb.box({-0.1, -20, -20}, {0, 20, 20});
  const scenes::Mesh crease = creaseMesh(0.0).build(), floor = fb.build(), wall = wb.build();
  const scenes::View corner{"corner", {2.0, 1.5, 1.0}, {0, 0, 0}, {0, 1, 0}, 1.0, 0.1};
  TracedView c, f, w;
  traceFirstView({"crease", crease, {corner}}, 48, 32, 3, 1.0, c);
  traceFirstView({"floor", floor, {corner}}, 48, 32, 3, 1.0, f);
  traceFirstView({"wall", wall, {corner}}, 48, 32, 3, 1.0, w);
  Settings s;
  s.radius = 0.8f;
  FloatImage one, two, floorOnly;
  ASSERT_TRUE(raytrace::screenVisibility(s, c.camera, {&c.primary.depth}, fewSlices(), one).ok());
  ASSERT_TRUE(raytrace::screenVisibility(s, c.camera, {&f.primary.depth, &w.primary.depth}, fewSlices(), two).ok());
  ASSERT_TRUE(raytrace::screenVisibility(s, c.camera, {&f.primary.depth}, fewSlices(), floorOnly).ok());
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(corner));
  std::size_t compared = 0;
  double minV = 1;
  for (std::uint32_t y = 1; y + 1 < c.camera.height; ++y)
    for (std::uint32_t x = 1; x + 1 < c.camera.width; ++x) {
      bool floorAround = true;  // the rebuilt normal is the floor's in both
      for (auto [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const glm::dvec4 p = cameraPosition(c, x + dx, y + dy);
        floorAround = floorAround && p.w != 0 && std::fabs((toWorld * glm::dvec4(glm::dvec3(p), 1.0)).y) < 1e-4;
      }
      if (!floorAround) continue;
      EXPECT_NEAR(two.at(x, y), one.at(x, y), 1e-5) << x << "," << y;
      minV = std::min(minV, double(two.at(x, y)));
      ++compared;
    }
  EXPECT_GT(compared, one.data.size() / 4);
  EXPECT_LT(minV, 0.7) << "the second layer must occlude";
}

TEST(ScreenVisibility, RejectsBadInput) {
  TracedView v;
  traceCrease(1.0, v);
  const DepthImage& depth = v.primary.depth;
  Settings s;
  FloatImage ao;
  auto code = [&](const raytrace::ConvergedInputs& in, const raytrace::ScreenVisibilityOptions& o) {
    const Status st = raytrace::screenVisibility(s, v.camera, in, o, ao);
    EXPECT_TRUE(ao.data.empty()) << "no image with an error";
    if (!st.ok()) std::printf("refused: %s\n", st.message.c_str());
    return st.code;
  };
  EXPECT_EQ(code({}, fewSlices()), StatusCode::InvalidInput);
  DepthImage small = depth;
  small.extent.width -= 1;
  small.texels.resize(std::size_t(small.extent.width) * small.extent.height);
  EXPECT_EQ(code({&small}, fewSlices()), StatusCode::InvalidInput);
  DepthImage linear = depth;
  linear.format = DepthFormat::LinearZ;
  EXPECT_EQ(code({&depth, &linear}, fewSlices()), StatusCode::InvalidInput);
  FloatImage twoChannels(depth.extent, 2);
  EXPECT_EQ(code({&depth, nullptr, &twoChannels}, fewSlices()), StatusCode::InvalidInput);
  raytrace::ScreenVisibilityOptions o = fewSlices();
  o.slices = 0;
  EXPECT_EQ(code({&depth}, o), StatusCode::InvalidInput);
  o = fewSlices();
  o.stride = 0;
  EXPECT_EQ(code({&depth}, o), StatusCode::InvalidInput);
  for (double t : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    o = fewSlices();
    o.thicknessMeters = t;
    EXPECT_EQ(code({&depth}, o), StatusCode::InvalidInput) << t;
  }
  for (double tol : {-0.1, 1.0, std::numeric_limits<double>::quiet_NaN()}) {
    o = fewSlices();
    o.tolerance = tol;
    EXPECT_EQ(code({&depth}, o), StatusCode::InvalidInput) << tol;
  }
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()})
    for (int which = 0; which < 3; ++which) {
      o = fewSlices();
      o.thicknessFromWidth = true;
      (which == 0 ? o.widthScale : which == 1 ? o.widthMinMeters : o.widthJump) = bad;
      EXPECT_EQ(code({&depth}, o), StatusCode::InvalidInput) << which << " " << bad;
    }
  s.radius = -1;
  EXPECT_NE(code({&depth}, fewSlices()), StatusCode::Ok);
}

// Thickness from width: the 10 cm slat before the wall is taken as about 5 cm deep (half its
// width) instead of a constant 1 m, so the wall behind it sees past it as the ray tracer does
// (the slat really is 10 cm deep), while open wall far from the slat stays exactly 1 (an open plane
// is one run reaching the end of the line: T, below the tangent plane anyway).
TEST(ScreenVisibility, ThicknessFromWidthTakesAThinObjectAsThin) {
  TracedView v;
  traceSlat(v);
  Settings s;
  raytrace::ScreenVisibilityOptions o = fewSlices(32);
  o.thicknessMeters = 1.0;
  FloatImage constant, fromWidth, again, reference;
  ASSERT_TRUE(raytrace::screenVisibility(s, v.camera, {&v.primary.depth}, o, constant).ok());
  o.thicknessFromWidth = true;
  ASSERT_TRUE(raytrace::screenVisibility(s, v.camera, {&v.primary.depth}, o, fromWidth).ok());
  ASSERT_TRUE(raytrace::screenVisibility(s, v.camera, {&v.primary.depth}, o, again).ok());
  EXPECT_EQ(fromWidth.data, again.data) << "deterministic";
  raytrace::ReferenceOptions ro;
  ro.rays = 256;
  ASSERT_TRUE(raytrace::referenceAmbientOcclusion(*v.rays, v.camera, v.primary, v.scene.views[0], ro, reference).ok());
  const glm::dmat4 toWorld = glm::inverse(scenes::viewMatrix(v.scene.views[0]));
  double errConstant = 0, errWidth = 0;
  std::size_t near = 0, openNotOne = 0, open = 0;
  for (std::uint32_t y = 0; y < v.camera.height; ++y)
    for (std::uint32_t x = 0; x < v.camera.width; ++x) {
      const glm::dvec4 p = cameraPosition(v, x, y);
      const glm::dvec3 w = toWorld * glm::dvec4(glm::dvec3(p), 1.0);
      if (p.w == 0 || std::fabs(w.z) > 1e-4) continue;  // the wall only
      if (std::fabs(w.x) > 2.0) {  // farther from the slat than the 1 m radius can reach
        ++open;
        openNotOne += fromWidth.at(x, y) != 1.0f;
        continue;
      }
      if (std::fabs(w.x) > 0.8) continue;
      errConstant += std::pow(constant.at(x, y) - reference.at(x, y), 2);
      errWidth += std::pow(fromWidth.at(x, y) - reference.at(x, y), 2);
      ++near;
    }
  ASSERT_GT(near, 200u);
  ASSERT_GT(open, 200u);
  errConstant = std::sqrt(errConstant / near), errWidth = std::sqrt(errWidth / near);
  std::printf("wall near the slat, %zu pixels: RMSE vs (a) %.4f (T 1 m), %.4f (from width, T <= 1 m)\n", near,
              errConstant, errWidth);
  EXPECT_LT(errWidth, 0.6 * errConstant);
  EXPECT_EQ(openNotOne, 0u) << "of " << open << " open wall pixels";
}

}  // namespace
}  // namespace sao::truthtest
