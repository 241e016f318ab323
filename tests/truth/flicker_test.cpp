// The flicker figure (sao/samples/flicker.h): mean |A_t - A_{t-1}| after reprojection onto the same
// surface. Exact on an unchanged frame and on a constant change; small for AO anchored to the
// world while the camera strafes (where comparing pixel to pixel is not); disoccluded pixels and
// those that left the view are not compared.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "sao/samples/flicker.h"

namespace sao::samples {
namespace {

constexpr std::uint32_t kW = 96, kH = 54, kGuard = 4;

Camera testCamera() {
  Camera c = perspectiveCamera(std::numbers::pi / 3, kW, kH, 0.1, INFINITY, ClipDepth::ZeroToOne, true);
  c.guardBand = kGuard;
  return c;
}

// Camera-space positions of a camera at `eyeX` (looking down -z) seeing the world plane z = -planeZ,
// except where `box` says a nearer surface (z = -boxZ) lies in front.
struct Frame {
  FloatImage position, ao;
  glm::dmat4 worldToCamera{1.0};
};

Frame render(const Camera& c, double eyeX, double planeZ, const std::function<bool(double, double)>& box,
             double boxZ, const std::function<float(double, double)>& aoOfWorld) {
  Frame f;
  f.worldToCamera = glm::translate(glm::dmat4(1.0), glm::dvec3(-eyeX, 0, 0));
  const std::uint32_t W = kW + 2 * kGuard, H = kH + 2 * kGuard;
  f.position = FloatImage({W, H}, 4);
  f.ao = FloatImage({kW, kH}, 1);
  const double P00 = c.projection[0], P11 = c.projection[5];
  for (std::uint32_t y = 0; y < H; ++y)
    for (std::uint32_t x = 0; x < W; ++x) {
      const double ndcX = 2.0 * (double(x) - kGuard + 0.5) / kW - 1.0, ndcY = 2.0 * (double(y) - kGuard + 0.5) / kH - 1.0;
      const double dx = ndcX / P00, dy = ndcY / P11;  // the ray's x, y at z = -1
      double z = -planeZ;
      const double wx = eyeX + dx * planeZ, wy = dy * planeZ;
      if (box && box(wx, wy)) z = -boxZ;
      const double px = dx * -z, py = dy * -z;
      f.position.at(x, y, 0) = float(px);
      f.position.at(x, y, 1) = float(py);
      f.position.at(x, y, 2) = float(z);
      f.position.at(x, y, 3) = 1.0f;
      if (x >= kGuard && y >= kGuard && x < kGuard + kW && y < kGuard + kH)
        f.ao.at(x - kGuard, y - kGuard) = aoOfWorld(px + eyeX, py);
    }
  return f;
}

Flicker flicker(const Frame& a, const Frame& b, const Camera& c) {
  return reprojectedFlicker({&a.ao, &a.position, a.worldToCamera}, {&b.ao, &b.position, b.worldToCamera}, c);
}

float anchored(double x, double y) { return float(0.5 + 0.25 * std::sin(3.0 * x) * std::cos(2.0 * y)); }

TEST(Flicker, UnchangedFrameIsZeroAndEveryPixelCompared) {
  const Camera c = testCamera();
  const Frame f = render(c, 0.0, 5.0, nullptr, 0, anchored);
  const Flicker r = flicker(f, f, c);
  EXPECT_EQ(r.geometry, std::uint64_t(kW) * kH);
  EXPECT_EQ(r.compared, r.geometry);
  EXPECT_EQ(r.meanAbsDifference, 0.0);
}

TEST(Flicker, AConstantChangeIsMeasuredExactly) {
  const Camera c = testCamera();
  const Frame a = render(c, 0.0, 5.0, nullptr, 0, [](double, double) { return 0.5f; });
  const Frame b = render(c, 0.0, 5.0, nullptr, 0, [](double, double) { return 0.625f; });
  EXPECT_EQ(flicker(a, b, c).meanAbsDifference, 0.125);
}

TEST(Flicker, WorldAnchoredAoWhileStrafingIsSmallAfterReprojection) {
  const Camera c = testCamera();
  const Frame a = render(c, 0.0, 5.0, nullptr, 0, anchored);
  const Frame b = render(c, 0.3, 5.0, nullptr, 0, anchored);
  const Flicker r = flicker(a, b, c);
  // Pixel to pixel, without reprojection, for comparison.
  double naive = 0;
  for (std::size_t i = 0; i < a.ao.data.size(); ++i) naive += std::abs(double(a.ao.data[i]) - b.ao.data[i]);
  naive /= double(a.ao.data.size());
  std::printf("strafe 0.3 at 5 m: reprojected %.5f over %llu of %llu pixels; pixel to pixel %.5f\n", r.meanAbsDifference,
              (unsigned long long)r.compared, (unsigned long long)r.geometry, naive);
  EXPECT_LT(r.meanAbsDifference, 0.02) << "nearest-pixel reprojection of a smooth pattern";
  EXPECT_GT(naive, 5 * r.meanAbsDifference);
  EXPECT_LT(r.compared, r.geometry) << "a strip left the view";
  EXPECT_GT(r.compared, r.geometry * 9 / 10);
}

TEST(Flicker, DisoccludedPixelsAreNotCompared) {
  const Camera c = testCamera();
  auto box = [](double x, double y) { return std::abs(x) < 0.5 && std::abs(y) < 0.5; };
  // Frame t-1 has a nearer box (z = -3) over the middle of the plane; frame t has none.
  const Frame a = render(c, 0.0, 5.0, box, 3.0, anchored);
  const Frame b = render(c, 0.0, 5.0, nullptr, 0, anchored);
  const Flicker r = flicker(a, b, c);
  EXPECT_LT(r.compared, r.geometry);
  EXPECT_EQ(r.meanAbsDifference, 0.0) << "only the unchanged plane is compared";
}

}  // namespace
}  // namespace sao::samples
