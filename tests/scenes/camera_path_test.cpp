// Camera paths (sao/scenes/camera_path.h): each path's frames move the view as documented,
// deterministically, from the first frame to the last; a single frame is the base view.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sao/scenes/camera_path.h"

namespace sao::scenes {
namespace {

View baseView() { return View{"base", {3.0, 2.0, 4.0}, {0.5, 0.5, -1.0}, {0, 1, 0}, 1.0, 0.1}; }

double horizontalAngle(glm::dvec3 v) { return std::atan2(v.x, v.z); }

TEST(CameraPath, NamesParseBack) {
  ASSERT_EQ(pathNames().size(), 3u);
  for (std::string_view name : pathNames()) {
    const auto kind = parsePathKind(name);
    ASSERT_TRUE(kind.has_value()) << name;
    EXPECT_EQ(toString(*kind), name);
  }
  EXPECT_FALSE(parsePathKind("Orbit").has_value());
  EXPECT_FALSE(parsePathKind("").has_value());
}

TEST(CameraPath, OrbitTurnsThirtyDegreesAtConstantDistanceAndHeight) {
  const View b = baseView();
  const glm::dvec3 toEye = b.eye - b.target;
  const std::uint32_t n = 61;
  for (std::uint32_t f = 0; f < n; ++f) {
    const View v = pathView(b, PathKind::Orbit, f, n);
    EXPECT_EQ(v.target, b.target);
    EXPECT_NEAR(glm::length(v.eye - v.target), glm::length(toEye), 1e-12);
    EXPECT_NEAR(v.eye.y, b.eye.y, 1e-12);
    const double turned = horizontalAngle(v.eye - v.target) - horizontalAngle(toEye);
    const double expected = (-15.0 + 30.0 * f / (n - 1)) * std::numbers::pi / 180.0;
    EXPECT_NEAR(turned, expected, 1e-12) << "frame " << f;
  }
  const View middle = pathView(b, PathKind::Orbit, 30, n);
  EXPECT_NEAR(glm::length(middle.eye - b.eye), 0.0, 1e-12) << "the middle frame is the base view";
}

TEST(CameraPath, DollyApproachesTheTargetToSixtyPercent) {
  const View b = baseView();
  const double d = glm::length(b.eye - b.target);
  const View first = pathView(b, PathKind::Dolly, 0, 60), last = pathView(b, PathKind::Dolly, 59, 60);
  EXPECT_NEAR(glm::length(first.eye - first.target), d, 1e-12);
  EXPECT_NEAR(glm::length(last.eye - last.target), 0.6 * d, 1e-12);
  for (std::uint32_t f = 0; f < 60; ++f) {
    const View v = pathView(b, PathKind::Dolly, f, 60);
    EXPECT_EQ(v.target, b.target);
    EXPECT_NEAR(glm::length(glm::cross(v.eye - v.target, b.eye - b.target)), 0.0, 1e-12) << "the same direction";
    EXPECT_NEAR(glm::length(v.eye - v.target), d * (1.0 - 0.4 * f / 59.0), 1e-12);
  }
}

TEST(CameraPath, StrafeMovesEyeAndTargetSidewaysTogether) {
  const View b = baseView();
  const glm::dvec3 forward = b.target - b.eye;
  const double d = glm::length(forward);
  const View first = pathView(b, PathKind::Strafe, 0, 60), last = pathView(b, PathKind::Strafe, 59, 60);
  const glm::dvec3 moved = last.eye - first.eye;
  EXPECT_NEAR(glm::length(moved), 0.3 * d, 1e-12);
  EXPECT_NEAR(glm::dot(moved, forward), 0.0, 1e-12) << "across the view";
  EXPECT_NEAR(moved.y, 0.0, 1e-12) << "horizontal";
  for (std::uint32_t f = 0; f < 60; ++f) {
    const View v = pathView(b, PathKind::Strafe, f, 60);
    EXPECT_NEAR(glm::length((v.target - v.eye) - forward), 0.0, 1e-12) << "the same view direction";
  }
}

TEST(CameraPath, OneFrameIsTheBaseViewAndPathsAreDeterministic) {
  const View b = baseView();
  for (std::string_view name : pathNames()) {
    const PathKind k = *parsePathKind(name);
    const View one = pathView(b, k, 0, 1);
    EXPECT_NEAR(glm::length(one.eye - b.eye), 0.0, 1e-12) << name;
    EXPECT_NEAR(glm::length(one.target - b.target), 0.0, 1e-12) << name;
    EXPECT_EQ(one.fovyRadians, b.fovyRadians);
    const View a = pathView(b, k, 17, 60), again = pathView(b, k, 17, 60);
    EXPECT_EQ(a.eye, again.eye);
    EXPECT_EQ(a.target, again.target);
  }
}

}  // namespace
}  // namespace sao::scenes
