// The OpenGL backend reads its inputs as a region of larger textures (gl::Inputs::region): at odd
// offsets and sizes the result is bit for bit that of the region cropped into textures of its own
// (csz is identical, so everything after it is), it agrees with the CPU reference at the reference
// tests' bounds (p99.9 <= 2/255, max <= 4/255), the offset changes per render() without planning
// again, and a region outside any texture is refused.
#include <epoxy/gl.h>

#include <cstdint>
#include <string>

#include "gl_support.h"
#include "input_region.h"
#include "sao/cpu/reference.h"

namespace sao::gltest {
namespace {

using test::kRegionCases;
using test::RegionCase;

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

GlDepth formatOf(std::size_t caseIndex) {
  constexpr GlDepth kFormats[] = {GlDepth::D24, GlDepth::D32F, GlDepth::D16, GlDepth::R32F};
  return kFormats[caseIndex % 4];
}

struct Textures {
  GLuint depth = 0, depth2 = 0, normals = 0;
  Textures() = default;
  Textures(const DepthImage& d, const DepthImage* d2, const FloatImage* n, GlDepth format)
      : depth(uploadDepth(d, format)), depth2(d2 ? uploadDepth(*d2, format) : 0), normals(n ? uploadNormals(*n) : 0) {}
  ~Textures() {
    deleteTexture(depth);
    deleteTexture(depth2);
    deleteTexture(normals);
  }
  Textures(const Textures&) = delete;
  Textures& operator=(const Textures&) = delete;
  gl::Inputs inputs(GlDepth format, Offset offset) const {
    gl::Inputs in;
    in.depth = {depth, internalFormat(format)};
    in.depth2 = {depth2, depth2 ? internalFormat(format) : 0};
    in.normals = normals;
    in.region = offset;
    return in;
  }
};

struct Frame {
  FloatImage ao, raw, csz;
};

Frame renderOrFail(gl::Effect& effect, const Camera& camera, const gl::Inputs& in) {
  const Status st = effect.render(camera, Settings{}, in);
  EXPECT_TRUE(st.ok()) << st.message;
  if (!st.ok()) return {};
  return {readTexture(effect.aoTexture(), 1), readTexture(effect.texture(gen::ResourceId::ao_raw), 2),
          readTexture(effect.texture(gen::ResourceId::csz), 1)};
}

void expectSameBits(const Frame& a, const Frame& b) {
  EXPECT_TRUE(test::sameBits(a.csz, b.csz)) << "csz level 0";
  EXPECT_TRUE(test::sameBits(a.raw, b.raw)) << "ao_raw";
  EXPECT_TRUE(test::sameBits(a.ao, b.ao)) << "ao";
}

class Region : public GlTest, public ::testing::WithParamInterface<std::size_t> {};

TEST_P(Region, EqualsTheCroppedTextureAndAgreesWithTheCpuReference) {
  const RegionCase& rc = kRegionCases[GetParam()];
  const GlDepth format = formatOf(GetParam());
  const Camera cam = camera(rc.width, rc.height, rc.guard);
  const test::Scene scene = sceneByName("sphere");
  const bool allInputs = rc.width < 1000;  // two layers and normals on the smaller cases
  const DepthImage depth = test::renderDepth(scene, cam, cpuFormat(format));
  const DepthImage depth2 = allInputs ? test::renderDepth(scene, cam, cpuFormat(format), 1) : DepthImage{};
  const FloatImage normals = allInputs ? test::renderNormals(scene, cam) : FloatImage{};
  const DepthImage big = test::embedDepth(depth, rc.texture, rc.offset);
  const DepthImage big2 = allInputs ? test::embedDepth(depth2, rc.texture, rc.offset) : DepthImage{};
  const FloatImage bigNormals = allInputs ? test::embedNormals(normals, rc.texture, rc.offset) : FloatImage{};

  auto effect = makeEffect();
  const Textures cropped(depth, allInputs ? &depth2 : nullptr, allInputs ? &normals : nullptr, format);
  const Textures region(big, allInputs ? &big2 : nullptr, allInputs ? &bigNormals : nullptr, format);
  const Frame a = renderOrFail(*effect, cam, cropped.inputs(format, {}));
  const Frame b = renderOrFail(*effect, cam, region.inputs(format, rc.offset));
  ASSERT_FALSE(a.ao.data.empty());
  ASSERT_FALSE(b.ao.data.empty());
  EXPECT_EQ(b.csz.extent, test::inputExtent(cam)) << "csz keeps the camera's extent";
  EXPECT_EQ(effect->params().input_offset.x, std::int32_t(rc.offset.x));
  EXPECT_EQ(effect->params().input_offset.y, std::int32_t(rc.offset.y));
  expectSameBits(a, b);

  cpu::Inputs ci{&big, allInputs ? &big2 : nullptr, allInputs ? &bigNormals : nullptr, rc.offset};
  cpu::Result ref;
  const Status cst = cpu::run(Settings{}, cam, ci, cpu::Options{cpu::Precision::Float, 2}, ref);
  ASSERT_TRUE(cst.ok()) << cst.message;
  const std::string name = std::string("region_") + rc.name + "_" + toString(format);
  const Agreement f = compare(b.ao, ref.ao, 0, kWithin, kNever, name + "_final");
  const Agreement r = compare(b.raw, ref.aoRaw, 0, kWithin, kNever, name + "_raw");
  EXPECT_TRUE(acceptable(f)) << "final AO: max " << f.maxAbs * 255 << "/255, p99.9 " << f.p999 * 255 << "/255";
  EXPECT_TRUE(acceptable(r)) << "raw AO: max " << r.maxAbs * 255 << "/255, p99.9 " << r.p999 * 255 << "/255";
}

INSTANTIATE_TEST_SUITE_P(Cases, Region, ::testing::Range<std::size_t>(0, std::size(kRegionCases)),
                         [](const auto& info) { return std::string(kRegionCases[info.param].name); });

// Dynamic resolution moves the region every frame: render() takes the offset without planning,
// compiling or allocating again, and the texture read follows it.
TEST_F(Region, TheOffsetChangesPerRenderWithoutPlanningAgain) {
  const Camera cam = camera(61, 37, 3);
  const DepthImage depth = test::renderDepth(sceneByName("stairs"), cam, DepthFormat::D24);
  const DepthImage at35 = test::embedDepth(depth, {90, 60}, {3, 5});
  const DepthImage at2017 = test::embedDepth(depth, {90, 60}, {20, 17});
  auto effect = makeEffect();
  const Textures cropped(depth, nullptr, nullptr, GlDepth::D24);
  const Textures first(at35, nullptr, nullptr, GlDepth::D24), second(at2017, nullptr, nullptr, GlDepth::D24);
  const Frame reference = renderOrFail(*effect, cam, cropped.inputs(GlDepth::D24, {}));
  const gl::Stats before = effect->stats();
  for (int frame = 0; frame < 3; ++frame) {
    SCOPED_TRACE(frame);
    expectSameBits(reference, renderOrFail(*effect, cam, first.inputs(GlDepth::D24, {3, 5})));
    expectSameBits(reference, renderOrFail(*effect, cam, second.inputs(GlDepth::D24, {20, 17})));
  }
  EXPECT_EQ(effect->stats().textureAllocations, before.textureAllocations);
  EXPECT_EQ(effect->stats().programsCompiled, before.programsCompiled);
}

// A region that does not lie inside every texture: InvalidInput naming the input, its size, the
// extent the camera needs and the offset; the effect renders again afterwards.
TEST_F(Region, OutsideAnyTextureIsRefused) {
  const Camera cam = camera(41, 23, 3);  // needs 47x29
  const test::Scene scene = sceneByName("sphere");
  const DepthImage depth = test::renderDepth(scene, cam, DepthFormat::D24);
  const DepthImage depth2 = test::renderDepth(scene, cam, DepthFormat::D24, 1);
  const FloatImage normals = test::renderNormals(scene, cam);
  const DepthImage big = test::embedDepth(depth, {50, 31}, {3, 2});
  const DepthImage big2 = test::embedDepth(depth2, {50, 31}, {3, 2});
  const FloatImage bigNormals = test::embedNormals(normals, {50, 31}, {3, 2});
  auto effect = makeEffect();
  const Textures good(big, &big2, &bigNormals, GlDepth::D24);
  const Textures exact(depth, &depth2, &normals, GlDepth::D24);
  ASSERT_TRUE(effect->render(cam, Settings{}, good.inputs(GlDepth::D24, {3, 2})).ok());
  const gl::Stats before = effect->stats();

  struct Case {
    gl::Inputs in;
    const char* needle;
  };
  gl::Inputs mixedDepth2 = good.inputs(GlDepth::D24, {3, 2});
  mixedDepth2.depth2 = {exact.depth2, internalFormat(GlDepth::D24)};
  gl::Inputs mixedNormals = good.inputs(GlDepth::D24, {3, 2});
  mixedNormals.normals = exact.normals;
  const Case cases[] = {
      {good.inputs(GlDepth::D24, {4, 2}),
       "sao::gl: the depth input is 50x31, the camera needs 47x29 (the viewport 41x23 plus twice the guard band 3) "
       "at offset (4, 2), which ends at (51, 31): the region must lie inside the texture"},
      {good.inputs(GlDepth::D24, {3, 3}), "at offset (3, 3), which ends at (50, 32)"},
      {good.inputs(GlDepth::D24, {0xFFFFFFFFu, 0}), "at offset (4294967295, 0), which ends at (4294967342, 29)"},
      {exact.inputs(GlDepth::D24, {0, 1}), "the depth input is 47x29"},
      {mixedDepth2, "the depth2 input is 47x29"},
      {mixedNormals, "the normals input is 47x29"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.needle);
    const Status st = effect->render(cam, Settings{}, c.in);
    EXPECT_EQ(st.code, StatusCode::InvalidInput);
    EXPECT_NE(st.message.find(c.needle), std::string::npos) << st.message;
  }
  EXPECT_EQ(effect->stats().textureAllocations, before.textureAllocations);
  EXPECT_TRUE(effect->render(cam, Settings{}, good.inputs(GlDepth::D24, {3, 2})).ok());
}

}  // namespace
}  // namespace sao::gltest
