// computeConstants against values derived by hand from the paper's eq. 2, 3 and 5, for every
// convention; camera analysis rejects matrices that contradict their declared convention.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

#include "sao/constants.h"
#include "sao/spiral.h"

namespace {

constexpr double kFovy = std::numbers::pi / 3.0;  // 60 degrees
constexpr double kNear = 0.1, kFar = 100.0;

double P(const sao::Camera& c, int row, int col) { return c.projection[col * 4 + row]; }

// The paper's eq. 2 with its own constants (zn, zf negative), d re-mapped for reversed-Z.
double paperZ(double d, bool reversed, bool infinite) {
  const double zn = -kNear, zf = -kFar;
  if (reversed) d = 1.0 - d;
  if (infinite) return zn / (1.0 - d);                // c = [zn, -1, +1]
  return (zn * zf) / (d * (zn - zf) + zf);            // c = [zn zf, zn - zf, zf]
}

struct Convention {
  const char* name;
  sao::ClipDepth clip;
  bool reversed;
  bool infinite;
};

const Convention kConventions[] = {
    {"gl_standard", sao::ClipDepth::NegativeOneToOne, false, false},
    {"gl_standard_infinite", sao::ClipDepth::NegativeOneToOne, false, true},
    {"zero_one_standard", sao::ClipDepth::ZeroToOne, false, false},
    {"zero_one_reversed", sao::ClipDepth::ZeroToOne, true, false},
    {"zero_one_reversed_infinite", sao::ClipDepth::ZeroToOne, true, true},
    {"gl_reversed_without_clip_control", sao::ClipDepth::NegativeOneToOne, true, false},
};

TEST(Constants, Eq2MatchesThePaperForEveryConvention) {
  for (const auto& cv : kConventions) {
    const auto cam = sao::perspectiveCamera(kFovy, 1280, 720, kNear, cv.infinite ? INFINITY : kFar, cv.clip, cv.reversed);
    sao::DepthModel m;
    ASSERT_TRUE(sao::analyze(cam, m).ok()) << cv.name;
    EXPECT_NEAR(m.nearDistance, kNear, 1e-12) << cv.name;
    if (cv.infinite) EXPECT_TRUE(std::isinf(m.farDistance)) << cv.name;
    else EXPECT_NEAR(m.farDistance, kFar, 1e-9) << cv.name;

    sao::ParamBlock p;
    ASSERT_TRUE(sao::computeConstants(sao::Settings{}, cam, sao::DepthEncoding::Hardware, p).ok());
    for (double d : {0.0, 0.25, 0.5, 0.9, 0.999, 0.999999}) {
      if (cv.infinite && d == (cv.reversed ? 0.0 : 1.0)) continue;
      const double expected = paperZ(d, cv.reversed, cv.infinite);
      EXPECT_NEAR(sao::linearZ(m, cam.kind, d), expected, 1e-12 * std::fabs(expected)) << cv.name << " d=" << d;
      // The float constants in the block reproduce it to float precision.
      const double fromBlock = double(p.clip_info.x) / (d * double(p.clip_info.y) + double(p.clip_info.z));
      EXPECT_NEAR(fromBlock, expected, 2e-6 * std::fabs(expected)) << cv.name << " d=" << d;
    }
    EXPECT_EQ(p.depth_mode, sao::gen::SAO_DEPTH_MODE_PERSPECTIVE);
    EXPECT_EQ(p.far_dir, cv.reversed ? -1.0f : 1.0f);
    EXPECT_EQ(p.far_lim, cv.reversed ? 0.0f : 1.0f);
  }
}

TEST(Constants, InfiniteFarMatchesThePapersConstantsExactly) {
  // Paper: c = [zn, -1, +1] for an infinite far plane, [0,1] standard clip.
  const auto cam = sao::perspectiveCamera(kFovy, 640, 480, kNear, INFINITY, sao::ClipDepth::ZeroToOne, false);
  sao::DepthModel m;
  ASSERT_TRUE(sao::analyze(cam, m).ok());
  // Ours is the paper's scaled by -1: (n, 1, -1).
  EXPECT_DOUBLE_EQ(m.c0, kNear);
  EXPECT_DOUBLE_EQ(m.c1, 1.0);
  EXPECT_DOUBLE_EQ(m.c2, -1.0);
}

TEST(Constants, OrthographicDepthIsLinear) {
  for (const auto& cv : kConventions) {
    if (cv.infinite) continue;
    const auto cam = sao::orthographicCamera(5.0, 800, 600, kNear, kFar, cv.clip, cv.reversed);
    sao::DepthModel m;
    ASSERT_TRUE(sao::analyze(cam, m).ok()) << cv.name;
    for (double d : {0.0, 0.3, 1.0}) {
      const double t = cv.reversed ? 1.0 - d : d;
      EXPECT_NEAR(sao::linearZ(m, cam.kind, d), -(kNear + t * (kFar - kNear)), 1e-9) << cv.name << " d=" << d;
    }
    sao::ParamBlock p;
    ASSERT_TRUE(sao::computeConstants(sao::Settings{}, cam, sao::DepthEncoding::Hardware, p).ok());
    EXPECT_EQ(p.depth_mode, sao::gen::SAO_DEPTH_MODE_ORTHOGRAPHIC);
    EXPECT_EQ(p.ortho, 1);
    EXPECT_FLOAT_EQ(p.proj_scale, 0.5f * 600.0f / 5.0f) << "S' = pixels per view unit";
  }
}

// Eq. 3: a csz texel centre with its z, reconstructed through proj_info, projects back through P
// onto the same pixel centre. Covers guard bands, off-centre frusta, flipped rows and ortho.
void expectEq3RoundTrip(sao::Camera cam, const char* what) {
  sao::ParamBlock p;
  ASSERT_TRUE(sao::computeConstants(sao::Settings{}, cam, sao::DepthEncoding::Hardware, p).ok()) << what;
  const bool ortho = cam.kind == sao::ProjectionKind::Orthographic;
  for (int x : {0, 17, int(cam.width) - 1})
    for (int y : {0, 5, int(cam.height) - 1})
      for (double z : {-0.5, -3.0, -40.0}) {
        const double X = x + cam.guardBand + 0.5, Y = y + cam.guardBand + 0.5;
        const double w = ortho ? 1.0 : z;
        const double xc = w * (X * p.proj_info.x + p.proj_info.z), yc = w * (Y * p.proj_info.y + p.proj_info.w);
        const double cx = P(cam, 0, 0) * xc + P(cam, 0, 2) * z + P(cam, 0, 3);
        const double cy = P(cam, 1, 1) * yc + P(cam, 1, 2) * z + P(cam, 1, 3);
        const double cw = ortho ? 1.0 : -z;
        const double ndcX = 2.0 * (x + 0.5) / cam.width - 1.0;
        const double ndcY = (cam.flipY ? -1.0 : 1.0) * (2.0 * (y + 0.5) / cam.height - 1.0);
        EXPECT_NEAR(cx / cw, ndcX, 2e-5) << what << " x=" << x << " z=" << z;
        EXPECT_NEAR(cy / cw, ndcY, 2e-5) << what << " y=" << y << " z=" << z;
      }
}

TEST(Constants, Eq3ReconstructsPositionsThatProjectBackOntoTheirPixel) {
  auto cam = sao::perspectiveCamera(kFovy, 1280, 720, kNear, kFar, sao::ClipDepth::NegativeOneToOne, false);
  expectEq3RoundTrip(cam, "symmetric");
  cam.guardBand = 32;
  expectEq3RoundTrip(cam, "guard band");
  cam.projection[2 * 4 + 0] = 0.1;   // P02: off-centre frustum
  cam.projection[2 * 4 + 1] = -0.05; // P12
  expectEq3RoundTrip(cam, "off-centre");
  cam.flipY = true;
  expectEq3RoundTrip(cam, "flipped rows");
  auto ortho = sao::orthographicCamera(4.0, 641, 479, 0.5, 50.0, sao::ClipDepth::ZeroToOne, true);
  ortho.guardBand = 8;
  expectEq3RoundTrip(ortho, "orthographic");
}

TEST(Constants, Eq3MatchesThePapersFormula) {
  // x_C = z ((1 - P02)/P00 - 2(x' + 1/2)/(w P00)) for x' an AO pixel; here with a guard band.
  auto cam = sao::perspectiveCamera(kFovy, 1280, 720, kNear, kFar, sao::ClipDepth::NegativeOneToOne, false);
  cam.guardBand = 10;
  sao::ParamBlock p;
  ASSERT_TRUE(sao::computeConstants(sao::Settings{}, cam, sao::DepthEncoding::Hardware, p).ok());
  const double z = -7.0, xp = 100.0;
  const double paper = z * ((1.0 - P(cam, 0, 2)) / P(cam, 0, 0) - 2.0 * (xp + 0.5) / (1280 * P(cam, 0, 0)));
  const double ours = z * ((xp + cam.guardBand + 0.5) * p.proj_info.x + p.proj_info.z);
  EXPECT_NEAR(ours, paper, 1e-5);
}

TEST(Constants, Eq5ProjectionScaleAndSettingScales) {
  auto cam = sao::perspectiveCamera(kFovy, 1280, 720, kNear, kFar, sao::ClipDepth::ZeroToOne, false);
  cam.metersToViewUnits = 100.0;  // centimetres
  sao::Settings s;
  s.radius = 1.5f;
  s.intensity = 2.0f;
  s.samples = 16;
  s.epsilon = 1e-4f;
  sao::ParamBlock p;
  ASSERT_TRUE(sao::computeConstants(s, cam, sao::DepthEncoding::Hardware, p).ok());
  // S': pixel size of a 1-unit object at distance 1: h / (2 tan(fovy / 2)).
  EXPECT_NEAR(p.proj_scale, 720.0 / (2.0 * std::tan(kFovy / 2.0)), 1e-3);
  EXPECT_FLOAT_EQ(p.radius, 150.0f);
  EXPECT_FLOAT_EQ(p.radius2, 22500.0f);
  // sigma is unitless: eq. 1's sum (1/length) is scaled by the radius in view units, 1.5 m * 100.
  EXPECT_FLOAT_EQ(p.intensity_div_s, 2.0f * 2.0f * 150.0f / 16.0f) << "sigma multiplies the sum by r in view units";
  EXPECT_FLOAT_EQ(p.inv_samples, 1.0f / 16.0f);
  EXPECT_NEAR(p.epsilon, 1e-4 * 1e4, 1e-6) << "epsilon is an area: scales with units squared";
  EXPECT_EQ(p.spiral_turns, sao::spiralTurns(16));
  s.spiral_turns = 5;  // an explicit tau replaces the built-in choice
  ASSERT_TRUE(sao::computeConstants(s, cam, sao::DepthEncoding::Hardware, p).ok());
  EXPECT_EQ(p.spiral_turns, 5);
  s.spiral_turns = 0;
  EXPECT_FLOAT_EQ(p.quad_edge_threshold, s.quad_edge_threshold * 100.0f);
  // The blur's sharpness is per key unit: per metre with rg16f intermediates (the key z / u, in
  // metres), per view unit with rg32f (the key z).
  EXPECT_FLOAT_EQ(p.blur_edge_sharpness, s.half_intermediates ? s.blur_edge_sharpness : s.blur_edge_sharpness / 100.0f);
  EXPECT_FLOAT_EQ(p.key_scale, s.half_intermediates ? 0.01f : 1.0f);
  EXPECT_EQ(p.ao_size.x, 1280);
  EXPECT_EQ(p.ao_size.y, 720);
}

TEST(Constants, LinearZInputSkipsEq2) {
  const auto cam = sao::perspectiveCamera(kFovy, 64, 64, kNear, kFar, sao::ClipDepth::ZeroToOne, false);
  sao::ParamBlock p;
  ASSERT_TRUE(sao::computeConstants(sao::Settings{}, cam, sao::DepthEncoding::LinearZ, p).ok());
  EXPECT_EQ(p.depth_mode, sao::gen::SAO_DEPTH_MODE_LINEAR);
  EXPECT_EQ(p.clip_info.y, 1.0f);
  EXPECT_EQ(p.clip_info.z, 0.0f);
}

TEST(Constants, BlurWeightsAreGaussianInTaps) {
  sao::Settings s;
  s.blur_radius = 4;
  sao::ParamBlock p;
  const auto cam = sao::perspectiveCamera(kFovy, 64, 64, kNear, kFar, sao::ClipDepth::ZeroToOne, false);
  ASSERT_TRUE(sao::computeConstants(s, cam, sao::DepthEncoding::Hardware, p).ok());
  EXPECT_FLOAT_EQ(p.blur_weights_1_4.x, float(std::exp(-2.0 / 16.0)));
  EXPECT_FLOAT_EQ(p.blur_weights_1_4.w, float(std::exp(-2.0)));
  EXPECT_EQ(p.blur_weights_5_8.x, 0.0f) << "taps beyond R weigh nothing";
}

TEST(Spiral, TurnsAreCoprimeAndMatchKnownGoodValues) {
  for (int s = 2; s <= 64; ++s) {
    const int t = sao::spiralTurns(s);
    EXPECT_GE(t, 1);
    EXPECT_LT(t, s);
    EXPECT_EQ(std::gcd(t, s), 1) << "s=" << s;
  }
  EXPECT_EQ(sao::spiralTurns(1), 1);
  // G3D's table (the shipped choice): the paper's s = 9 (tau 2, the mirror image of its 7) and 16.
  EXPECT_EQ(sao::spiralTurns(9), 2);
  EXPECT_EQ(sao::spiralTurns(16), 7);
  // The lattice criterion: coprime and below s too, and the same lattice as the table at 9, 11, 32.
  for (int s = 2; s <= 64; ++s) {
    const int t = sao::latticeSpiralTurns(s);
    EXPECT_LT(t, s);
    EXPECT_EQ(std::gcd(t, s), 1) << "s=" << s;
  }
  for (int s : {9, 11, 32}) EXPECT_EQ(sao::latticeSpiralTurns(s), sao::spiralTurns(s)) << "s=" << s;
  EXPECT_EQ(sao::latticeSpiralTurns(16), 3);
}

// Eq. 6, as the block holds it for ao_sample: tap 0's alpha_0 * tau turns mod 1 in 2^-32 turns
// (alpha_0 = 0.5 / s, to the 24 bits the shader keeps), and the step (cos, sin)(2 pi tau / s) that
// turns each tap's direction into the next one's. Walked in float as the shader does, every tap's
// direction stays within 2e-6 rad of eq. 6's angle (i + 0.5) tau / s turns and within 2e-6 of unit
// length, for every s (measured: 1.4e-6 rad, 1.7e-6): a tap h pixels away moves less than h * 4e-6
// pixels (0.26 px at the largest radius the shader allows, 65536 px).
TEST(Spiral, TapTurnAndStepInTheBlockAreEq6) {
  auto cam = sao::perspectiveCamera(kFovy, 640, 360, kNear, kFar, sao::ClipDepth::ZeroToOne, false);
  double worstAngle = 0, worstLength = 0;
  for (int samples = 1; samples <= sao::gen::SAO_MAX_SAMPLES; ++samples) {
    sao::Settings s;
    s.samples = samples;
    sao::ParamBlock p;
    ASSERT_TRUE(sao::computeConstants(s, cam, sao::DepthEncoding::Hardware, p).ok());
    const std::uint32_t turn = p.tap_turn0;
    EXPECT_EQ(turn & 0xFFu, 0u);
    EXPECT_NEAR(double(turn) / 4294967296.0, std::fmod(0.5 / samples * p.spiral_turns, 1.0), 1.0 / 16777216.0)
        << "s=" << samples;
    EXPECT_EQ(turn, sao::spiralTapTurn(0, samples, p.spiral_turns));
    const double step = 2 * std::numbers::pi * p.spiral_turns / samples;
    EXPECT_EQ(p.tap_step.x, float(std::cos(step))) << "s=" << samples;
    EXPECT_EQ(p.tap_step.y, float(std::sin(step))) << "s=" << samples;

    const double theta0 = double(std::int32_t(turn) >> 8) * (2 * std::numbers::pi / 16777216.0);
    float ux = float(std::cos(theta0)), uy = float(std::sin(theta0));
    for (int i = 0; i < samples; ++i) {
      const double want = 2 * std::numbers::pi * std::fmod((i + 0.5) / samples * p.spiral_turns, 1.0);
      const double error = std::remainder(std::atan2(double(uy), double(ux)) - want, 2 * std::numbers::pi);
      worstAngle = std::max(worstAngle, std::abs(error));
      worstLength = std::max(worstLength, std::abs(std::hypot(double(ux), double(uy)) - 1.0));
      const float x = p.tap_step.x * ux - p.tap_step.y * uy;  // sao_spiral_step
      const float y = p.tap_step.y * ux + p.tap_step.x * uy;
      ux = x;
      uy = y;
    }
  }
  std::printf("spiral walk, s = 1..64: largest angle error %.3g rad, largest |u| - 1 %.3g\n", worstAngle, worstLength);
  EXPECT_LT(worstAngle, 2e-6);
  EXPECT_LT(worstLength, 2e-6);
}

// The matrix alone cannot tell [-1,1] from [0,1]: a standard GL matrix read as [0,1] is a valid
// projection whose near plane is 2fn/(f+n) (2n with an infinite far plane); a reversed one keeps
// its near plane and moves its far plane. expectedNear / expectedFar catch the mix-up.
TEST(Camera, ExpectedPlanesCatchAClipRangeThatContradictsTheMatrix) {
  for (double far : {kFar, double(INFINITY)}) {
    auto gl = sao::perspectiveCamera(kFovy, 640, 480, kNear, far, sao::ClipDepth::NegativeOneToOne, false);
    sao::DepthModel m;
    auto wrong = gl;
    wrong.clipDepth = sao::ClipDepth::ZeroToOne;
    ASSERT_TRUE(sao::analyze(wrong, m).ok()) << "without expectedNear the mix-up is undetectable";
    const double misread = std::isinf(far) ? 2 * kNear : 2 * far * kNear / (far + kNear);
    EXPECT_NEAR(m.nearDistance, misread, 1e-12);
    wrong.expectedNear = kNear;
    const sao::Status st = sao::analyze(wrong, m);
    EXPECT_EQ(st.code, sao::StatusCode::InvalidCamera);
    char expectedText[64];
    std::snprintf(expectedText, sizeof expectedText, "has its near plane at %g,", misread);
    EXPECT_NE(st.message.find(expectedText), std::string::npos) << st.message;
    EXPECT_NE(st.message.find("check clipDepth"), std::string::npos) << st.message;
    gl.expectedNear = kNear;
    gl.expectedFar = far;
    EXPECT_TRUE(sao::analyze(gl, m).ok()) << "the right convention passes";
    gl.expectedNear = kNear * (1 + 1e-5);  // a matrix built in float still passes
    EXPECT_TRUE(sao::analyze(gl, m).ok());
    gl.expectedNear = -1;
    EXPECT_NE(sao::analyze(gl, m).message.find("expectedNear must be >= 0"), std::string::npos);
  }
  // Reversed-Z, finite far, GL [-1,1] read as [0,1]: the near plane survives the misreading, the
  // far plane moves to 2fn/(f+n) (ndc 0 is halfway in 1/z); only expectedFar tells.
  auto reversed = sao::perspectiveCamera(kFovy, 640, 480, kNear, kFar, sao::ClipDepth::NegativeOneToOne, true);
  reversed.clipDepth = sao::ClipDepth::ZeroToOne;
  reversed.expectedNear = kNear;
  sao::DepthModel m;
  ASSERT_TRUE(sao::analyze(reversed, m).ok()) << sao::analyze(reversed, m).message;
  EXPECT_NEAR(m.farDistance, 2 * kFar * kNear / (kFar + kNear), 1e-9);
  reversed.expectedFar = kFar;
  EXPECT_NE(sao::analyze(reversed, m).message.find("has its far plane at"), std::string::npos);
  // An infinite expected far plane is not met by any finite one.
  auto finite = sao::perspectiveCamera(kFovy, 640, 480, kNear, kFar, sao::ClipDepth::ZeroToOne, false);
  finite.expectedFar = INFINITY;
  EXPECT_NE(sao::analyze(finite, m).message.find("has its far plane at 100, not at expectedFar = inf"), std::string::npos)
      << sao::analyze(finite, m).message;

  auto ortho = sao::orthographicCamera(2.0, 640, 480, kNear, kFar, sao::ClipDepth::ZeroToOne, false);
  ortho.expectedNear = kNear;
  ortho.expectedFar = kFar;
  EXPECT_TRUE(sao::analyze(ortho, m).ok());
  ortho.clipDepth = sao::ClipDepth::NegativeOneToOne;
  EXPECT_EQ(sao::analyze(ortho, m).code, sao::StatusCode::InvalidCamera);
}

// A matrix built for one clip range and declared with the other comes out with a wrong far plane:
// the message names the clip depth it was read with, not only the far plane (issue 19).
TEST(Camera, WrongClipDepthIsNamedWhenTheFarPlaneComesOutWrong) {
  struct Case {
    sao::ClipDepth built;
    double far;
    const char* declared;
  };
  for (const Case& c : {Case{sao::ClipDepth::NegativeOneToOne, INFINITY, "clipDepth = [0,1]"},
                        Case{sao::ClipDepth::ZeroToOne, INFINITY, "clipDepth = [-1,1]"},
                        Case{sao::ClipDepth::ZeroToOne, kFar, "clipDepth = [-1,1]"}}) {
    auto cam = sao::perspectiveCamera(kFovy, 640, 480, kNear, c.far, c.built, /*reversedZ=*/true);
    cam.clipDepth = c.built == sao::ClipDepth::ZeroToOne ? sao::ClipDepth::NegativeOneToOne : sao::ClipDepth::ZeroToOne;
    sao::DepthModel m;
    const sao::Status st = sao::analyze(cam, m);
    EXPECT_EQ(st.code, sao::StatusCode::InvalidCamera) << st.message;
    EXPECT_NE(st.message.find(c.declared), std::string::npos) << st.message;
    EXPECT_NE(st.message.find("check clipDepth"), std::string::npos) << st.message;
  }
}

TEST(Camera, RejectsMatricesThatContradictTheirConvention) {
  auto standard = sao::perspectiveCamera(kFovy, 640, 480, kNear, kFar, sao::ClipDepth::ZeroToOne, false);
  sao::DepthModel m;
  auto cam = standard;
  cam.reversedZ = true;
  sao::Status st = sao::analyze(cam, m);
  EXPECT_EQ(st.code, sao::StatusCode::InvalidCamera);
  EXPECT_NE(st.message.find("reversedZ = false"), std::string::npos) << st.message;

  cam = standard;
  cam.infiniteFar = true;
  st = sao::analyze(cam, m);
  EXPECT_NE(st.message.find("infinite far plane, but the projection read with clipDepth = [0,1] has a far plane"),
            std::string::npos)
      << st.message;

  cam = sao::perspectiveCamera(kFovy, 640, 480, kNear, INFINITY, sao::ClipDepth::ZeroToOne, false);
  cam.infiniteFar = false;
  EXPECT_NE(sao::analyze(cam, m).message.find("set infiniteFar = true"), std::string::npos);

  cam = standard;
  cam.projection[3 * 4 + 2] = -cam.projection[3 * 4 + 2];  // near plane behind the eye
  EXPECT_EQ(sao::analyze(cam, m).code, sao::StatusCode::InvalidCamera);

  cam = standard;
  cam.projection[5] = std::nan("");
  EXPECT_NE(sao::analyze(cam, m).message.find("non-finite"), std::string::npos);

  cam = standard;
  cam.kind = sao::ProjectionKind::Orthographic;
  EXPECT_NE(sao::analyze(cam, m).message.find("declared orthographic"), std::string::npos);

  cam = standard;
  cam.width = 0;
  EXPECT_EQ(sao::analyze(cam, m).code, sao::StatusCode::InvalidCamera);

  cam = standard;
  cam.metersToViewUnits = 0;
  EXPECT_EQ(sao::analyze(cam, m).code, sao::StatusCode::InvalidCamera);
  cam.metersToViewUnits = 1e7;
  EXPECT_NE(sao::analyze(cam, m).message.find("outside the supported range"), std::string::npos);

  // A finite far plane 1e8 times the near distance is finite, not "infinite".
  cam = sao::perspectiveCamera(kFovy, 640, 480, 1e-4, 1e4, sao::ClipDepth::ZeroToOne, false);
  ASSERT_TRUE(sao::analyze(cam, m).ok()) << sao::analyze(cam, m).message;
  EXPECT_NEAR(m.farDistance, 1e4, 1e-2);
}

}  // namespace
