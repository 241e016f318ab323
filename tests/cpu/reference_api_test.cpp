// sao::cpu as an API and as an emulation: validation, thread-count independence, the planned
// passes and their structural invariants (Table 1 MIPs, 2x2 quads, output rounding).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "untuned_settings.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::Precision;

// ---- Thread count independence

void expectIdentical(const cpu::Result& a, const cpu::Result& b) {
  ASSERT_EQ(a.csz.size(), b.csz.size());
  for (std::size_t m = 0; m < a.csz.size(); ++m) EXPECT_TRUE(sameBits(a.csz[m], b.csz[m])) << "csz level " << m;
  ASSERT_EQ(a.csz2.size(), b.csz2.size());
  for (std::size_t m = 0; m < a.csz2.size(); ++m) EXPECT_TRUE(sameBits(a.csz2[m], b.csz2[m])) << "csz2 level " << m;
  EXPECT_TRUE(sameBits(a.aoRaw, b.aoRaw)) << "ao_raw";
  const auto low = static_cast<std::size_t>(gen::ResourceId::ao_low);
  ASSERT_EQ(a.images[low].size(), b.images[low].size());
  for (std::size_t m = 0; m < a.images[low].size(); ++m) EXPECT_TRUE(sameBits(a.images[low][m], b.images[low][m])) << "ao_low";
  EXPECT_TRUE(sameBits(a.ao, b.ao)) << "ao";
}

TEST(Threads, AnyCountGivesIdenticalBits) {
  // Odd viewport (partial work groups and quads), guard band, both layers and user normals, so
  // every pass and every variant-dependent path runs.
  const Camera camera = testCamera(6, 1000.0, ClipDepth::NegativeOneToOne, false, 157, 89);
  const Scene scene = sphereOnPlaneScene();
  const DepthImage depth = renderDepth(scene, camera, DepthFormat::D24);
  const DepthImage depth2 = renderDepth(scene, camera, DepthFormat::D24, 1);
  const FloatImage normals = renderNormals(scene, camera);
  for (const cpu::Inputs& inputs : {cpu::Inputs{&depth}, cpu::Inputs{&depth, &depth2, &normals}}) {
    for (Precision precision : {Precision::Float, Precision::Double}) {
      SCOPED_TRACE(std::string(cpu::toString(precision)) + (inputs.depth2 ? " two layers + normals" : " one layer"));
      const cpu::Result one = runOrFail(Settings{}, camera, inputs, precision, 1);
      ASSERT_FALSE(one.ao.data.empty());
      for (unsigned threads : {2u, 7u, 33u}) {
        SCOPED_TRACE(std::to_string(threads) + " threads");
        expectIdentical(one, runOrFail(Settings{}, camera, inputs, precision, threads));
      }
    }
  }
}

// ---- Bad input returns a Status that names the problem

class BadInput : public ::testing::Test {
 protected:
  Camera camera = testCamera(4);
  DepthImage depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D24);

  Status runWith(const cpu::Inputs& inputs, const Settings& settings = {}) {
    cpu::Result r;
    r.ao = FloatImage(Extent{2, 2}, 1);  // must be cleared on error
    const Status st = cpu::run(settings, camera, inputs, cpu::Options{}, r);
    EXPECT_TRUE(r.ao.data.empty() && r.csz.empty() && r.plan.passes.empty()) << "out is reset on error";
    return st;
  }
};

TEST_F(BadInput, NullDepth) {
  const Status st = runWith({nullptr});
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("depth"), std::string::npos) << st.message;
}

TEST_F(BadInput, WrongExtent) {
  Camera noGuard = camera;
  noGuard.guardBand = 0;
  const DepthImage small = renderDepth(sphereOnPlaneScene(), noGuard, DepthFormat::D24);  // forgot the guard band
  const Status st = runWith({&small});
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("160x90"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("168x98"), std::string::npos) << st.message;
}

TEST_F(BadInput, EmptyDepth) {
  const DepthImage empty;
  EXPECT_EQ(runWith({&empty}).code, StatusCode::InvalidInput);
}

TEST_F(BadInput, TexelCountDisagreesWithExtent) {
  DepthImage truncated = depth;
  truncated.texels.pop_back();
  const Status st = runWith({&truncated});
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("texels"), std::string::npos) << st.message;
}

TEST_F(BadInput, UnknownDepthFormat) {
  DepthImage odd = depth;
  odd.format = static_cast<DepthFormat>(42);
  EXPECT_EQ(runWith({&odd}).code, StatusCode::UnsupportedFormat);
}

TEST_F(BadInput, MismatchedDepth2Format) {
  const DepthImage depth2 = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D32F, 1);
  const Status st = runWith({&depth, &depth2});
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("depth2 is D32F"), std::string::npos) << st.message;
}

TEST_F(BadInput, WrongDepth2Extent) {
  DepthImage depth2 = depth;
  depth2.extent.width -= 1;
  depth2.texels.resize(std::size_t(depth2.extent.width) * depth2.extent.height);
  const Status st = runWith({&depth, &depth2});
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("depth2"), std::string::npos) << st.message;
}

TEST_F(BadInput, NormalsWithWrongChannelsOrExtent) {
  const FloatImage rgb(inputExtent(camera), 3);
  EXPECT_EQ(runWith({&depth, nullptr, &rgb}).code, StatusCode::UnsupportedFormat);
  const FloatImage small(Extent{camera.width, camera.height}, 4);
  const Status st = runWith({&depth, nullptr, &small});
  EXPECT_EQ(st.code, StatusCode::InvalidInput);
  EXPECT_NE(st.message.find("normals"), std::string::npos) << st.message;
}

TEST_F(BadInput, SettingsAndCameraAreValidated) {
  Settings bad;
  bad.samples = 0;
  EXPECT_EQ(runWith({&depth}, bad).code, StatusCode::InvalidSetting);
  bad = Settings{};
  bad.radius = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(runWith({&depth}, bad).code, StatusCode::InvalidSetting);
  camera.reversedZ = true;  // contradicts the matrix
  EXPECT_EQ(runWith({&depth}).code, StatusCode::InvalidCamera);
}

TEST_F(BadInput, ExcludedVariantCombination) {
  Settings noHierarchy;
  noHierarchy.use_z_hierarchy = false;  // Z_HIERARCHY=0 with TWO_LAYER=1 is never compiled
  EXPECT_EQ(runWith({&depth, &depth}, noHierarchy).code, StatusCode::InvalidInput);
}

// ---- The planned passes run, and only those

TEST(Passes, FollowThePlan) {
  const Camera camera = testCamera(8);
  const DepthImage depth = renderDepth(stairsScene(), camera, DepthFormat::D32F);
  Settings s = test::untunedDefaults();
  {
    const cpu::Result r = runOrFail(s, camera, {&depth}, Precision::Float);
    ASSERT_GT(r.plan.cszLevels, 1u);
    EXPECT_EQ(r.csz.size(), r.plan.cszLevels);
    EXPECT_EQ(r.params.max_mip + 1, int(r.plan.cszLevels));
    EXPECT_TRUE(r.csz2.empty());
    const auto& low = r.images[static_cast<std::size_t>(gen::ResourceId::ao_low)];
    ASSERT_EQ(low.size(), 1u) << "the blur's (A, key) image";
    EXPECT_EQ(low[0].extent, r.plan.aoExtent);
    EXPECT_EQ(low[0].channels, 2u);
    EXPECT_EQ(r.ao.extent, r.plan.aoExtent);
    EXPECT_EQ(r.csz[0].extent, r.plan.inputExtent);
  }
  {
    cpu::Result r;
    ASSERT_TRUE(cpu::run(s, camera, {&depth}, cpu::Options{Precision::Float, 2, true}, r).ok());
    EXPECT_EQ(r.timings.method, TimingMethod::CpuClock);
    ASSERT_EQ(r.timings.passes.size(), r.plan.passes.size());
    for (std::size_t i = 0; i < r.plan.passes.size(); ++i) {
      EXPECT_EQ(r.timings.passes[i].pass, gen::pass(r.plan.passes[i].pass).name);
      EXPECT_GE(r.timings.passes[i].milliseconds, 0.0);
    }
    EXPECT_EQ(runOrFail(s, camera, {&depth}, Precision::Float).timings.method, TimingMethod::None);
  }
  s.use_z_hierarchy = false;
  {
    const cpu::Result r = runOrFail(s, camera, {&depth}, Precision::Float);
    EXPECT_EQ(r.plan.cszLevels, 1u);
    EXPECT_EQ(r.csz.size(), 1u) << "no mips pass without the hierarchy";
  }
  // Without blur at full resolution ao_sample_output writes the output itself (no ao_raw). With
  // temporal accumulation ao_sample and the output pass run instead (ao_sample writes the history),
  // and on the first frame (no history: the blend is this frame's sum exactly) the output pass
  // copies ao_raw's A: both paths give the same output, bit for bit.
  s = test::untunedDefaults();
  s.blur_radius = 0;
  Camera still = camera;
  still.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // temporal needs it
  Settings viaRaw = s;
  viaRaw.temporal = true;
  for (Precision precision : {Precision::Float, Precision::Double}) {
    const cpu::Result direct = runOrFail(s, still, {&depth}, precision);
    ASSERT_EQ(direct.plan.passes.back().pass, gen::PassId::ao_sample_output);
    EXPECT_TRUE(direct.aoRaw.data.empty());
    EXPECT_TRUE(direct.images[static_cast<std::size_t>(gen::ResourceId::ao_low)].empty());
    const cpu::Result r = runOrFail(viaRaw, still, {&depth}, precision);
    ASSERT_EQ(r.plan.passes.back().pass, gen::PassId::output);
    EXPECT_TRUE(r.images[static_cast<std::size_t>(gen::ResourceId::ao_low)].empty());
    std::size_t occluded = 0;
    for (std::uint32_t y = 0; y < r.ao.extent.height; ++y)
      for (std::uint32_t x = 0; x < r.ao.extent.width; ++x) {
        const float a = r.aoRaw.at(x, y, 0);
        ASSERT_EQ(r.ao.at(x, y), precision == Precision::Float ? cpu::roundToHalfAsShader(a) : a);
        ASSERT_EQ(std::bit_cast<std::uint32_t>(direct.ao.at(x, y)), std::bit_cast<std::uint32_t>(r.ao.at(x, y)))
            << x << "," << y;
        occluded += a < 0.9f;
      }
    EXPECT_GT(occluded, 100u) << "some pixels to compare on";
  }
}

// ---- Structural invariants of the emulation

TEST(Mips, RotatedGridCopiesOfTheLevelAbove) {
  const Camera camera = testCamera(8, 1000.0, ClipDepth::NegativeOneToOne, false, 157, 89);
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D24);
  const cpu::Result r = runOrFail(Settings{}, camera, {&depth}, Precision::Float);
  ASSERT_GE(r.csz.size(), 3u);
  const Extent e0 = r.csz[0].extent;
  for (std::size_t m = 1; m < r.csz.size(); ++m) {
    const FloatImage &prev = r.csz[m - 1], &cur = r.csz[m];
    ASSERT_EQ(cur.extent, (Extent{std::max(1u, e0.width >> m), std::max(1u, e0.height >> m)}));
    for (std::uint32_t y = 0; y < cur.extent.height; ++y)
      for (std::uint32_t x = 0; x < cur.extent.width; ++x) {
        const std::uint32_t sx = std::min(2 * x + ((y & 1) ^ 1), prev.extent.width - 1);
        const std::uint32_t sy = std::min(2 * y + ((x & 1) ^ 1), prev.extent.height - 1);
        ASSERT_EQ(cur.at(x, y), prev.at(sx, sy)) << "level " << m << " texel " << x << "," << y;
      }
  }
}

TEST(LinearZ, MatchesTheAnalyticDepth) {
  const Scene scene = stairsScene();
  // Reversed-Z D32F: the float precision of depth is nearly uniform in relative z.
  const Camera camera = testCamera(4, kInfinity, ClipDepth::ZeroToOne, true);
  const std::vector<double> z = renderZ(scene, camera);
  const DepthImage depth = renderDepth(scene, camera, DepthFormat::D32F);
  const DepthImage linear = renderDepth(scene, camera, DepthFormat::LinearZ);
  const cpu::Result hw = runOrFail(Settings{}, camera, {&depth}, Precision::Float);
  const cpu::Result lin = runOrFail(Settings{}, camera, {&linear}, Precision::Float);
  ASSERT_EQ(hw.params.depth_mode, gen::SAO_DEPTH_MODE_PERSPECTIVE);
  ASSERT_EQ(lin.params.depth_mode, gen::SAO_DEPTH_MODE_LINEAR);
  for (std::size_t i = 0; i < z.size(); ++i) {
    ASSERT_EQ(lin.csz[0].data[i], float(z[i])) << "linear z passes through unchanged";
    if (z[i] == 0.0) {
      ASSERT_EQ(hw.csz[0].data[i], 0.0f);
      continue;
    }
    ASSERT_NEAR(hw.csz[0].data[i], z[i], 1e-6 * std::abs(z[i])) << "texel " << i;
  }
}

TEST(LinearZ, UnormDepthIsReadLikeMesa) {
  // Float models the texture unit of Mesa's llvmpipe / lavapipe: float(v) * float(1 / (2^24 - 1)),
  // which turns the D24 texel just below the clear value into 1.0, i.e. sky. Double reads the
  // exact v / (2^24 - 1) < 1: geometry just in front of the far plane.
  const Camera camera = testCamera(0);
  DepthImage depth;
  depth.extent = inputExtent(camera);
  depth.format = DepthFormat::D24;
  depth.texels.assign(std::size_t(depth.extent.width) * depth.extent.height, 0xFFFFFEu);
  const cpu::Result f = runOrFail(Settings{}, camera, {&depth}, Precision::Float);
  const cpu::Result d = runOrFail(Settings{}, camera, {&depth}, Precision::Double);
  EXPECT_EQ(f.csz[0].data[0], 0.0f);
  EXPECT_LT(d.csz[0].data[0], -100.0f);
  // Any other texel: eq. 2 in float on that read, (d*c1 + c2) first, then c0 / that.
  depth.texels.assign(depth.texels.size(), 0xABCDEFu);
  const cpu::Result g = runOrFail(Settings{}, camera, {&depth}, Precision::Float);
  const float dRead = float(0xABCDEFu) * float(1.0 / 16777215.0);
  const gen::Float4 c = g.params.clip_info;
  const float den = dRead * c.y + c.z;
  EXPECT_EQ(g.csz[0].data[0], c.x / den);
}

TEST(Reconstruction, QuadsThatMixFullyShareOneValue) {
  // ao_raw = mix along x, then along y: when all four members of an aligned quad are geometry
  // and both x pairs and both y pairs are within the threshold, all four get the same value.
  const Camera camera = testCamera(8);
  const DepthImage depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D32F);
  for (Precision precision : {Precision::Float, Precision::Double}) {
    const cpu::Result r = runOrFail(Settings{}, camera, {&depth}, precision);
    const float thr = r.params.quad_edge_threshold;
    const FloatImage& a = r.aoRaw;
    auto close = [&](std::uint32_t x0, std::uint32_t y0, std::uint32_t x1, std::uint32_t y1) {
      const float z0 = a.at(x0, y0, 1), z1 = a.at(x1, y1, 1);
      return z0 < 0 && z1 < 0 && std::abs(z0 - z1) < thr;
    };
    int mixed = 0, differing = 0;
    for (std::uint32_t y = 0; y + 1 < a.extent.height; y += 2)
      for (std::uint32_t x = 0; x + 1 < a.extent.width; x += 2) {
        if (!(close(x, y, x + 1, y) && close(x, y + 1, x + 1, y + 1) && close(x, y, x, y + 1) &&
              close(x + 1, y, x + 1, y + 1)))
          continue;
        ++mixed;
        const float v = a.at(x, y, 0);
        differing += !(a.at(x + 1, y, 0) == v && a.at(x, y + 1, 0) == v && a.at(x + 1, y + 1, 0) == v);
      }
    EXPECT_GT(mixed, 100) << "the scene must have fully mixing quads";
    EXPECT_EQ(differing, 0);
  }
}

TEST(Reconstruction, KeysAreTheCentreDepthInsideAndAtOddEdges) {
  // An odd viewport leaves half-empty quads and work groups at the right and top edges.
  const Camera camera = testCamera(3, 1000.0, ClipDepth::NegativeOneToOne, false, 95, 53);
  const DepthImage depth = renderDepth(rodsScene(), camera, DepthFormat::D32F);
  const cpu::Result r = runOrFail(test::untunedDefaults(), camera, {&depth}, Precision::Float);  // full resolution
  for (std::uint32_t y = 0; y < r.aoRaw.extent.height; ++y)
    for (std::uint32_t x = 0; x < r.aoRaw.extent.width; ++x) {
      ASSERT_EQ(r.aoRaw.at(x, y, 1), r.csz[0].at(x + 3, y + 3));
      const float A = r.aoRaw.at(x, y, 0);
      ASSERT_TRUE(A >= 0.0f && A <= 1.0f) << A;
    }
  ASSERT_TRUE(allFinite(r.ao));
}

// ---- Output rounding

TEST(Output, FloatIsBinary16DoubleIsNot) {
  const Camera camera = testCamera(8);
  const DepthImage depth = renderDepth(creaseScene(2.0), camera, DepthFormat::D32F);
  const cpu::Result f = runOrFail(Settings{}, camera, {&depth}, Precision::Float);
  const cpu::Result d = runOrFail(Settings{}, camera, {&depth}, Precision::Double);
  int notHalf = 0;
  for (float a : f.ao.data) {
    ASSERT_TRUE(a >= 0.0f && a <= 1.0f);
    ASSERT_EQ(cpu::quantizeHalf(a), a);
  }
  for (float a : d.ao.data) notHalf += cpu::quantizeHalf(a) != a;
  EXPECT_GT(notHalf, int(d.ao.data.size() / 2)) << "Double returns the unrounded A";
}

TEST(Output, HalfHelpers) {
  EXPECT_EQ(cpu::quantizeHalf(1.0f), 1.0f);
  EXPECT_EQ(cpu::quantizeHalf(1.0f / 3.0f), 0.333251953125f);
  EXPECT_EQ(cpu::quantizeHalf(1.0f + 1.0f / 2048.0f), 1.0f) << "tie to even";
  EXPECT_EQ(cpu::quantizeHalf(1.0f + 3.0f / 2048.0f), 1.0f + 4.0f / 2048.0f) << "tie to even";
  EXPECT_EQ(cpu::quantizeHalf(-0.1f), -0.0999755859375f);
  EXPECT_EQ(cpu::quantizeHalf(65504.0f), 65504.0f);
  EXPECT_EQ(cpu::quantizeHalf(65519.0f), 65504.0f);
  EXPECT_EQ(cpu::quantizeHalf(65520.0f), std::numeric_limits<float>::infinity());
  EXPECT_EQ(cpu::quantizeHalf(std::ldexp(3.0f, -26)), std::ldexp(1.0f, -24)) << "subnormal half";
  EXPECT_EQ(cpu::quantizeHalf(std::ldexp(1.0f, -26)), 0.0f);
  EXPECT_TRUE(std::isnan(cpu::quantizeHalf(std::numeric_limits<float>::quiet_NaN())));
  // The bits: the usual encodings, and decoding them gives back quantizeHalf.
  EXPECT_EQ(cpu::halfBits(1.0f), 0x3C00u);
  EXPECT_EQ(cpu::halfBits(-2.0f), 0xC000u);
  EXPECT_EQ(cpu::halfBits(1.0f / 3.0f), 0x3555u);
  EXPECT_EQ(cpu::halfBits(65504.0f), 0x7BFFu);
  EXPECT_EQ(cpu::halfBits(1e6f), 0x7C00u);
  EXPECT_EQ(cpu::halfBits(-0.0f), 0x8000u);
  EXPECT_EQ(cpu::halfBits(std::ldexp(1.0f, -24)), 0x0001u);
  EXPECT_EQ(cpu::halfBits(std::ldexp(1023.0f, -24)), 0x03FFu);
  EXPECT_EQ(cpu::halfBits(std::ldexp(1.0f, -14)), 0x0400u);
  EXPECT_EQ(cpu::halfBits(std::numeric_limits<float>::quiet_NaN()) & 0x7E00u, 0x7E00u);
  auto decode = [](std::uint16_t h) {
    const int e = (h >> 10) & 0x1F, m = h & 0x3FF;
    const float v = e == 0 ? std::ldexp(float(m), -24) : std::ldexp(float(m + 1024), e - 25);
    return (h & 0x8000u) ? -v : v;
  };
  for (int i = -20000; i <= 20000; ++i) {
    const float x = std::sinh(float(i) * 6e-4f) * 1.37f;  // -> about +-2e5, through every binade
    if (std::isinf(cpu::quantizeHalf(x))) continue;
    ASSERT_EQ(decode(cpu::halfBits(x)), cpu::quantizeHalf(x)) << x;
  }
  // The shader's rounding: clamped, ties away from zero.
  EXPECT_EQ(cpu::roundToHalfAsShader(1.0f + 1.0f / 2048.0f), 1.0f) << "clamped to 1";
  EXPECT_EQ(cpu::roundToHalfAsShader(0.5f + 1.0f / 4096.0f), 0.5f + 1.0f / 2048.0f) << "tie away from zero";
  EXPECT_EQ(cpu::roundToHalfAsShader(-0.25f), 0.0f);
  EXPECT_EQ(cpu::roundToHalfAsShader(std::ldexp(1.0f, -30)), 0.0f);
}

}  // namespace
}  // namespace sao::test
