// The CPU reference reads its inputs as a region of larger images (cpu::Inputs::region): the result
// is bit for bit that of the region cropped into images of its own (both precisions, one and two
// layers, user normals), and a region that does not lie inside every image is refused.
#include <cstdint>
#include <limits>
#include <string>

#include "input_region.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::Precision;

void expectIdentical(const cpu::Result& a, const cpu::Result& b) {
  ASSERT_EQ(a.csz.size(), b.csz.size());
  for (std::size_t m = 0; m < a.csz.size(); ++m) EXPECT_TRUE(sameBits(a.csz[m], b.csz[m])) << "csz level " << m;
  ASSERT_EQ(a.csz2.size(), b.csz2.size());
  for (std::size_t m = 0; m < a.csz2.size(); ++m) EXPECT_TRUE(sameBits(a.csz2[m], b.csz2[m])) << "csz2 level " << m;
  EXPECT_TRUE(sameBits(a.aoRaw, b.aoRaw)) << "ao_raw";
  EXPECT_TRUE(sameBits(a.ao, b.ao)) << "ao";
}

DepthFormat formatOf(std::size_t caseIndex) {
  constexpr DepthFormat kFormats[] = {DepthFormat::D24, DepthFormat::D32F, DepthFormat::D16, DepthFormat::LinearZ};
  return kFormats[caseIndex % 4];
}

class Region : public ::testing::TestWithParam<std::size_t> {};

TEST_P(Region, EqualsTheCroppedInputBitForBit) {
  const RegionCase& rc = kRegionCases[GetParam()];
  const Camera camera = testCamera(rc.guard, 1000.0, ClipDepth::NegativeOneToOne, false, rc.width, rc.height);
  const Scene scene = sphereOnPlaneScene();
  const DepthFormat format = formatOf(GetParam());
  const DepthImage depth = renderDepth(scene, camera, format);
  const DepthImage big = embedDepth(depth, rc.texture, rc.offset);
  // The two-layer, user-normals configuration on the small cases (every input shares the region).
  const bool allInputs = rc.width < 1000;
  const DepthImage depth2 = allInputs ? renderDepth(scene, camera, format, 1) : DepthImage{};
  const FloatImage normals = allInputs ? renderNormals(scene, camera) : FloatImage{};
  const DepthImage big2 = allInputs ? embedDepth(depth2, rc.texture, rc.offset) : DepthImage{};
  const FloatImage bigNormals = allInputs ? embedNormals(normals, rc.texture, rc.offset) : FloatImage{};

  cpu::Inputs cropped{&depth}, region{&big};
  region.region = rc.offset;
  if (allInputs) {
    cropped = {&depth, &depth2, &normals};
    region = {&big, &big2, &bigNormals, rc.offset};
  }
  for (Precision precision : {Precision::Float, Precision::Double}) {
    SCOPED_TRACE(std::string(cpu::toString(precision)) + " " + toString(format));
    const cpu::Result a = runOrFail(Settings{}, camera, cropped, precision);
    const cpu::Result b = runOrFail(Settings{}, camera, region, precision);
    ASSERT_FALSE(a.ao.data.empty());
    EXPECT_EQ(b.params.input_offset.x, std::int32_t(rc.offset.x));
    EXPECT_EQ(b.params.input_offset.y, std::int32_t(rc.offset.y));
    EXPECT_EQ(b.csz[0].extent, inputExtent(camera)) << "csz keeps the camera's extent";
    expectIdentical(a, b);
  }
  // The junk around the region is read if the offset is ignored: the result would differ.
  const cpu::Result atOrigin = runOrFail(Settings{}, camera, cpu::Inputs{&big, nullptr, nullptr, Offset{}}, Precision::Float);
  // Without a declared region a larger image is refused: an undeclared guard band, or a wrong one,
  // must not be read silently from the image's corner.
  cpu::Result undeclared;
  const Status refused = cpu::run(Settings{}, camera, cpu::Inputs{&big}, cpu::Options{}, undeclared);
  EXPECT_FALSE(refused.ok());
  EXPECT_NE(refused.message.find("set Inputs::region"), std::string::npos) << refused.message;
  const cpu::Result a = runOrFail(Settings{}, camera, cpu::Inputs{&depth}, Precision::Float);
  if (rc.offset.x != 0 || rc.offset.y != 0) {
    EXPECT_FALSE(sameBits(atOrigin.csz[0], a.csz[0]));
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, Region, ::testing::Range<std::size_t>(0, std::size(kRegionCases)),
                         [](const auto& info) { return std::string(kRegionCases[info.param].name); });

// ---- A region that does not lie inside every image: InvalidInput naming the offset, the extent the
// camera needs and the image's size; nothing is clamped.

class RegionBadInput : public ::testing::Test {
 protected:
  Camera camera = testCamera(3, 1000.0, ClipDepth::NegativeOneToOne, false, 41, 23);  // needs 47x29
  DepthImage depth = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D24);

  Status runWith(const cpu::Inputs& inputs) {
    cpu::Result r;
    const Status st = cpu::run(Settings{}, camera, inputs, cpu::Options{}, r);
    if (!st.ok()) {
      EXPECT_TRUE(r.ao.data.empty() && r.csz.empty()) << "out is reset on error";
    }
    return st;
  }
  void expectRefused(const cpu::Inputs& inputs, std::initializer_list<const char*> needles) {
    const Status st = runWith(inputs);
    EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    for (const char* n : needles) EXPECT_NE(st.message.find(n), std::string::npos) << n << " in: " << st.message;
  }
};

TEST_F(RegionBadInput, OutsideTheImageIsRefused) {
  const DepthImage big = embedDepth(depth, {50, 31}, {3, 2});
  ASSERT_TRUE(runWith({&big, nullptr, nullptr, Offset{3, 2}}).ok());
  ASSERT_TRUE(runWith({&big, nullptr, nullptr, Offset{0, 0}}).ok()) << "a larger image at the origin";
  expectRefused({&big}, {"depth is 50x31", "47x29", "set Inputs::region"});
  expectRefused({&big, nullptr, nullptr, Offset{4, 2}}, {"depth is 50x31", "47x29", "offset (4, 2)", "ends at (51, 31)"});
  expectRefused({&big, nullptr, nullptr, Offset{3, 3}}, {"depth is 50x31", "offset (3, 3)", "ends at (50, 32)"});
  // No 32-bit wrap-around of offset + extent.
  constexpr std::uint32_t kMax = std::numeric_limits<std::uint32_t>::max();
  expectRefused({&big, nullptr, nullptr, Offset{kMax, 0}}, {"offset (4294967295, 0)", "ends at (4294967342, 29)"});
  expectRefused({&big, nullptr, nullptr, Offset{0, kMax - 10}}, {"depth is 50x31"});
  // The exact image at a non-zero offset is too small.
  expectRefused({&depth, nullptr, nullptr, Offset{1, 0}}, {"depth is 47x29", "offset (1, 0)"});
}

TEST_F(RegionBadInput, EveryInputMustHoldTheSharedRegion) {
  const DepthImage big = embedDepth(depth, {50, 31}, {3, 2});
  const DepthImage depth2 = renderDepth(sphereOnPlaneScene(), camera, DepthFormat::D24, 1);
  const FloatImage normals = renderNormals(sphereOnPlaneScene(), camera);
  const DepthImage big2 = embedDepth(depth2, {50, 31}, {3, 2});
  const FloatImage bigNormals = embedNormals(normals, {50, 31}, {3, 2});
  ASSERT_TRUE(runWith({&big, &big2, &bigNormals, Offset{3, 2}}).ok());
  // Layers and normals of the camera's exact extent cannot hold the region at (3, 2).
  expectRefused({&big, &depth2, nullptr, Offset{3, 2}}, {"depth2 is 47x29", "offset (3, 2)"});
  expectRefused({&big, nullptr, &normals, Offset{3, 2}}, {"normals are 47x29", "offset (3, 2)"});
  expectRefused({&big, &big2, &normals, Offset{3, 2}}, {"normals are 47x29"});
}

}  // namespace
}  // namespace sao::test
