// The depth convention warnings of the sample programs (sao/samples/depth_convention.h): no
// geometry, LinearZ holding positive distances, a buffer read with the other Z convention or as
// window depth when it is linear, on a synthetic scene and on every built-in scene (ray cast in
// each depth format, perspective and orthographic), where the right conventions give no warning.
#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "sao/raytrace/raytrace.h"
#include "sao/samples/depth_convention.h"
#include "sao/samples/scale_warnings.h"
#include "sao/scenes/scene.h"

namespace sao::samples {
namespace {

constexpr std::uint32_t kW = 96, kH = 64;

Camera perspective(bool reversedZ, double farDistance = INFINITY, double nearDistance = 0.1) {
  return perspectiveCamera(std::numbers::pi / 3, kW, kH, nearDistance, farDistance, ClipDepth::ZeroToOne, reversedZ);
}
Camera orthographic(bool reversedZ) {
  return orthographicCamera(6.0, kW, kH, 0.5, 30.0, ClipDepth::ZeroToOne, reversedZ);
}

// The distance along the view axis of texel (x, y)'s first hit, or INFINITY (sky): a floor 1.5
// below the camera, a wall 12 away up to 4 above it, and a slanted wall on the right (the one an
// orthographic camera sees slanted). Sky above the walls.
double sceneDistance(const Camera& c, std::uint32_t x, std::uint32_t y) {
  const double nx = 2 * (x + 0.5) / kW - 1, ny = 2 * (y + 0.5) / kH - 1;
  const bool ortho = c.kind == ProjectionKind::Orthographic;
  // The ray: origin o, direction u with u.z = -1, so that the hit's distance is its parameter.
  const double ox = ortho ? nx / c.projection[0] : 0, oy = ortho ? ny / c.projection[5] : 0;
  const double ux = ortho ? 0 : nx / c.projection[0], uy = ortho ? 0 : ny / c.projection[5];
  double best = INFINITY;
  if (uy < 0) best = std::min(best, (oy + 1.5) / -uy);  // floor y = -1.5
  if (oy + 12 * uy < 4) best = std::min(best, 12.0);  // wall z = -12
  const double side = (6 - ox) / (ux + 0.6);  // slanted: x + 0.6 D = 6
  if (side > 0 && oy + side * uy < 4) best = std::min(best, side);
  return best;
}

// The scene as `camera` stores it in `format` (the clear value for sky and beyond the planes).
DepthImage render(const Camera& camera, DepthFormat format) {
  DepthModel m;
  EXPECT_TRUE(analyze(camera, m));
  DepthImage d;
  d.extent = {kW, kH};
  d.format = format;
  for (std::uint32_t y = 0; y < kH; ++y)
    for (std::uint32_t x = 0; x < kW; ++x) {
      const double dist = sceneDistance(camera, x, y);
      const bool seen = dist >= m.nearDistance && dist <= m.farDistance && std::isfinite(dist);
      if (format == DepthFormat::LinearZ) {
        d.texels.push_back(encodeDepth(format, seen ? -dist : 0.0));
        continue;
      }
      const double window = !seen ? m.depthAtFar
                            : camera.kind == ProjectionKind::Orthographic ? (-dist - m.c2) / m.c1
                                                                           : (m.c0 / -dist - m.c2) / m.c1;
      d.texels.push_back(encodeDepth(format, window));
    }
  return d;
}

// A buffer of D32F values f(distance) (INFINITY for sky): linear depth as other tools store it.
template <class F>
DepthImage linearBuffer(const Camera& camera, F f) {
  DepthImage d;
  d.extent = {kW, kH};
  d.format = DepthFormat::D32F;
  for (std::uint32_t y = 0; y < kH; ++y)
    for (std::uint32_t x = 0; x < kW; ++x)
      d.texels.push_back(std::bit_cast<std::uint32_t>(float(f(sceneDistance(camera, x, y)))));
  return d;
}

DepthImage filled(DepthFormat format, float value) {
  DepthImage d;
  d.extent = {kW, kH};
  d.format = format;
  d.texels.assign(std::size_t(kW) * kH, std::bit_cast<std::uint32_t>(value));
  return d;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

TEST(DepthConvention, TheRightConventionsGiveNoWarning) {
  for (const DepthFormat format : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F, DepthFormat::LinearZ})
    for (const bool reversed : {false, true}) {
      for (const double far : {double(INFINITY), 100.0}) {
        const Camera c = perspective(reversed, far);
        EXPECT_EQ(joined(depthConventionWarnings(render(c, format), c, Settings{})), "")
            << toString(format) << (reversed ? " reversed" : " standard") << " far " << far;
      }
      const Camera o = orthographic(reversed);
      EXPECT_EQ(joined(depthConventionWarnings(render(o, format), o, Settings{})), "")
          << toString(format) << (reversed ? " reversed" : " standard") << " orthographic";
    }
}

TEST(DepthConvention, ReversedZReadAsStandard) {
  const Camera reversed = perspective(true), standard = perspective(false);
  const auto w = depthConventionWarnings(render(reversed, DepthFormat::D32F), standard, Settings{});
  ASSERT_EQ(w.size(), 1u) << joined(w);
  EXPECT_EQ(w[0],
            "the depth looks reversed-Z but is read as standard depth: 728 texels are 0, reversed-Z depth's clear "
            "value (sky), and none is 1; read as standard, the median geometry lies 1.02 x the near distance away "
            "(0.102 view units; the radius spans 544 px there), read as reversed-Z 56.6 x (9.79 px): give "
            "--reversed-z (a depth file with its own camera: set its sao.reversedZ to 1)");
  for (const DepthFormat format : {DepthFormat::D16, DepthFormat::D24}) {
    const auto wf = depthConventionWarnings(render(reversed, format), standard, Settings{});
    ASSERT_EQ(wf.size(), 1u) << toString(format);
    EXPECT_TRUE(startsWith(wf[0], "the depth looks reversed-Z but is read as standard depth")) << wf[0];
  }
  // Orthographic: the sky alone tells.
  const auto wo = depthConventionWarnings(render(orthographic(true), DepthFormat::D24), orthographic(false), Settings{});
  ASSERT_EQ(wo.size(), 1u);
  EXPECT_EQ(wo[0],
            "the depth looks reversed-Z but is read as standard depth: 1162 texels are 0, reversed-Z depth's clear "
            "value (sky), and none is 1; give --reversed-z (a depth file with its own camera: set its sao.reversedZ "
            "to 1)");
  // An empty reversed-Z buffer read as standard is the near plane everywhere.
  const auto we = depthConventionWarnings(filled(DepthFormat::D32F, 0.0f), standard, Settings{});
  ASSERT_EQ(we.size(), 1u);
  EXPECT_EQ(we[0],
            "the depth looks reversed-Z but is read as standard depth: all 6144 texels are 0, reversed-Z depth's "
            "clear value (sky), and none is 1; read as standard depth they are the near plane: give --reversed-z (a "
            "depth file with its own camera: set its sao.reversedZ to 1)");
}

TEST(DepthConvention, StandardReadAsReversedZ) {
  const Camera reversed = perspective(true, 100.0), standard = perspective(false, 100.0);
  for (const DepthFormat format : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F}) {
    const auto w = depthConventionWarnings(render(standard, format), reversed, Settings{});
    ASSERT_EQ(w.size(), 1u) << toString(format);
    EXPECT_TRUE(startsWith(w[0], "the depth looks standard but is read as reversed-Z depth: 728 texels are 1, "
                                 "standard depth's clear value (sky), and none is 0; read as reversed-Z, the median "
                                 "geometry lies 1.02 x the near distance away"))
        << w[0];
    EXPECT_NE(w[0].find("leave out --reversed-z"), std::string::npos);
  }
  const auto wo = depthConventionWarnings(render(orthographic(false), DepthFormat::D16), orthographic(true), Settings{});
  ASSERT_EQ(wo.size(), 1u);
  EXPECT_TRUE(startsWith(wo[0], "the depth looks standard but is read as reversed-Z depth: 1162 texels are 1"));
}

TEST(DepthConvention, OtherZConventionWithoutSkyFromTheDistancesAlone) {
  // Floor and walls everywhere (no sky): the median distance says it.
  const Camera reversed = perspective(true), standard = perspective(false);
  DepthImage d = render(reversed, DepthFormat::D32F);
  const std::uint32_t wall = std::bit_cast<std::uint32_t>(float(0.1 / 12));
  for (std::uint32_t& t : d.texels)
    if (t == 0) t = wall;
  const auto w = depthConventionWarnings(d, standard, Settings{});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(startsWith(w[0], "the depth looks reversed-Z but is read as standard depth: read as standard, the "
                               "median geometry lies 1.02 x the near distance away (0.102 view units; the radius spans 545 px there), "
                               "read as reversed-Z 61.9 x (8.96 px): give --reversed-z"))
      << w[0];
  EXPECT_TRUE(depthConventionWarnings(d, reversed, Settings{}).empty());
}

TEST(DepthConvention, LinearDepthNormalisedReadAsWindowDepth) {
  // Distance / 30 (the far plane the tool normalised by), sky 1, read with a standard camera and
  // with a reversed-Z one; and distance / 30 with sky 0.
  for (const bool reversed : {false, true})
    for (const float sky : {1.0f, 0.0f}) {
      const Camera c = perspective(reversed);
      const auto w = depthConventionWarnings(
          linearBuffer(c, [sky](double d) { return std::isfinite(d) ? d / 30 : sky; }), c, Settings{});
      ASSERT_EQ(w.size(), 1u) << reversed << " " << sky;
      EXPECT_TRUE(startsWith(w[0], "the depth looks linear in distance (normalised to [0, 1]?), not ")) << w[0];
      EXPECT_NE(w[0].find("scale it back to view units and give it with --depth-distances"), std::string::npos);
    }
  const Camera c = perspective(false);
  const auto w = depthConventionWarnings(
      linearBuffer(c, [](double d) { return std::isfinite(d) ? d / 30 : 1.0; }), c, Settings{});
  EXPECT_EQ(w[0],
            "the depth looks linear in distance (normalised to [0, 1]?), not standard window depth: on flat surfaces "
            "its reciprocal changes evenly across the image where window depth itself would (4070 neighbourhoods "
            "against 3); read as window depth the median geometry lies 1.23 x the near distance away (the radius "
            "spans 450 px there): scale it back to view units and give it with --depth-distances, or store "
            "camera-space z as LinearZ");
}

TEST(DepthConvention, NoGeometryNamesTheValues) {
  // A camera whose near plane lies beyond the scene: every texel the clear value.
  const Camera farNear = perspective(true, INFINITY, 100.0);
  const auto w = depthConventionWarnings(render(farNear, DepthFormat::D32F), farNear, Settings{});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0],
            "no geometry: every one of the 6144 depth texels is sky (all 0, the reversed-Z clear value), so the AO is "
            "1 everywhere: nothing in view lies between the near plane (100 view units) and the far plane (inf): is "
            "the near plane (--near) beyond the scene, the camera looking away from it, or the depth buffer empty?");
  const auto ws = depthConventionWarnings(filled(DepthFormat::D16, 0), perspective(false, 50), Settings{});
  ASSERT_EQ(ws.size(), 1u);
  EXPECT_TRUE(startsWith(ws[0], "the depth looks reversed-Z")) << "0 in a standard buffer is the near plane";
  // Not a depth at all (a pure function's input need not have passed checkDepthValues).
  const auto wn = depthConventionWarnings(filled(DepthFormat::D32F, NAN), perspective(true), Settings{});
  ASSERT_EQ(wn.size(), 1u);
  EXPECT_TRUE(startsWith(wn[0], "no geometry: every one of the 6144 depth texels is sky (all NaN or infinite)"));
  DepthImage full = filled(DepthFormat::D16, 0);
  for (std::uint32_t& t : full.texels) t = 65535;
  const auto w1 = depthConventionWarnings(full, perspective(false, 50), Settings{});
  ASSERT_EQ(w1.size(), 1u);
  EXPECT_TRUE(startsWith(w1[0], "no geometry: every one of the 6144 depth texels is sky (all 1, the standard clear "
                                "value), so the AO is 1 everywhere: nothing in view lies between the near plane (0.1 "
                                "view units) and the far plane (50)"))
      << w1[0];
}

TEST(DepthConvention, LinearZHoldingPositiveDistances) {
  const Camera c = perspective(false);
  DepthImage d = render(c, DepthFormat::LinearZ);
  for (std::uint32_t& t : d.texels) t = std::bit_cast<std::uint32_t>(-std::bit_cast<float>(t));  // distances
  const auto w = depthConventionWarnings(d, c, Settings{});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0],
            "no geometry: every one of the 6144 depth texels is sky, so the AO is 1 everywhere: 5416 of them are "
            "positive (2.63932 to 12), which LinearZ reads as sky: LinearZ holds camera-space z, negative in front of "
            "the camera; positive distances along the view axis (e.g. a Blender Z pass) are read with "
            "--depth-distances");
  // Mostly positive: some geometry left, still the same cause.
  for (std::size_t i = 0; i < 100; ++i) d.texels[i] = std::bit_cast<std::uint32_t>(-5.0f);
  const auto wm = depthConventionWarnings(d, c, Settings{});
  ASSERT_EQ(wm.size(), 1u);
  EXPECT_TRUE(startsWith(wm[0], "5316 of the 6144 depth texels are positive (2.72585 to 12), which LinearZ reads as sky "
                                "(AO 1): LinearZ holds camera-space z"))
      << wm[0];
  // Nothing but zeros and NaN.
  DepthImage empty = filled(DepthFormat::LinearZ, 0.0f);
  empty.texels[7] = std::bit_cast<std::uint32_t>(NAN);
  const auto we = depthConventionWarnings(empty, c, Settings{});
  ASSERT_EQ(we.size(), 1u);
  EXPECT_EQ(we[0],
            "no geometry: every one of the 6144 depth texels is sky (6143 0, 1 NaN or infinite; LinearZ geometry is "
            "finite and negative), so the AO is 1 everywhere");
}

TEST(DepthConvention, ScaleCheckSaysTheConventionFirstAndNotTheUnits) {
  // Reversed-Z read as standard puts the scene at the near plane: the radius would project beyond
  // the image, but the units are not the problem.
  const Camera reversed = perspective(true), standard = perspective(false);
  const DepthImage d = render(reversed, DepthFormat::D32F);
  ScaleCheck c;
  ASSERT_TRUE(checkScale(Settings{}, standard, d, FloatImage({kW, kH}, 1, 1.0f), c));
  EXPECT_GT(c.fractionAboveImage, 0.5) << "the figures stay";
  ASSERT_EQ(c.warnings.size(), 1u) << joined(c.warnings);
  EXPECT_TRUE(startsWith(c.warnings[0], "the depth looks reversed-Z"));
  // No geometry: the warning the scale check never gave.
  ASSERT_TRUE(checkScale(Settings{}, perspective(true, INFINITY, 100.0),
                         render(perspective(true, INFINITY, 100.0), DepthFormat::D24), FloatImage({kW, kH}, 1, 1.0f),
                         c));
  EXPECT_EQ(c.geometryPixels, 0u);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_TRUE(startsWith(c.warnings[0], "no geometry: every one of the 6144 depth texels is sky (all 0,"));
  // The right convention: the scale warnings as before.
  ASSERT_TRUE(checkScale(Settings{}, reversed, d, FloatImage({kW, kH}, 1, 1.0f), c));
  ASSERT_EQ(c.warnings.size(), 1u) << joined(c.warnings);
  EXPECT_TRUE(startsWith(c.warnings[0], "the AO is 1.0 on every geometry pixel"));
}

TEST(DepthConvention, GuardBandAndMismatchedExtents) {
  // Only the viewport counts: geometry in the guard band alone is still no geometry.
  Camera c = perspectiveCamera(std::numbers::pi / 3, kW - 8, kH - 8, 0.1, INFINITY, ClipDepth::ZeroToOne, true);
  c.guardBand = 4;
  DepthImage d = filled(DepthFormat::D32F, 0.0f);
  d.texels[0] = std::bit_cast<std::uint32_t>(0.02f);
  const auto w = depthConventionWarnings(d, c, Settings{});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(startsWith(w[0], "no geometry: every one of the 4928 depth texels is sky")) << w[0];
  // An image of another size than the camera: the whole image is judged; a broken one is left alone.
  c.guardBand = 0;
  EXPECT_TRUE(startsWith(depthConventionWarnings(filled(DepthFormat::D32F, 0.0f), c, Settings{}).at(0),
                         "no geometry: every one of the 6144 depth texels"));
  DepthImage broken = filled(DepthFormat::D32F, 0.0f);
  broken.texels.pop_back();
  EXPECT_TRUE(depthConventionWarnings(broken, c, Settings{}).empty());
}

// Linear depth as a tool normalises it: the distance over the largest one, sky 1, from reversed-Z
// D32F depth.
DepthImage normalisedDistances(const DepthImage& reversedDepth, const Camera& reversed) {
  DepthModel m;
  EXPECT_TRUE(analyze(reversed, m));
  auto distance = [&](std::uint32_t t) { return -linearZ(m, reversed.kind, std::bit_cast<float>(t)); };
  double farthest = 0;
  for (const std::uint32_t t : reversedDepth.texels)
    if (t) farthest = std::max(farthest, distance(t));
  DepthImage linear = reversedDepth;
  for (std::uint32_t& t : linear.texels) t = std::bit_cast<std::uint32_t>(t ? float(distance(t) / farthest) : 1.0f);
  return linear;
}

// Every built-in scene and view, perspective and orthographic, in D16, D24 and D32F: read with
// its own conventions (reversed-Z as rendered, or turned into standard depth) nothing is said;
// read with the other one, or as linear depth normalised to [0, 1], the warning names it.
TEST(DepthConvention, BuiltinScenesNoFalseAlarmAndEachMistakeFound) {
  constexpr std::uint32_t w = 96, h = 54;
  for (const std::string_view name : scenes::builtinSceneNames()) {
    scenes::Scene scene;
    ASSERT_TRUE(scenes::makeBuiltinScene(name, scene));
    std::unique_ptr<raytrace::RayScene> rays;
    ASSERT_TRUE(raytrace::RayScene::create(scene.mesh, rays));
    for (const scenes::View& perspectiveView : scene.views)
      for (const bool ortho : {false, true}) {
        const scenes::View view = ortho ? scenes::toOrthographic(perspectiveView, scene.mesh) : perspectiveView;
        const Camera reversed = scenes::makeCamera(view, w, h, INFINITY, ClipDepth::ZeroToOne, true);
        const Camera standard = scenes::makeCamera(view, w, h, INFINITY, ClipDepth::ZeroToOne, false);
        for (const DepthFormat format : {DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F}) {
          const std::string what = std::string(name) + " " + view.name + (ortho ? " ortho " : " ") + toString(format);
          raytrace::Primary primary;
          ASSERT_TRUE(raytrace::castPrimary(*rays, view, reversed, format, primary));
          const DepthImage& rev = primary.depth;
          DepthImage standardDepth = rev;  // d -> 1 - d: exact for the integer formats
          for (std::uint32_t& t : standardDepth.texels)
            t = format == DepthFormat::D32F ? std::bit_cast<std::uint32_t>(1.0f - std::bit_cast<float>(t))
                                            : (format == DepthFormat::D16 ? 65535u : 16777215u) - t;
          EXPECT_EQ(joined(depthConventionWarnings(rev, reversed, Settings{})), "") << what;
          EXPECT_EQ(joined(depthConventionWarnings(standardDepth, standard, Settings{})), "") << what;
          const auto asStandard = depthConventionWarnings(rev, standard, Settings{});
          const auto asReversed = depthConventionWarnings(standardDepth, reversed, Settings{});
          // Orthographic depth is affine in the distance: only the sky tells the conventions apart, and
          // a view that is all geometry (sphere-plane's top view) cannot be judged.
          const auto skyTexels = std::count(rev.texels.begin(), rev.texels.end(), 0u);
          if (ortho && std::size_t(skyTexels) * 200 < rev.texels.size()) {
            EXPECT_TRUE(asStandard.empty() && asReversed.empty()) << what;
            continue;
          }
          ASSERT_EQ(asStandard.size(), 1u) << what;
          ASSERT_EQ(asReversed.size(), 1u) << what;
          EXPECT_TRUE(startsWith(asStandard[0], "the depth looks reversed-Z but is read as standard")) << what;
          EXPECT_TRUE(startsWith(asReversed[0], "the depth looks standard but is read as reversed-Z")) << what;
          if (ortho || format != DepthFormat::D32F) continue;
          const auto asWindow = depthConventionWarnings(normalisedDistances(rev, reversed), standard, Settings{});
          ASSERT_EQ(asWindow.size(), 1u) << what;
          EXPECT_TRUE(startsWith(asWindow[0], "the depth looks linear in distance")) << what << ": " << asWindow[0];
        }
      }
  }
}

}  // namespace
}  // namespace sao::samples

namespace sao::samples {
namespace {

// A large image tells linear depth as well as a small one: the flat-surface test compares texels
// 1/64 of the image apart, not neighbours, whose curvature drowns in the rounding (the sphere on
// its plane seen from the top at 1280x720: 2.3 % of the texels vote for linear depth with
// neighbours, 91 % with texels 11 apart). Without that, 640x360 fails here.
TEST(DepthConvention, LargeImagesTellLinearDepthToo) {
  scenes::Scene scene;
  ASSERT_TRUE(scenes::makeBuiltinScene("sphere-plane", scene));
  std::unique_ptr<raytrace::RayScene> rays;
  ASSERT_TRUE(raytrace::RayScene::create(scene.mesh, rays));
  for (const scenes::View& view : scene.views) {
    const Camera reversed = scenes::makeCamera(view, 640, 360, INFINITY, ClipDepth::ZeroToOne, true);
    const Camera standard = scenes::makeCamera(view, 640, 360, INFINITY, ClipDepth::ZeroToOne, false);
    raytrace::Primary primary;
    ASSERT_TRUE(raytrace::castPrimary(*rays, view, reversed, DepthFormat::D32F, primary));
    EXPECT_EQ(joined(depthConventionWarnings(primary.depth, reversed, Settings{})), "") << view.name;
    const auto w = depthConventionWarnings(normalisedDistances(primary.depth, reversed), standard, Settings{});
    ASSERT_EQ(w.size(), 1u) << view.name;
    EXPECT_TRUE(startsWith(w[0], "the depth looks linear in distance")) << view.name << ": " << w[0];
  }
}

}  // namespace
}  // namespace sao::samples
