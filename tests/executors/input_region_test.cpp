// The inputs as a region of larger images (Inputs::region): at odd offsets and sizes the result is
// bit for bit that of the region cropped into images of its own (csz is identical, so everything
// after it is), it agrees with the CPU reference at the agreement bounds, the offset changes per
// frame without planning, allocating or building again, and a region outside any image is refused.
// Each case under GL's and Vulkan's depth conventions.
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>

#include "harness.h"
#include "input_region.h"

namespace sao::exectest {
namespace {

using test::embedDepth;
using test::embedNormals;
using test::kRegionCases;

// GL's camera ([-1, 1], far 1000) or Vulkan's ([0, 1]: reversed and infinite, standard to 100 m for D16).
Camera cameraFor(bool opengl, std::uint32_t w, std::uint32_t h, std::uint32_t guard, Depth format) {
  if (opengl) return test::openglCamera(w, h, guard);
  return format == Depth::D16 ? test::vulkanCamera(w, h, guard, 100.0)
                              : test::vulkanCamera(w, h, guard, INFINITY, /*reversedZ=*/true);
}

// The cameras and formats the GL and Vulkan tests of one placement used.
struct Convention {
  const char* name;
  Camera camera;
  Depth format;
};
std::vector<Convention> conventions(std::uint32_t w, std::uint32_t h, std::uint32_t guard) {
  return {{"opengl_D24", test::openglCamera(w, h, guard), Depth::D24},
          {"vulkan_D32F", test::vulkanCamera(w, h, guard), Depth::D32F}};
}

struct Images {
  FloatImage ao, raw, csz;
};
Images read(Executor& e) { return {e.output(), e.image(gen::ResourceId::ao_raw), e.image(gen::ResourceId::csz)}; }

void expectSameBits(const Images& a, const Images& b) {
  EXPECT_TRUE(test::sameBits(a.csz, b.csz)) << "csz level 0";
  EXPECT_TRUE(test::sameBits(a.raw, b.raw)) << "ao_raw";
  EXPECT_TRUE(test::sameBits(a.ao, b.ao)) << "ao";
}

void expectOffset(Executor& e, Offset o) {
  EXPECT_EQ(e.params().input_offset.x, std::int32_t(o.x));
  EXPECT_EQ(e.params().input_offset.y, std::int32_t(o.y));
}

using Region = ApiCaseTest<std::size_t>;  // an index into kRegionCases
std::string caseName(std::size_t i) { return kRegionCases[i].name; }
std::vector<std::size_t> regionCases() {
  std::vector<std::size_t> v(std::size(kRegionCases));
  std::iota(v.begin(), v.end(), 0);
  return v;
}

TEST_P(Region, EqualsTheCroppedImageAndAgreesWithTheCpuReference) {
  const test::RegionCase& rc = kRegionCases[param()];
  constexpr Depth kFormats[] = {Depth::D24, Depth::D32F, Depth::D16, Depth::R32F};
  const Depth format = kFormats[param() % 4];
  const bool allInputs = rc.width < 1000;  // two layers and normals on the smaller cases
  const test::Scene scene = sceneByName("sphere");
  auto e = make();
  for (const bool opengl : {true, false}) {
    const Camera cam = cameraFor(opengl, rc.width, rc.height, rc.guard, format);
    const std::string name = std::string("region_") + rc.name + "_" + toString(format) + (opengl ? "_gl" : "_vk");
    SCOPED_TRACE(name);
    const DepthImage depth = test::renderDepth(scene, cam, cpuFormat(format));
    const DepthImage depth2 = allInputs ? test::renderDepth(scene, cam, cpuFormat(format), 1) : DepthImage{};
    const FloatImage normals = allInputs ? test::renderNormals(scene, cam) : FloatImage{};
    const DepthImage big = embedDepth(depth, rc.texture, rc.offset);
    const DepthImage big2 = allInputs ? embedDepth(depth2, rc.texture, rc.offset) : DepthImage{};
    const FloatImage bigNormals = allInputs ? embedNormals(normals, rc.texture, rc.offset) : FloatImage{};
    Frame cropped;
    cropped.camera = cam;
    cropped.format = format;
    cropped.depth = &depth;
    cropped.depth2 = allInputs ? &depth2 : nullptr;
    cropped.normals = allInputs ? &normals : nullptr;
    Frame region = cropped;
    region.depth = &big;
    region.depth2 = allInputs ? &big2 : nullptr;
    region.normals = allInputs ? &bigNormals : nullptr;
    region.region = rc.offset;

    Status st = e->render(cropped);
    ASSERT_TRUE(st.ok()) << st.message;
    const Images a = read(*e);
    st = e->render(region);
    ASSERT_TRUE(st.ok()) << st.message;
    const Images b = read(*e);
    EXPECT_EQ(b.csz.extent, test::inputExtent(cam)) << "csz keeps the camera's extent";
    expectOffset(*e, rc.offset);
    expectSameBits(a, b);
    cpu::Result ref;
    st = runCpu(region, ref);
    ASSERT_TRUE(st.ok()) << st.message;
    expectAgreesWithCpu(*e, ref, name);
  }
}
SAO_INSTANTIATE_API_CASES(Region, regionCases());

// Dynamic resolution moves the region every frame: the frame takes the offset (Vulkan: the ring
// slot's copy of the parameter block) without planning, allocating or building again, and the read
// follows it, for more frames than the ring has slots.
using RegionPerFrame = ApiTest;
TEST_P(RegionPerFrame, TheOffsetChangesPerFrameWithoutPlanningAgain) {
  for (const Convention& c : conventions(61, 37, 3)) {
    SCOPED_TRACE(c.name);
    const DepthImage depth = test::renderDepth(sceneByName("stairs"), c.camera, cpuFormat(c.format));
    const Offset offsets[] = {{3, 5}, {20, 17}};
    const DepthImage embedded[] = {embedDepth(depth, {90, 60}, offsets[0]), embedDepth(depth, {90, 60}, offsets[1])};
    Frame f;
    f.camera = c.camera;
    f.format = c.format;
    f.depth = &depth;
    auto e = make();
    ASSERT_TRUE(e->render(f).ok());
    const Images reference = read(*e);
    const std::uint64_t plans = e->plans(), images = e->imageAllocations(), pipelines = e->pipelines();
    for (int frame = 0; frame < 4; ++frame) {
      SCOPED_TRACE(frame);
      f.depth = &embedded[frame % 2];
      f.region = offsets[frame % 2];
      const Status st = e->render(f);
      ASSERT_TRUE(st.ok()) << st.message;
      expectOffset(*e, *f.region);
      expectSameBits(reference, read(*e));
    }
    EXPECT_EQ(e->plans(), plans);
    EXPECT_EQ(e->imageAllocations(), images);
    EXPECT_EQ(e->pipelines(), pipelines);
  }
}
SAO_INSTANTIATE_APIS(RegionPerFrame);

// A region that does not lie inside every image: InvalidInput naming the input, its size, the
// extent the camera needs and the offset; nothing is allocated, and the effect renders afterwards.
// (Vulkan's declared extent beyond the device's limit: tests/vulkan/input_region_test.cpp.)
using RegionRefused = ApiTest;
TEST_P(RegionRefused, OutsideAnyImageIsRefused) {
  // Each executor's prefix (the engine-side example's FrameState is "vk-engine-example").
  const std::string who = api() == Api::Gl       ? "sao::gl: "
                          : api() == Api::Gles   ? "sao::gles: "
                          : api() == Api::Vulkan ? "sao::vk::Effect::record() Inputs: "
                                                 : "vk-engine-example: ";
  for (const Convention& c : conventions(41, 23, 3)) {  // needs 47x29
    SCOPED_TRACE(c.name);
    const test::Scene scene = sceneByName("sphere");
    const DepthImage depth = test::renderDepth(scene, c.camera, cpuFormat(c.format));
    const DepthImage depth2 = test::renderDepth(scene, c.camera, cpuFormat(c.format), 1);
    const FloatImage normals = test::renderNormals(scene, c.camera);
    const DepthImage big = embedDepth(depth, {50, 31}, {3, 2}), big2 = embedDepth(depth2, {50, 31}, {3, 2});
    const FloatImage bigNormals = embedNormals(normals, {50, 31}, {3, 2});
    Frame good;
    good.camera = c.camera;
    good.format = c.format;
    good.depth = &big;
    good.depth2 = &big2;
    good.normals = &bigNormals;
    good.region = Offset{3, 2};
    auto e = make();
    ASSERT_TRUE(e->render(good).ok());
    const std::uint64_t images = e->imageAllocations();

    auto at = [&](Offset o) {
      Frame f = good;
      f.region = o;
      return f;
    };
    Frame exact = at({0, 1}), smallDepth2 = good, smallNormals = good;
    exact.depth = &depth;
    exact.depth2 = &depth2;
    exact.normals = &normals;
    smallDepth2.depth2 = &depth2;
    smallNormals.normals = &normals;
    const std::pair<Frame, std::string> cases[] = {
        {at({4, 2}), who + "the depth input is 50x31, the camera needs 47x29 (the viewport 41x23 plus twice the guard "
                           "band 3) at offset (4, 2), which ends at (51, 31): the region must lie inside the texture"},
        {at({3, 3}), "at offset (3, 3), which ends at (50, 32)"},
        {at({0xFFFFFFFFu, 0}), "at offset (4294967295, 0), which ends at (4294967342, 29)"},
        {exact, "the depth input is 47x29"},
        {smallDepth2, "the depth2 input is 47x29"},
        {smallNormals, "the normals input is 47x29"},
    };
    for (const auto& [frame, needle] : cases) {
      SCOPED_TRACE(needle);
      const Status st = e->render(frame);
      EXPECT_EQ(st.code, StatusCode::InvalidInput);
      EXPECT_NE(st.message.find(needle), std::string::npos) << st.message;
    }
    EXPECT_EQ(e->imageAllocations(), images);
    EXPECT_TRUE(e->render(good).ok());
  }
}
SAO_INSTANTIATE_APIS(RegionRefused);

}  // namespace
}  // namespace sao::exectest
