// The Vulkan backend reads its inputs as a region of larger images (vk::Inputs::region), under the
// validation layers: at odd offsets and sizes the result is bit for bit that of the region cropped
// into images of its own (csz is identical, so everything after it is), it agrees with the CPU
// reference at the reference tests' bounds (p99.9 <= 2/255, max <= 4/255), the offset changes per
// record() without update(), and a region outside any image is refused.
#include <cmath>
#include <cstdint>
#include <string>

#include "analytic_scenes.h"
#include "input_region.h"
#include "sao/cpu/reference.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using test::kRegionCases;
using test::RegionCase;

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;

VkDepth formatOf(std::size_t caseIndex) {
  constexpr VkDepth kFormats[] = {VkDepth::X8D24, VkDepth::D32F, VkDepth::D16, VkDepth::R32F};
  return kFormats[caseIndex % 4];
}

Camera cameraFor(const RegionCase& rc, VkDepth f) {
  return f == VkDepth::D16 ? vulkanCamera(rc.width, rc.height, rc.guard, 100.0)
                           : vulkanCamera(rc.width, rc.height, rc.guard, INFINITY, /*reversedZ=*/true);
}

void expectSameBits(const RunResult& a, const RunResult& b) {
  EXPECT_TRUE(test::sameBits(a.csz0, b.csz0)) << "csz level 0";
  EXPECT_TRUE(test::sameBits(a.aoRaw, b.aoRaw)) << "ao_raw";
  EXPECT_TRUE(test::sameBits(a.ao, b.ao)) << "ao";
}

class Region : public VkTest, public ::testing::WithParamInterface<std::size_t> {};

TEST_P(Region, EqualsTheCroppedImageAndAgreesWithTheCpuReference) {
  const RegionCase& rc = kRegionCases[GetParam()];
  const VkDepth format = formatOf(GetParam());
  const Camera cam = cameraFor(rc, format);
  const test::Scene scene = test::sphereOnPlaneScene();
  const bool allInputs = rc.width < 1000;  // two layers and normals on the smaller cases
  const DepthImage depth = test::renderDepth(scene, cam, cpuFormat(format));
  const DepthImage depth2 = allInputs ? test::renderDepth(scene, cam, cpuFormat(format), 1) : DepthImage{};
  const FloatImage normals = allInputs ? test::renderNormals(scene, cam) : FloatImage{};
  const DepthImage big = test::embedDepth(depth, rc.texture, rc.offset);
  const DepthImage big2 = allInputs ? test::embedDepth(depth2, rc.texture, rc.offset) : DepthImage{};
  const FloatImage bigNormals = allInputs ? test::embedNormals(normals, rc.texture, rc.offset) : FloatImage{};

  RunOptions croppedOptions, regionOptions;
  if (allInputs) {
    croppedOptions.depth2 = &depth2;
    croppedOptions.normals = &normals;
    regionOptions.depth2 = &big2;
    regionOptions.normals = &bigNormals;
  }
  regionOptions.region = rc.offset;
  RunResult a, b;
  const Status sa = runEffect(Settings{}, cam, depth, format, a, croppedOptions);
  ASSERT_TRUE(sa.ok()) << sa.message;
  const Status sb = runEffect(Settings{}, cam, big, format, b, regionOptions);
  ASSERT_TRUE(sb.ok()) << sb.message;
  EXPECT_EQ(b.csz0.extent, test::inputExtent(cam)) << "csz keeps the camera's extent";
  EXPECT_EQ(b.params.input_offset.x, std::int32_t(rc.offset.x));
  EXPECT_EQ(b.params.input_offset.y, std::int32_t(rc.offset.y));
  expectSameBits(a, b);

  cpu::Inputs ci{&big, allInputs ? &big2 : nullptr, allInputs ? &bigNormals : nullptr, rc.offset};
  cpu::Result ref;
  const Status cst = cpu::run(Settings{}, cam, ci, cpu::Options{cpu::Precision::Float, 2}, ref);
  ASSERT_TRUE(cst.ok()) << cst.message;
  const std::string name = std::string("region_") + rc.name + "_" + toString(format);
  const Agreement f = compare(b.ao, ref.ao, 0, kWithin, kNever, name + "_final");
  const Agreement r = compare(b.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_raw");
  EXPECT_TRUE(acceptable(f)) << "final AO: max " << f.maxAbs * 255 << "/255, p99.9 " << f.p999 * 255 << "/255";
  EXPECT_TRUE(acceptable(r)) << "raw AO: max " << r.maxAbs * 255 << "/255, p99.9 " << r.p999 * 255 << "/255";
}

INSTANTIATE_TEST_SUITE_P(Cases, Region, ::testing::Range<std::size_t>(0, std::size(kRegionCases)),
                         [](const auto& info) { return std::string(kRegionCases[info.param].name); });

// Images of one test, destroyed at its end.
struct Images {
  vk::headless::Context& ctx = context();
  vk::headless::Image depth, depth2, normals;
  ~Images() {
    ctx.destroy(depth);
    ctx.destroy(depth2);
    ctx.destroy(normals);
  }
};

// Dynamic resolution moves the region every frame: record() takes the offset (the ring slot's copy
// of the parameter block) with no update(), no new memory and no new pipeline.
TEST_F(Region, TheOffsetChangesPerRecordWithoutUpdate) {
  const Camera cam = vulkanCamera(61, 37, 3);
  const DepthImage depth = test::renderDepth(test::stairsScene(), cam, DepthFormat::D32F);
  RunResult reference;
  const Status sr = runEffect(Settings{}, cam, depth, VkDepth::D32F, reference);
  ASSERT_TRUE(sr.ok()) << sr.message;

  const Offset offsets[] = {{3, 5}, {20, 17}};
  Images at35, at2017;
  auto& ctx = context();
  const VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  ASSERT_TRUE(ctx.uploadDepth(test::embedDepth(depth, {90, 60}, offsets[0]), VK_FORMAT_D32_SFLOAT, layout, at35.depth).ok());
  ASSERT_TRUE(ctx.uploadDepth(test::embedDepth(depth, {90, 60}, offsets[1]), VK_FORMAT_D32_SFLOAT, layout, at2017.depth).ok());
  vk::Config config;
  config.camera = cam;
  config.depthFormat = VK_FORMAT_D32_SFLOAT;
  std::unique_ptr<vk::Effect> effect;
  const Status sc = vk::Effect::create(ctx.deviceContext(), config, effect);
  ASSERT_TRUE(sc.ok()) << sc.message;
  const vk::MemoryStats memory = effect->memoryStats();
  const std::uint32_t pipelines = effect->pipelineCount();
  for (int frame = 0; frame < 4; ++frame) {  // more frames than the ring has slots
    SCOPED_TRACE(frame);
    const Images& images = frame % 2 ? at2017 : at35;
    vk::Inputs in;
    in.depth = {images.depth.view, layout, {90, 60}};
    in.region = offsets[frame % 2];
    Status recorded;
    ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) { recorded = effect->record(cmd, in); }).ok());
    ASSERT_TRUE(recorded.ok()) << recorded.message;
    EXPECT_EQ(effect->params().input_offset.x, std::int32_t(in.region->x));
    const vk::OutputImage o = effect->output();
    FloatImage ao;
    ASSERT_TRUE(ctx.readback(o.image, o.format, o.extent, 0, o.layout, config.outputDstStages, config.outputDstAccess, ao)
                    .ok());
    EXPECT_TRUE(test::sameBits(ao, reference.ao)) << "ao at offset " << test::offsetText(*in.region);
  }
  EXPECT_EQ(effect->memoryStats().totalAllocations, memory.totalAllocations);
  EXPECT_EQ(effect->pipelineCount(), pipelines);
}

// A region that does not lie inside every image, or an image larger than the device makes:
// InvalidInput naming the input, its size, the extent the camera needs and the offset; nothing is
// recorded, and a good record in the same command buffer works.
TEST_F(Region, OutsideAnyImageIsRefused) {
  const Camera cam = vulkanCamera(41, 23, 3);  // needs 47x29
  const test::Scene scene = test::sphereOnPlaneScene();
  const DepthImage depth = test::renderDepth(scene, cam, DepthFormat::D32F);
  const DepthImage depth2 = test::renderDepth(scene, cam, DepthFormat::D32F, 1);
  const FloatImage normals = test::renderNormals(scene, cam);
  auto& ctx = context();
  const VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const VkFormat half4 = VK_FORMAT_R16G16B16A16_SFLOAT;
  Images big, exact;
  ASSERT_TRUE(ctx.uploadDepth(test::embedDepth(depth, {50, 31}, {3, 2}), VK_FORMAT_D32_SFLOAT, layout, big.depth).ok());
  ASSERT_TRUE(ctx.uploadDepth(test::embedDepth(depth2, {50, 31}, {3, 2}), VK_FORMAT_D32_SFLOAT, layout, big.depth2).ok());
  ASSERT_TRUE(ctx.uploadColor(test::embedNormals(normals, {50, 31}, {3, 2}), half4, layout, big.normals).ok());
  ASSERT_TRUE(ctx.uploadDepth(depth2, VK_FORMAT_D32_SFLOAT, layout, exact.depth2).ok());
  ASSERT_TRUE(ctx.uploadColor(normals, half4, layout, exact.normals).ok());
  vk::Config config;
  config.camera = cam;
  config.depthFormat = VK_FORMAT_D32_SFLOAT;
  config.normalsFormat = half4;
  config.secondLayer = true;
  std::unique_ptr<vk::Effect> effect;
  const Status sc = vk::Effect::create(ctx.deviceContext(), config, effect);
  ASSERT_TRUE(sc.ok()) << sc.message;

  vk::Inputs good;
  good.depth = {big.depth.view, layout, {50, 31}};
  good.depth2 = {big.depth2.view, layout, {50, 31}};
  good.normals = {big.normals.view, layout, {50, 31}};
  good.region = Offset{3, 2};
  auto with = [&](Offset offset) {
    vk::Inputs in = good;
    in.region = offset;
    return in;
  };
  vk::Inputs smallDepth2 = good, smallNormals = good, tooLarge = good;
  smallDepth2.depth2 = {exact.depth2.view, layout, {47, 29}};
  smallNormals.normals = {exact.normals.view, layout, {47, 29}};
  const std::uint32_t maxSide = ctx.properties().limits.maxImageDimension2D;
  tooLarge.depth.extent = {maxSide + 1, 31};  // a declaration no image of this device can have
  struct Case {
    vk::Inputs in;
    const char* needle;
  };
  const Case cases[] = {
      {with({4, 2}),
       "the depth input is 50x31, the camera needs 47x29 (the viewport 41x23 plus twice the guard band 3) at offset "
       "(4, 2), which ends at (51, 31): the region must lie inside the texture"},
      {with({3, 3}), "at offset (3, 3), which ends at (50, 32)"},
      {with({0xFFFFFFFFu, 0}), "at offset (4294967295, 0), which ends at (4294967342, 29)"},
      {smallDepth2, "the depth2 input is 47x29"},
      {smallNormals, "the normals input is 47x29"},
      {tooLarge, "exceeds this device's maxImageDimension2D"},
  };
  std::vector<Status> results;
  Status after;
  ASSERT_TRUE(ctx.submit([&](VkCommandBuffer cmd) {
                   for (const Case& c : cases) results.push_back(effect->record(cmd, c.in));
                   after = effect->record(cmd, good);
                 }).ok());
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    SCOPED_TRACE(cases[i].needle);
    EXPECT_EQ(results[i].code, StatusCode::InvalidInput);
    EXPECT_NE(results[i].message.find(cases[i].needle), std::string::npos) << results[i].message;
  }
  EXPECT_TRUE(after.ok()) << after.message;
}

}  // namespace
}  // namespace sao::vktest
