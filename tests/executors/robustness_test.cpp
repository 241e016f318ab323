// Bad input on each API (docs/ROBUSTNESS.md): every setting NaN / +-inf / out of range, non-finite
// and degenerate cameras, sizes beyond the largest image side, empty viewports, a depth larger than
// the camera needs, two-channel normals with an xyz encoding. Each is refused with the documented
// code and a message naming the problem, by an effect that never rendered and by
// one that did (Vulkan: record(), which plans), allocating nothing; both then render what a new
// effect renders. Versions, feedback loops (an input also passed as the output), null handles and
// GL texture kinds stay in tests/gl/robustness_test.cpp and tests/vulkan/robustness_test.cpp.
#include <cmath>
#include <limits>

#include "harness.h"
#include "normal_encodings.h"

namespace sao::exectest {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using test::sameBits;

class Robustness : public ApiTest {
 protected:
  void SetUp() override {
    ApiTest::SetUp();
    good.camera = test::openglCamera(64, 36, 8);
    good.format = Depth::D24;
    depth = test::renderDepth(test::sphereOnPlaneScene(), good.camera, cpuFormat(good.format));
    good.depth = &depth;
    fresh = make();
    used = make();
    const Status st = used->render(good);
    ASSERT_TRUE(st.ok()) << st.message;
  }
  void TearDown() override {
    // Whatever came before, both effects still render what a new effect renders.
    auto reference = make();
    if (!HasFatalFailure() && reference->render(good).ok())
      for (Executor* e : {fresh.get(), used.get()}) {
        const Status st = e->render(good);
        EXPECT_TRUE(st.ok()) << "the effect is not usable after the bad frames: " << st.message;
        if (st.ok()) {
          EXPECT_TRUE(sameBits(e->output(), reference->output()));
        }
      }
    reference.reset();
    fresh.reset();
    used.reset();
    ApiTest::TearDown();
  }
  Frame with(const Settings& s) const {
    Frame f = good;
    f.settings = s;
    return f;
  }
  Frame with(const Camera& c) const {
    Frame f = good;
    f.camera = c;
    return f;
  }
  // `e` refuses `bad` with `code`, naming `needle`, and allocates nothing.
  static void expectRejected(Executor& e, const Frame& bad, StatusCode code, const std::string& needle) {
    const std::uint64_t allocations = e.imageAllocations();
    const Status st = e.render(bad);
    EXPECT_EQ(st.code, code) << toString(st.code) << ": " << st.message;
    EXPECT_NE(st.message.find(needle), std::string::npos) << "expected \"" << needle << "\" in: " << st.message;
    EXPECT_EQ(e.imageAllocations(), allocations) << st.message;
  }
  // ... by the effect that never rendered and by the one that did.
  void expectRejected(const Frame& bad, StatusCode code, const std::string& needle) {
    for (Executor* e : {fresh.get(), used.get()}) {
      SCOPED_TRACE(e == fresh.get() ? "never rendered" : "rendered");
      expectRejected(*e, bad, code, needle);
    }
  }

  DepthImage depth;
  Frame good;
  std::unique_ptr<Executor> fresh, used;
};

// Every setting NaN, +inf, -inf and just outside its range: InvalidSetting naming the setting.
TEST_P(Robustness, EverySettingNonFiniteOrOutOfRange) {
  int cases = 0;
  for (std::size_t i = 0; i < gen::kSettings.size(); ++i) {
    const SettingInfo& info = gen::kSettings[i];
    std::vector<double> values;
    if (info.type == gen::SettingType::Float) values = {kNaN, kInf, -kInf};
    if (info.type != gen::SettingType::Bool) values.insert(values.end(), {info.minValue - 1, info.maxValue + 1});
    for (double v : values) {
      Settings s;
      gen::setSettingValue(s, static_cast<SettingId>(i), v);
      SCOPED_TRACE(std::string(info.name) + " = " + std::to_string(v));
      expectRejected(with(s), StatusCode::InvalidSetting, std::string(info.name));
      ++cases;
    }
  }
  EXPECT_GE(cases, 40);
}

TEST_P(Robustness, NonFiniteAndDegenerateCameras) {
  for (int element : {0, 5, 10, 11, 14})
    for (double v : {kNaN, kInf}) {
      SCOPED_TRACE("projection element " + std::to_string(element) + " = " + std::to_string(v));
      Camera c = good.camera;
      c.projection[std::size_t(element)] = v;
      expectRejected(with(c), StatusCode::InvalidCamera, "non-finite");
    }
  for (double m : {kNaN, kInf, 0.0, -1.0, 1e-9, 1e9}) {
    SCOPED_TRACE("metersToViewUnits = " + std::to_string(m));
    Camera c = good.camera;
    c.metersToViewUnits = m;
    expectRejected(with(c), StatusCode::InvalidCamera, "metersToViewUnits");
  }
  Camera zero = good.camera;
  zero.projection.fill(0.0);
  expectRejected(with(zero), StatusCode::InvalidCamera, "");
}

// Sizes beyond the largest image side (the plan's kMaxImageSide; the device's limit is the same on
// llvmpipe and lavapipe) are refused before anything is allocated, with no 32-bit wrap-around.
TEST_P(Robustness, HugeAndEmptySizes) {
  const std::uint32_t beyond = kMaxImageSide + 1;
  struct Case {
    std::uint32_t w, h, guard;
    StatusCode code;
    const char* needle;
  };
  const Case cases[] = {
      {beyond, 36, 0, StatusCode::InvalidExtent, "exceeds"},
      {64, beyond, 0, StatusCode::InvalidExtent, "exceeds"},
      {kMaxImageSide - 8, 36, 8, StatusCode::InvalidExtent, "exceeds"},  // the guard band pushes it over
      {0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu, StatusCode::InvalidExtent, "exceeds"},
      {64, 36, 0x80000000u, StatusCode::InvalidExtent, "exceeds"},
      {0, 36, 8, StatusCode::InvalidCamera, "viewport size is 0x36"},
      {64, 0, 8, StatusCode::InvalidCamera, "viewport size is 64x0"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::to_string(c.w) + "x" + std::to_string(c.h) + " guard " + std::to_string(c.guard));
    Camera big = good.camera;  // the projection stays that of 64x36 (a valid perspective); only the sizes are wrong
    big.width = c.w;
    big.height = c.h;
    big.guardBand = c.guard;
    expectRejected(with(big), c.code, c.needle);
  }
  // A depth image larger than the camera's extent with no region declared, and a region one texel
  // beyond it (the caller's mistakes, not a huge allocation).
  DepthImage large;
  large.extent = {4096, 4096};
  large.format = depth.format;
  large.texels.assign(std::size_t(4096) * 4096, 0u);
  Frame f = good;
  f.depth = &large;
  expectRejected(*used, f, StatusCode::InvalidInput, "is 4096x4096, the camera needs 80x52");
  f.region = Offset{4096 - 79, 0};
  expectRejected(*used, f, StatusCode::InvalidInput, "is 4096x4096, the camera needs 80x52");
}

// A refused frame keeps the previous configuration (Vulkan: a failed record()): the output, its
// extent and the images stay, and the next frame renders as before.
TEST_P(Robustness, RefusedFramesKeepThePreviousConfiguration) {
  const FloatImage before = used->output();
  Settings nanRadius;
  nanRadius.radius = float(kNaN);
  Camera wide = good.camera, infinite = good.camera;
  wide.width = 0xFFFFFFFFu;
  infinite.projection[0] = kInf;
  for (const Frame& bad : {with(nanRadius), with(wide), with(infinite)}) {
    const std::uint64_t allocations = used->imageAllocations();
    const Status st = used->render(bad);
    EXPECT_FALSE(st.ok());
    EXPECT_FALSE(st.message.empty());
    EXPECT_EQ(used->imageAllocations(), allocations);
    EXPECT_EQ(used->output().extent, before.extent);
  }
  ASSERT_TRUE(used->render(good).ok());
  EXPECT_TRUE(sameBits(used->output(), before)) << "the effect renders as before the refused frames";
}

// Normals' channels against Camera::normalsEncoding: a two-channel image holds only the octahedral
// .xy, so an xyz encoding (which would read z = 0) is refused naming the encoding. Octahedral
// normals in RG16F and RG32F render with both octahedral encodings, and a frame refused for an xyz
// encoding keeps that configuration, which renders as before.
TEST_P(Robustness, TwoChannelNormalsNeedAnOctahedralEncoding) {
  const auto rotation = test::viewRotation(0.7, -0.4, 0.25);
  const FloatImage normals = test::renderNormals(test::sphereOnPlaneScene(), good.camera);
  const char* noun = api() == Api::Gl ? "texture" : "format";
  Frame f = good;
  f.camera.viewRotation = rotation;
  for (Texels texels : {Texels::RG16F, Texels::RG32F}) {
    f.normalsTexels = texels;
    f.normals = &normals;
    for (auto [encoding, name] :
         {std::pair{NormalsEncoding::CameraXyz, "CameraXyz"}, std::pair{NormalsEncoding::WorldXyz, "WorldXyz"}}) {
      f.camera.normalsEncoding = encoding;
      expectRejected(f, StatusCode::UnsupportedFormat,
                     std::string("(two channels) but Camera::normalsEncoding is ") + name +
                         ", which reads .xyz: use an octahedral encoding or a three- or four-channel " + noun);
    }
    for (NormalsEncoding encoding : {NormalsEncoding::CameraOctahedral, NormalsEncoding::WorldOctahedral}) {
      SCOPED_TRACE(int(encoding));
      const FloatImage encoded = test::encodeNormals(normals, encoding, rotation);
      f.normals = &encoded;
      f.camera.normalsEncoding = encoding;
      ASSERT_TRUE(used->render(f).ok());
      const FloatImage before = used->output();
      Frame bad = f;
      bad.camera.normalsEncoding = NormalsEncoding::WorldXyz;
      expectRejected(*used, bad, StatusCode::UnsupportedFormat,
                     "(two channels) but Camera::normalsEncoding is WorldXyz");
      ASSERT_TRUE(used->render(f).ok());
      EXPECT_TRUE(sameBits(used->output(), before)) << "the effect renders as before the refused frame";
    }
  }
}
SAO_INSTANTIATE_APIS(Robustness);

}  // namespace
}  // namespace sao::exectest
