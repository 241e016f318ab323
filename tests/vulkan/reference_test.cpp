// Vulkan against the CPU reference (Precision::Float, the GPU-mimicking mode): five analytic scenes
// x every preset x D16 / D24 / D32F at 160x90 (guard band 8), the final AO and the raw (pre-blur)
// AO: at least 99.9 % of the pixels within 2/255 and none beyond 4/255. Failing comparisons write
// actual / expected / difference images to tests/vulkan/failures in the build tree. The
// orientation tests check that Vulkan's top-left origin does not flip anything.
#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <cstring>
#include <mutex>

#include "analytic_scenes.h"
#include "untuned_settings.h"
#include "normal_encodings.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;
constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;

// Each format also runs under another depth convention, so all of them are covered.
Camera cameraFor(VkDepth f) {
  switch (f) {
    case VkDepth::D16: return vulkanCamera(kW, kH, kGuard, 100.0);                // [0,1], standard
    case VkDepth::X8D24: return openglCamera(kW, kH, kGuard, 100.0);              // [-1,1], standard
    default: return vulkanCamera(kW, kH, kGuard, INFINITY, /*reversedZ=*/true);  // [0,1], reversed, infinite
  }
}
const char* conventionOf(VkDepth f) {
  switch (f) {
    case VkDepth::D16: return "zero-to-one, far 100";
    case VkDepth::X8D24: return "minus-one-to-one, far 100";
    default: return "zero-to-one, reversed, infinite far";
  }
}

std::vector<test::Scene> scenes() {
  return {test::planeScene(2.0), test::creaseScene(2.0), test::sphereOnPlaneScene(), test::stairsScene(),
          test::rodsScene()};
}

// Worst case over the scenes, per preset and format, printed at the end.
struct Worst {
  double finalMax = 0, finalP999 = 0, rawMax = 0, rawP999 = 0;
  double finalWithin = 1, rawWithin = 1;
};
std::mutex gMutex;
std::map<std::string, Worst> gTable;

class Summary : public ::testing::Environment {
 public:
  void TearDown() override {
    if (gTable.empty()) return;
    std::printf("\nVulkan vs CPU reference (float), %ux%u + guard %u, worst over 5 scenes (units of 1/255):\n", kW, kH,
                kGuard);
    for (VkDepth f : {VkDepth::D16, VkDepth::X8D24, VkDepth::D32F})
      std::printf("  %s: camera %s\n", toString(f), conventionOf(f));
    std::printf("%-22s %9s %9s %8s %9s %9s %8s\n", "preset/format", "final max", "final p999", "within", "raw max",
                "raw p999", "within");
    for (const auto& [k, w] : gTable)
      std::printf("%-22s %9.4f %9.4f %7.3f%% %9.4f %9.4f %7.3f%%\n", k.c_str(), w.finalMax * 255, w.finalP999 * 255,
                  w.finalWithin * 100, w.rawMax * 255, w.rawP999 * 255, w.rawWithin * 100);
  }
};
const auto* const kSummary = ::testing::AddGlobalTestEnvironment(new Summary);

class VkVsCpu : public VkTest, public ::testing::WithParamInterface<std::tuple<std::size_t, VkDepth>> {};

TEST_P(VkVsCpu, FinalAndRawAoAgree) {
  const auto [index, format] = GetParam();
  const Settings settings = test::agreementSettings()[index].settings;
  const Camera camera = cameraFor(format);
  const std::string presetName = test::agreementSettings()[index].name;
  Worst worst;
  for (const auto& scene : scenes()) {
    SCOPED_TRACE(scene.name);
    const DepthImage depth = test::renderDepth(scene, camera, cpuFormat(format));
    RunResult vk;
    const Status st = runEffect(settings, camera, depth, format, vk);
    ASSERT_TRUE(st.ok()) << st.message;
    cpu::Result ref;
    cpu::Inputs in;
    in.depth = &depth;
    const Status cs = cpu::run(settings, camera, in, {cpu::Precision::Float, 2}, ref);
    ASSERT_TRUE(cs.ok()) << cs.message;
    ASSERT_EQ(vk.plan.cszLevels, ref.plan.cszLevels);
    EXPECT_EQ(std::memcmp(&vk.params, &ref.params, sizeof(ParamBlock)), 0) << "same parameter block";

    const std::string name = "vk_cpu_" + presetName + "_" + toString(format) + "_" + scene.name;
    std::string noteF, noteR;
    const Agreement f = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_final", &noteF);
    const Agreement r = compare(vk.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_raw", &noteR);
    EXPECT_TRUE(acceptable(f)) << "final AO: " << f.fractionWithin * 100 << "% within 2/255, " << f.beyond
                               << " beyond 4/255, max " << f.maxAbs * 255 << "/255. " << noteF;
    EXPECT_TRUE(acceptable(r)) << "raw AO: " << r.fractionWithin * 100 << "% within 2/255, " << r.beyond
                               << " beyond 4/255, max " << r.maxAbs * 255 << "/255. " << noteR;
    // csz level 0 is exact arithmetic on the same texels: bit for bit, apart from the unorm
    // conversion of D16/D24 that the CPU reference computes correctly rounded.
    std::size_t cszDiff = 0;
    for (std::size_t i = 0; i < vk.csz0.data.size(); ++i)
      cszDiff += std::bit_cast<std::uint32_t>(vk.csz0.data[i]) != std::bit_cast<std::uint32_t>(ref.csz[0].data[i]);
    std::printf("%-9s %-6s %-16s final max %.4f p999 %.4f | raw max %.4f p999 %.4f (1/255) | csz0 bits differ %zu\n",
                presetName.c_str(), toString(format), scene.name.c_str(), f.maxAbs * 255, f.p999 * 255, r.maxAbs * 255,
                r.p999 * 255, cszDiff);
    worst.finalMax = std::max(worst.finalMax, f.maxAbs);
    worst.finalP999 = std::max(worst.finalP999, f.p999);
    worst.rawMax = std::max(worst.rawMax, r.maxAbs);
    worst.rawP999 = std::max(worst.rawP999, r.p999);
    worst.finalWithin = std::min(worst.finalWithin, f.fractionWithin);
    worst.rawWithin = std::min(worst.rawWithin, r.fractionWithin);
  }
  std::lock_guard l(gMutex);
  gTable[presetName + "/" + toString(format)] = worst;
}

INSTANTIATE_TEST_SUITE_P(
    Matrix, VkVsCpu,
    ::testing::Combine(::testing::Range(std::size_t{0}, test::agreementSettings().size()),
                       ::testing::Values(VkDepth::D16, VkDepth::X8D24, VkDepth::D32F)),
    [](const auto& info) {
      return test::agreementSettings()[std::get<0>(info.param)].name + "_" +
             toString(std::get<1>(info.param));
    });

// Linear z (R32F) input and the combined depth-stencil formats agree with the reference too.
TEST_F(VkTest, LinearZAndCombinedFormatsAgree) {
  const Camera camera = vulkanCamera(kW, kH, kGuard, 100.0);
  for (VkDepth format : {VkDepth::R32F, VkDepth::D24S8, VkDepth::D32FS8}) {
    for (const auto& scene : {test::sphereOnPlaneScene(), test::stairsScene()}) {
      SCOPED_TRACE(std::string(toString(format)) + " " + scene.name);
      const DepthImage depth = test::renderDepth(scene, camera, cpuFormat(format));
      RunResult vk;
      RunOptions o;
      o.depthLayout = format == VkDepth::R32F ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
                                              : VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
      ASSERT_TRUE(runEffect(Settings{}, camera, depth, format, vk, o).ok());
      cpu::Result ref;
      cpu::Inputs in;
      in.depth = &depth;
      ASSERT_TRUE(cpu::run(Settings{}, camera, in, {cpu::Precision::Float, 2}, ref).ok());
      const std::string name = std::string("vk_cpu_default_") + toString(format) + "_" + scene.name;
      const Agreement f = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_final");
      const Agreement r = compare(vk.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_raw");
      EXPECT_TRUE(acceptable(f)) << f.maxAbs * 255;
      EXPECT_TRUE(acceptable(r)) << r.maxAbs * 255;
      std::printf("default %-6s %-16s final max %.4f | raw max %.4f (1/255)\n", toString(format), scene.name.c_str(),
                  f.maxAbs * 255, r.maxAbs * 255);
    }
  }
}

// The distance fade (fade_start 3 m, fade_end 6 m: the floors recede through it) agrees too, at
// full and at half resolution.
TEST_F(VkTest, DistanceFadeAgrees) {
  const Camera camera = vulkanCamera(kW, kH, kGuard, 100.0);
  for (const int divisor : {1, 2}) {
    for (const auto& scene : {test::sphereOnPlaneScene(), test::stairsScene()}) {
      SCOPED_TRACE(scene.name + " divisor " + std::to_string(divisor));
      Settings s = presetSettings(Preset::Medium);
      s.fade_start = 3.0f;
      s.fade_end = 6.0f;
      s.resolution_divisor = divisor;
      const DepthImage depth = test::renderDepth(scene, camera, DepthFormat::D32F);
      RunResult vk;
      ASSERT_TRUE(runEffect(s, camera, depth, VkDepth::D32F, vk).ok());
      cpu::Result ref;
      cpu::Inputs in;
      in.depth = &depth;
      ASSERT_TRUE(cpu::run(s, camera, in, {cpu::Precision::Float, 2}, ref).ok());
      EXPECT_EQ(std::memcmp(&vk.params, &ref.params, sizeof(ParamBlock)), 0) << "same parameter block";
      const std::string name = "vk_cpu_fade_d" + std::to_string(divisor) + "_" + scene.name;
      const Agreement f = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_final");
      const Agreement r = compare(vk.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_raw");
      EXPECT_TRUE(acceptable(f)) << f.maxAbs * 255;
      EXPECT_TRUE(acceptable(r)) << r.maxAbs * 255;
      std::printf("fade 3-6 m d=%d %-16s final max %.4f p999 %.4f | raw max %.4f p999 %.4f (1/255)\n", divisor,
                  scene.name.c_str(), f.maxAbs * 255, f.p999 * 255, r.maxAbs * 255, r.p999 * 255);
    }
  }
}

// Normals in world space and octahedral (Camera::normalsEncoding): Vulkan agrees with the CPU
// reference on the encoded input and with the CPU's result for the camera-space normals; a
// world-space encoding without a view rotation is refused.
TEST_F(VkTest, EncodedNormalsMatchTheCameraSpaceResult) {
  const Camera base = vulkanCamera(kW, kH, kGuard, 100.0);
  for (const auto& scene : {test::stairsScene(), test::sphereOnPlaneScene()}) {
    const DepthImage depth = test::renderDepth(scene, base, DepthFormat::D32F);
    const FloatImage n = test::renderNormals(scene, base);
    cpu::Inputs ci;
    ci.depth = &depth;
    ci.normals = &n;
    cpu::Result cameraSpace;
    ASSERT_TRUE(cpu::run(presetSettings(Preset::Medium), base, ci, {cpu::Precision::Float, 2}, cameraSpace).ok());
    for (NormalsEncoding e :
         {NormalsEncoding::WorldXyz, NormalsEncoding::CameraOctahedral, NormalsEncoding::WorldOctahedral}) {
      SCOPED_TRACE(scene.name + " encoding " + std::to_string(int(e)));
      Camera cam = base;
      cam.normalsEncoding = e;
      cam.viewRotation = test::viewRotation(0.7, -0.4, 0.25);
      const FloatImage encoded = test::encodeNormals(n, e, *cam.viewRotation);
      RunResult vk;
      RunOptions o;
      o.normals = &encoded;
      const Status st = runEffect(presetSettings(Preset::Medium), cam, depth, VkDepth::D32F, vk, o);
      ASSERT_TRUE(st.ok()) << st.message;
      cpu::Result ref;
      cpu::Inputs ei = ci;
      ei.normals = &encoded;
      ASSERT_TRUE(cpu::run(presetSettings(Preset::Medium), cam, ei, {cpu::Precision::Float, 2}, ref).ok());
      EXPECT_EQ(std::memcmp(&vk.params, &ref.params, sizeof(ParamBlock)), 0) << "same parameter block";
      const std::string name = "vk_cpu_normals_enc" + std::to_string(int(e)) + "_" + scene.name;
      const Agreement f = compare(vk.ao, ref.ao, 0, kWithin, kNever, name + "_final");
      const Agreement r = compare(vk.aoRaw, ref.aoRaw, 0, kWithin, kNever, name + "_raw");
      const Agreement c = compare(vk.ao, cameraSpace.ao, 0, kWithin, kNever, name + "_vs_camera_space");
      EXPECT_TRUE(acceptable(f)) << f.maxAbs * 255;
      EXPECT_TRUE(acceptable(r)) << r.maxAbs * 255;
      EXPECT_TRUE(acceptable(c)) << "against the camera-space run: max " << c.maxAbs * 255 << "/255, p99.9 "
                                 << c.p999 * 255 << "/255";
      std::printf("normals encoding %d %-16s vs CPU same input: final max %.4f raw max %.4f | vs CPU camera-space "
                  "normals: final max %.4f p999 %.4f (1/255)\n",
                  int(e), scene.name.c_str(), f.maxAbs * 255, r.maxAbs * 255, c.maxAbs * 255, c.p999 * 255);
    }
  }
  Camera noRotation = base;
  noRotation.normalsEncoding = NormalsEncoding::WorldOctahedral;
  const DepthImage depth = test::renderDepth(test::planeScene(2.0), base, DepthFormat::D32F);
  const FloatImage n = test::renderNormals(test::planeScene(2.0), base);
  RunResult vk;
  RunOptions o;
  o.normals = &n;
  const Status st = runEffect(Settings{}, noRotation, depth, VkDepth::D32F, vk, o);
  EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
  EXPECT_NE(st.message.find("needs Camera::viewRotation"), std::string::npos) << st.message;
}

// Octahedral normals in a two-channel image (the .xy the decode reads): R16G16_SFLOAT holding the
// same halves as the R16G16B16A16_SFLOAT image's .xy gives the same output, bit for bit.
TEST_F(VkTest, TwoChannelOctahedralNormalsMatchFourChannel) {
  Camera cam = vulkanCamera(kW, kH, kGuard, 100.0);
  cam.viewRotation = test::viewRotation(0.7, -0.4, 0.25);
  const test::Scene scene = test::stairsScene();
  const DepthImage depth = test::renderDepth(scene, cam, DepthFormat::D32F);
  const FloatImage n = test::renderNormals(scene, cam);
  for (NormalsEncoding e : {NormalsEncoding::CameraOctahedral, NormalsEncoding::WorldOctahedral}) {
    SCOPED_TRACE(int(e));
    cam.normalsEncoding = e;
    const FloatImage four = test::encodeNormals(n, e, *cam.viewRotation);
    FloatImage two(four.extent, 2);
    for (std::size_t i = 0; i < two.data.size() / 2; ++i) {
      two.data[2 * i] = four.data[4 * i];
      two.data[2 * i + 1] = four.data[4 * i + 1];
    }
    RunResult a, b;
    RunOptions o;
    o.normals = &four;
    Status st = runEffect(presetSettings(Preset::Medium), cam, depth, VkDepth::D32F, a, o);
    ASSERT_TRUE(st.ok()) << st.message;
    o.normals = &two;
    o.normalsFormat = VK_FORMAT_R16G16_SFLOAT;
    st = runEffect(presetSettings(Preset::Medium), cam, depth, VkDepth::D32F, b, o);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_LT(*std::min_element(a.ao.data.begin(), a.ao.data.end()), 0.5f) << "the scene is occluded somewhere";
    EXPECT_TRUE(test::sameBits(b.ao, a.ao));
    EXPECT_TRUE(test::sameBits(b.aoRaw, a.aoRaw));
  }
}

// ---- Orientation: a box against a wall, only in the camera's top-left. With Vulkan's usual
// conventions (a flipped viewport, Camera::flipY, or a projection with a negative y scale) row 0
// of the depth image is the top of the screen, and the darkening must appear in the top-left of
// the result, where the CPU reference puts it. With neither, row 0 is the bottom (the image is
// upside down on screen) and the effect, reading the rows as they are, must follow.
test::Scene boxInTopLeft() {
  test::Scene s;
  s.name = "box_top_left";
  s.planes.push_back({{0, 0, -4}, {0, 0, 1}, {}});
  s.boxes.push_back({{-3.4, 1.0, -4.0}, {-2.4, 1.9, -3.6}});
  return s;
}

struct Darkness {
  double quadrant[2][2] = {};  // [top rows?][left columns?] in memory order: [row < H/2][x < W/2]
  double cx = 0, cy = 0, total = 0;
};

Darkness darkness(const FloatImage& ao) {
  Darkness d;
  for (std::uint32_t y = 0; y < ao.extent.height; ++y)
    for (std::uint32_t x = 0; x < ao.extent.width; ++x) {
      const double v = std::max(0.0, 1.0 - double(ao.at(x, y)));
      d.quadrant[y < ao.extent.height / 2 ? 0 : 1][x < ao.extent.width / 2 ? 0 : 1] += v;
      d.cx += v * x;
      d.cy += v * y;
      d.total += v;
    }
  if (d.total > 0) d.cx /= d.total, d.cy /= d.total;
  return d;
}

void checkOrientation(const Camera& camera, bool row0IsTop, const char* label) {
  const DepthImage depth = test::renderDepth(boxInTopLeft(), camera, DepthFormat::D32F);
  RunResult vk;
  ASSERT_TRUE(runEffect(Settings{}, camera, depth, VkDepth::D32F, vk).ok());
  cpu::Result ref;
  cpu::Inputs in;
  in.depth = &depth;
  ASSERT_TRUE(cpu::run(Settings{}, camera, in, {cpu::Precision::Float, 2}, ref).ok());
  const Darkness v = darkness(vk.ao), c = darkness(ref.ao);
  const int row = row0IsTop ? 0 : 1;  // the memory half that is the screen's top
  std::printf("%s: darkness in the screen's top-left quadrant %.1f of %.1f (%.1f%%), centroid (%.2f, %.2f) in memory "
              "rows; CPU (%.2f, %.2f)\n",
              label, v.quadrant[row][0], v.total, 100.0 * v.quadrant[row][0] / v.total, v.cx, v.cy, c.cx, c.cy);
  ASSERT_GT(v.total, 5.0) << "the box must occlude the wall around it";
  EXPECT_GT(v.quadrant[row][0], 0.95 * v.total) << "the darkening is in the top-left of the screen";
  EXPECT_LT(v.cx, kW / 2.0);
  EXPECT_TRUE(row0IsTop ? v.cy < kH / 2.0 : v.cy > kH / 2.0);
  EXPECT_NEAR(v.cx, c.cx, 0.25) << "the same place as the CPU reference";
  EXPECT_NEAR(v.cy, c.cy, 0.25) << "the same place as the CPU reference";
  EXPECT_TRUE(acceptable(compare(vk.ao, ref.ao, 0, kWithin, kNever, std::string("vk_orientation_") + label)));
}

TEST_F(VkTest, OrientationFlippedViewport) {
  checkOrientation(vulkanCamera(kW, kH, kGuard, 100.0, false, /*flipY=*/true), true, "flipY");
}

TEST_F(VkTest, OrientationNegativeYProjection) {
  Camera c = vulkanCamera(kW, kH, kGuard, 100.0);
  c.projection[5] = -c.projection[5];  // GLM-style matrix with proj[1][1] *= -1, the common Vulkan idiom
  checkOrientation(c, true, "negative_p11");
}

TEST_F(VkTest, OrientationUnflippedFollowsTheRows) {
  checkOrientation(vulkanCamera(kW, kH, kGuard, 100.0), false, "unflipped");
}

}  // namespace
}  // namespace sao::vktest
