// Camera errors name the real cause: the builders' arguments are checked by
// checkPerspectiveArguments / checkOrthographicArguments, and analyze() names what it can see
// in a matrix built from bad ones (issue 14: "non-finite element" for near == far, "set
// reversedZ = true" for near > far).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "sao/camera.h"
#include "sao/plan.h"

namespace {

constexpr double kFovy = std::numbers::pi / 3;

std::string perspectiveError(double fovy, std::uint32_t w, std::uint32_t h, double n, double f) {
  const sao::Status st = sao::checkPerspectiveArguments(fovy, w, h, n, f);
  EXPECT_EQ(st.code, st.ok() ? sao::StatusCode::Ok : sao::StatusCode::InvalidCamera);
  return st.message;
}

TEST(CameraArguments, GoodArgumentsPass) {
  EXPECT_TRUE(sao::checkPerspectiveArguments(kFovy, 320, 180, 0.1, INFINITY).ok());
  EXPECT_TRUE(sao::checkPerspectiveArguments(kFovy, 1, 1, 0.1, 0.1000001).ok());
  EXPECT_TRUE(sao::checkOrthographicArguments(2.0, 320, 180, 0.0, 10.0).ok());
}

TEST(CameraArguments, NearEqualToFarIsNamed) {
  EXPECT_EQ(perspectiveError(kFovy, 320, 180, 0.1, 0.1),
            "far distance 0.1 equals the near distance 0.1: far must be beyond near (or +inf)");
  // What the builder makes of it anyway: analyze() names the element and the likely cause.
  const sao::Camera cam = sao::perspectiveCamera(kFovy, 320, 180, 0.1, 0.1, sao::ClipDepth::ZeroToOne, false);
  sao::DepthModel m;
  const sao::Status st = sao::analyze(cam, m);
  EXPECT_NE(st.message.find("non-finite element P22 (row 2, column 2) = -inf"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("were the near and far planes equal"), std::string::npos) << st.message;
}

TEST(CameraArguments, FarNearerThanNearIsNamed) {
  EXPECT_EQ(perspectiveError(kFovy, 320, 180, 1.0, 0.5),
            "far distance 0.5 is nearer than the near distance 1: far must be beyond near (or +inf)");
  // A standard matrix built with near and far swapped is exactly a reversed-Z one: analyze()
  // cannot tell the two apart and names both.
  const sao::Camera cam = sao::perspectiveCamera(kFovy, 320, 180, 1.0, 0.5, sao::ClipDepth::ZeroToOne, false);
  sao::DepthModel m;
  const sao::Status st = sao::analyze(cam, m);
  EXPECT_NE(st.message.find("set reversedZ = true, or, if the matrix was built with the near and far distances "
                            "swapped, swap them"),
            std::string::npos)
      << st.message;
  EXPECT_EQ(sao::checkOrthographicArguments(2.0, 320, 180, 5.0, 5.0).message,
            "far distance 5 equals the near distance 5: far must be beyond near");
}

TEST(CameraArguments, EveryOtherBadArgumentIsNamed) {
  EXPECT_NE(perspectiveError(0, 320, 180, 0.1, 1).find("vertical field of view 0 rad"), std::string::npos);
  EXPECT_NE(perspectiveError(std::numbers::pi, 320, 180, 0.1, 1).find("outside (0, pi)"), std::string::npos);
  EXPECT_NE(perspectiveError(NAN, 320, 180, 0.1, 1).find("vertical field of view nan"), std::string::npos);
  // An unsigned underflow (a guard band wider than the image) shows as a viewport of ~4e9 pixels.
  EXPECT_EQ(perspectiveError(kFovy, 320u - 400u, 180, 0.1, 1),
            "viewport size is 4294967216x180; each side must be in [1, " + std::to_string(sao::kMaxImageSide) + "]");
  EXPECT_NE(perspectiveError(kFovy, 0, 180, 0.1, 1).find("viewport size is 0x180"), std::string::npos);
  EXPECT_EQ(perspectiveError(kFovy, 320, 180, 0, 1), "near distance 0 must be finite and > 0");
  EXPECT_EQ(perspectiveError(kFovy, 320, 180, -1, 1), "near distance -1 must be finite and > 0");
  EXPECT_EQ(perspectiveError(kFovy, 320, 180, INFINITY, INFINITY), "near distance inf must be finite and > 0");
  EXPECT_EQ(perspectiveError(kFovy, 320, 180, 0.1, NAN), "far distance nan must be a number > near or +inf");
  EXPECT_EQ(perspectiveError(kFovy, 320, 180, 0.1, -INFINITY), "far distance -inf must be a number > near or +inf");
  EXPECT_EQ(sao::checkOrthographicArguments(0, 320, 180, 0, 1).message,
            "orthographic half height 0 must be finite and > 0");
  EXPECT_EQ(sao::checkOrthographicArguments(1, 320, 180, 0, INFINITY).message,
            "far distance inf of an orthographic projection must be finite");
}

}  // namespace
