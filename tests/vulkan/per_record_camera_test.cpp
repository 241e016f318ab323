// vk::Inputs::camera, a camera per record (TAA jitter, an animated field of view, a new view
// rotation for world-space normals), under validation and synchronization validation: an effect
// created with camera A and recorded with camera B writes exactly (every texel, bit for bit) what
// an effect created with B writes (record() and measure()); two command buffers in flight each keep
// their own camera; a record with a camera allocates nothing in the library; cameras that change
// the plan (size, guard band, csz levels) or are invalid are refused with create()'s code and
// message or one naming what differs, and the effect stays usable. record() accepts a camera
// exactly when sao::plan() of that camera equals the effect's plan.
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>

#include "analytic_scenes.h"
#include "library_allocations.h"
#include "normal_encodings.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Image;

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;
constexpr VkFormat kNormalsFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

// Vulkan's [0, 1] clip range, far 100, a vertical field of view in degrees.
Camera cameraWith(double fovDegrees, double nearDistance, std::uint32_t w = kW, std::uint32_t h = kH,
                  std::uint32_t guard = kGuard) {
  Camera c = perspectiveCamera(fovDegrees * std::numbers::pi / 180.0, w, h, nearDistance, 100.0, ClipDepth::ZeroToOne, false);
  c.guardBand = guard;
  return c;
}

// A TAA jitter of (dx, dy) pixels: the projection's x and y offsets (P02, P12).
Camera jittered(Camera c, double dx, double dy) {
  c.projection[8] += 2.0 * dx / c.width;
  c.projection[9] += 2.0 * dy / c.height;
  return c;
}

Camera worldNormals(Camera c, const std::array<double, 9>& rotation) {
  c.normalsEncoding = NormalsEncoding::WorldXyz;
  c.viewRotation = rotation;
  return c;
}

// Texels whose bits differ (R16F read back as float: equal bits, equal output).
std::size_t differences(const FloatImage& a, const FloatImage& b) {
  EXPECT_EQ(a.data.size(), b.data.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i)
    n += std::memcmp(&a.data[i], &b.data[i], sizeof(float)) != 0;
  return n;
}

class PerRecordCamera : public VkTest {
 protected:
  void SetUp() override {
    VkTest::SetUp();
    base = cameraWith(60, 0.1);
    const test::Scene scene = test::sphereOnPlaneScene();
    depth = test::renderDepth(scene, base, DepthFormat::D32F);
    ASSERT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depthImage).ok());
    // World-space normals written with rotation R0. The same texels serve every camera: each
    // comparison is between two effects on the same inputs.
    const FloatImage n = test::encodeNormals(test::renderNormals(scene, base), NormalsEncoding::WorldXyz, r0);
    ASSERT_TRUE(context().uploadColor(n, kNormalsFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, normalsImage).ok());
  }
  void TearDown() override {
    context().destroy(depthImage);
    context().destroy(normalsImage);
    VkTest::TearDown();
  }

  vk::Config config(const Camera& camera) const {
    vk::Config c;
    c.settings = presetSettings(Preset::Medium);
    c.camera = camera;
    c.depthFormat = VK_FORMAT_D32_SFLOAT;
    if (camera.normalsEncoding == NormalsEncoding::WorldXyz) c.normalsFormat = kNormalsFormat;
    c.userOutput = true;  // every result in an image of its own
    return c;
  }
  vk::Inputs inputs(const vk::Effect& e, const Camera* camera) const {
    vk::Inputs in;
    in.depth = {depthImage.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_D32_SFLOAT};
    if (e.config().normalsFormat != VK_FORMAT_UNDEFINED)
      in.normals = {normalsImage.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, kNormalsFormat};
    in.camera = camera;
    return in;
  }
  std::unique_ptr<vk::Effect> create(const vk::Config& c) const {
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_TRUE(st.ok()) << st.message;
    return e;
  }
  static vk::OutputImage outputOf(const Image& out) {
    return {out.image, out.view, VK_FORMAT_R16_SFLOAT, {kW, kH}, VK_IMAGE_LAYOUT_UNDEFINED};
  }
  static FloatImage read(const vk::Effect& e, const Image& out) {
    FloatImage ao;
    const vk::Config& c = e.config();
    const Status st = context().readback(out.image, VK_FORMAT_R16_SFLOAT, {kW, kH}, 0, c.outputLayout, c.outputDstStages,
                                         c.outputDstAccess, ao);
    EXPECT_TRUE(st.ok()) << st.message;
    return ao;
  }
  // One record of `e` with Inputs::camera = `camera` into a new output image, submitted, read back.
  FloatImage run(vk::Effect& e, const Camera* camera) const {
    Image out;
    EXPECT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
    const vk::OutputImage o = outputOf(out);
    Status recorded;
    EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = e.record(cmd, inputs(e, camera), &o); }).ok());
    EXPECT_TRUE(recorded.ok()) << recorded.message;
    FloatImage ao = read(e, out);
    context().destroy(out);
    return ao;
  }
  // The reference: an effect created with Config::camera = `camera`, recorded without Inputs::camera.
  FloatImage fresh(const Camera& camera, Plan* plan = nullptr) const {
    auto e = create(config(camera));
    if (!e) return {};
    if (plan) *plan = e->plan();
    return run(*e, nullptr);
  }

  const std::array<double, 9> r0 = test::viewRotation(0.7, -0.4, 0.25);
  const std::array<double, 9> r1 = test::viewRotation(-0.3, 0.5, -0.6);
  Camera base;
  DepthImage depth;
  Image depthImage, normalsImage;
};

TEST_F(PerRecordCamera, MatchesAnEffectCreatedWithThatCamera) {
  struct Case {
    const char* name;
    Camera a, b;
  };
  const Case cases[] = {
      {"jitter", base, jittered(base, 0.37, -0.21)},
      {"fov 50", base, cameraWith(50, 0.1)},
      {"fov 70", base, cameraWith(70, 0.1)},
      {"world normals, new rotation", worldNormals(base, r0), worldNormals(base, r1)},
      {"world normals, new rotation and jitter", worldNormals(base, r0), worldNormals(jittered(base, -0.45, 0.3), r1)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Plan planA, planB;
    const FloatImage expectedA = fresh(c.a, &planA);
    const FloatImage expectedB = fresh(c.b, &planB);
    ASSERT_EQ(planA.describe(), planB.describe()) << "the case must not change the plan";
    auto effect = create(config(c.a));
    ASSERT_TRUE(effect);
    const ParamBlock paramsA = effect->params();
    const FloatImage actual = run(*effect, &c.b);
    EXPECT_EQ(differences(actual, expectedB), 0u) << "texels unlike the effect created with camera B";
    EXPECT_GT(differences(actual, expectedA), 0u) << "camera B changed nothing: the test would prove nothing";
    // params() is the last record's block: camera B's, as an effect created with B has it.
    auto effectB = create(config(c.b));
    ASSERT_TRUE(effectB);
    EXPECT_EQ(std::memcmp(&effect->params(), &effectB->params(), sizeof(ParamBlock)), 0);
    // Config::camera stays; the slots go back to it: slot 1 then slot 0 again (the slot that held
    // B's block) without a camera, and so does params().
    EXPECT_EQ(effect->config().camera, c.a);
    EXPECT_EQ(differences(run(*effect, nullptr), expectedA), 0u) << "slot 1 without a camera";
    EXPECT_EQ(std::memcmp(&effect->params(), &paramsA, sizeof(ParamBlock)), 0);
    EXPECT_EQ(differences(run(*effect, nullptr), expectedA), 0u) << "slot 0 again without a camera";
    expectNoMessages(c.name);
  }
}

// measure() takes Inputs like record(): its run uses the camera too.
TEST_F(PerRecordCamera, MeasureUsesTheCamera) {
  const Camera b = worldNormals(jittered(cameraWith(65, 0.1), 0.3, -0.3), r1);
  const FloatImage expected = fresh(b);
  auto effect = create(config(worldNormals(base, r0)));
  ASSERT_TRUE(effect);
  for (vk::MeasureMethod method : {vk::MeasureMethod::Auto, vk::MeasureMethod::FenceClock}) {
    Image out;
    ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
    const vk::OutputImage o = outputOf(out);
    Timings t;
    const Status st = effect->measure(context().queue(), inputs(*effect, &b), &o, t, method);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(differences(read(*effect, out), expected), 0u) << "method " << int(method);
    context().destroy(out);
  }
  Camera bad = b;
  bad.projection[0] = INFINITY;
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = outputOf(out);
  Timings t;
  const Status st = effect->measure(context().queue(), inputs(*effect, &bad), &o, t);
  EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
  EXPECT_NE(st.message.find("non-finite element P00"), std::string::npos) << st.message;
  context().destroy(out);
}

// Two command buffers recorded with cameras B and C (ring slots 0 and 1), both pending at once,
// submitted together: each output is its camera's fresh result.
TEST_F(PerRecordCamera, TwoFramesInFlightKeepTheirCameras) {
  const Camera a = worldNormals(base, r0);
  const Camera b = worldNormals(jittered(cameraWith(55, 0.1), 0.25, 0.25), r1);
  const Camera c = worldNormals(jittered(base, -0.25, 0.4), test::viewRotation(1.1, 0.2, 0.0));
  const FloatImage expectedB = fresh(b), expectedC = fresh(c);
  ASSERT_GT(differences(expectedB, expectedC), 0u);
  vk::Config cfg = config(a);
  cfg.framesInFlight = 2;
  auto effect = create(cfg);
  ASSERT_TRUE(effect);

  vk::headless::Context& ctx = context();
  const VkDevice device = ctx.device();
  Image outB, outC;
  ASSERT_TRUE(ctx.createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, outB).ok());
  ASSERT_TRUE(ctx.createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, outC).ok());
  VkCommandBuffer cmds[2]{};
  ASSERT_TRUE(ctx.allocateCommandBuffers(cmds, 2).ok());
  VkFence fence = VK_NULL_HANDLE;
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  ASSERT_EQ(vkCreateFence(device, &fi, nullptr, &fence), VK_SUCCESS);

  const Camera* cameras[2] = {&b, &c};
  const vk::OutputImage outputs[2] = {outputOf(outB), outputOf(outC)};
  for (int i = 0; i < 2; ++i) {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ASSERT_EQ(vkBeginCommandBuffer(cmds[i], &bi), VK_SUCCESS);
    const Status st = effect->record(cmds[i], inputs(*effect, cameras[i]), &outputs[i]);
    ASSERT_EQ(vkEndCommandBuffer(cmds[i]), VK_SUCCESS);
    ASSERT_TRUE(st.ok()) << st.message;
  }
  VkSubmitInfo si[2]{};
  for (int i = 0; i < 2; ++i) {
    si[i].sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si[i].commandBufferCount = 1;
    si[i].pCommandBuffers = &cmds[i];
  }
  ASSERT_EQ(vkQueueSubmit(ctx.queue(), 2, si, fence), VK_SUCCESS);
  ASSERT_EQ(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
  vkDestroyFence(device, fence, nullptr);
  vkFreeCommandBuffers(device, ctx.commandPool(), 2, cmds);

  EXPECT_EQ(differences(read(*effect, outB), expectedB), 0u) << "slot 0, camera B";
  EXPECT_EQ(differences(read(*effect, outC), expectedC), 0u) << "slot 1, camera C";
  ctx.destroy(outB);
  ctx.destroy(outC);
}

// A camera per record allocates nothing in the library once warm (the allocation counter of
// tests/common/library_allocations.h) and needs no update(): 64 jittered frames with an animated
// field of view and view rotation.
TEST_F(PerRecordCamera, NoAllocationPerRecord) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  vk::Config cfg = config(worldNormals(base, r0));
  cfg.timestamps = true;
  auto effect = create(cfg);
  ASSERT_TRUE(effect);
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = outputOf(out);
  Camera last;
  long counted = 0;
  constexpr int kWarmUp = 4, kFrames = 64;
  for (int f = 0; f < kWarmUp + kFrames; ++f) {
    // Halton (2, 3) jitter in [-0.5, 0.5), a field of view between 58 and 62 degrees, a turning view.
    auto halton = [](int i, int b) {
      double r = 0, k = 1.0 / b;
      for (; i > 0; i /= b, k /= b) r += k * (i % b);
      return r;
    };
    const Camera camera = worldNormals(jittered(cameraWith(60 + 2 * std::sin(f * 0.3), 0.1), halton(f + 1, 2) - 0.5,
                                                halton(f + 1, 3) - 0.5),
                                       test::viewRotation(0.05 * f, -0.4, 0.25));
    Status recorded;
    ASSERT_TRUE(context()
                    .submit([&](VkCommandBuffer cmd) {
                      const vk::Inputs in = inputs(*effect, &camera);
                      test::startCountingAllocations();
                      recorded = effect->record(cmd, in, &o);
                      test::stopCountingAllocations();
                      if (f >= kWarmUp) counted += test::countedAllocations();
                    })
                    .ok());
    ASSERT_TRUE(recorded.ok()) << "frame " << f << ": " << recorded.message;
    last = camera;
  }
  EXPECT_EQ(counted, 0) << "library allocations in " << kFrames << " record() calls with Inputs::camera";
  EXPECT_EQ(effect->config().camera, cfg.camera) << "Config's camera is untouched";
  // params() is the last record's block: its camera's, as an effect created with it has it.
  vk::Config lastConfig = cfg;
  lastConfig.camera = last;
  auto withLast = create(lastConfig);
  ASSERT_TRUE(withLast);
  EXPECT_EQ(std::memcmp(&effect->params(), &withLast->params(), sizeof(ParamBlock)), 0);
  // The counter sees the library: a refused camera builds its message.
  const Camera other = cameraWith(60, 0.1, kW + 2);
  Status refused;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    test::startCountingAllocations();
                    refused = effect->record(cmd, inputs(*effect, &other), &o);
                    test::stopCountingAllocations();
                  })
                  .ok());
  EXPECT_FALSE(refused.ok());
  EXPECT_GT(test::countedAllocations(), 0);
  context().destroy(out);
}

// Each refusal: the code and a message naming what is wrong, nothing recorded, and the effect
// records the next valid camera exactly as a fresh effect does.
TEST_F(PerRecordCamera, RefusesCamerasThatChangeThePlanOrAreInvalid) {
  const Camera a = worldNormals(base, r0);
  auto effect = create(config(a));
  ASSERT_TRUE(effect);
  const Camera valid = worldNormals(jittered(base, 0.2, 0.1), r1);
  const FloatImage expectedValid = fresh(valid);

  // create()'s code and message for a camera, or ok.
  auto createStatus = [&](const Camera& camera) {
    std::unique_ptr<vk::Effect> e;
    return vk::Effect::create(context().deviceContext(), config(camera), e);
  };
  Camera nonFinite = a;
  nonFinite.projection[5] = NAN;
  Camera noRotation = a;
  noRotation.viewRotation.reset();
  Camera scaled = a;
  for (int i = 0; i < 3; ++i) (*scaled.viewRotation)[std::size_t(i)] *= 1.5;
  Camera orthographic = orthographicCamera(2.0, kW, kH, 0.1, 100.0, ClipDepth::ZeroToOne, false);
  orthographic.guardBand = kGuard;
  orthographic = worldNormals(orthographic, r0);
  struct Case {
    const char* name;
    Camera camera;
    StatusCode code;
    std::string says;      // in the message
    bool sameAsCreate;     // create() refuses it with the same code and message
  };
  const Case cases[] = {
      {"another size", worldNormals(cameraWith(60, 0.1, kW + 2, kH), r0), StatusCode::InvalidInput,
       "is 162x90 with guard band 8 but the plan's camera is 160x90 with guard band 8", false},
      {"another guard band", worldNormals(cameraWith(60, 0.1, kW, kH, kGuard + 1), r0), StatusCode::InvalidInput,
       "is 160x90 with guard band 9 but the plan's camera is 160x90 with guard band 8", false},
      {"a near plane that needs fewer csz levels", worldNormals(cameraWith(60, 1.0), r0), StatusCode::InvalidInput,
       "csz MIP levels but the plan has", false},
      {"orthographic (fewer csz levels here)", orthographic, StatusCode::InvalidInput,
       "csz MIP levels but the plan has", false},
      {"a non-finite projection", nonFinite, StatusCode::InvalidCamera, "non-finite element P11", true},
      {"world normals without a rotation", noRotation, StatusCode::InvalidCamera, "needs Camera::viewRotation", true},
      {"a scaled rotation", scaled, StatusCode::InvalidCamera, "is not a rotation", true},
  };
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = outputOf(out);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Status st;
    ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = effect->record(cmd, inputs(*effect, &c.camera), &o); }).ok());
    EXPECT_EQ(st.code, c.code) << st.message;
    EXPECT_NE(st.message.find("Inputs::camera"), std::string::npos) << st.message;
    EXPECT_NE(st.message.find(c.says), std::string::npos) << st.message;
    const Status created = createStatus(c.camera);
    if (c.sameAsCreate) {
      EXPECT_EQ(created.code, st.code) << created.message;
      EXPECT_FALSE(created.message.empty());
      EXPECT_NE(st.message.find(created.message), std::string::npos) << st.message << "\ncreate(): " << created.message;
    } else {
      EXPECT_TRUE(created.ok()) << "a valid camera for an effect of its own: " << created.message;
      if (c.code == StatusCode::InvalidInput) {
        EXPECT_NE(st.message.find("call update()"), std::string::npos) << st.message;
      }
    }
    EXPECT_EQ(differences(run(*effect, &valid), expectedValid), 0u) << "the next valid record";
  }

  // The normals contract: a camera whose encoding reads more channels than Config::normalsFormat has.
  Camera octahedral = a;
  octahedral.normalsEncoding = NormalsEncoding::CameraOctahedral;
  vk::Config rg = config(octahedral);
  rg.normalsFormat = VK_FORMAT_R16G16_SFLOAT;
  Image rgNormals;
  ASSERT_TRUE(context()
                  .uploadColor(FloatImage(depth.extent, 2), VK_FORMAT_R16G16_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                               rgNormals)
                  .ok());
  auto rgEffect = create(rg);
  ASSERT_TRUE(rgEffect);
  vk::Inputs in = inputs(*rgEffect, &a);  // a: WorldXyz, three channels
  in.normals = {rgNormals.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth.extent, VK_FORMAT_R16G16_SFLOAT};
  Status st;
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = rgEffect->record(cmd, in, &o); }).ok());
  EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
  vk::Config rgXyz = rg;
  rgXyz.camera = a;
  std::unique_ptr<vk::Effect> refused;
  const Status created = vk::Effect::create(context().deviceContext(), rgXyz, refused);
  EXPECT_EQ(created.code, StatusCode::UnsupportedFormat) << created.message;
  EXPECT_NE(st.message.find(created.message), std::string::npos) << st.message << "\ncreate(): " << created.message;
  EXPECT_NE(st.message.find("VK_FORMAT_R16G16_SFLOAT (two channels)"), std::string::npos) << st.message;
  in.camera = &octahedral;
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = rgEffect->record(cmd, in, &o); }).ok());
  EXPECT_TRUE(st.ok()) << st.message;
  context().destroy(rgNormals);
  context().destroy(out);
}

// What record() compares instead of calling sao::plan() (which allocates) decides exactly as
// sao::plan() does: over fields of view, near planes, units, projection kinds and conventions, a
// camera is accepted when its plan equals the effect's and refused (InvalidInput) otherwise.
TEST_F(PerRecordCamera, AcceptsExactlyTheCamerasThatPlanAlike) {
  const vk::Config cfg = config(base);
  auto effect = create(cfg);
  ASSERT_TRUE(effect);
  const std::string planned = effect->plan().describe();
  std::vector<Camera> cameras;
  for (double fov : {10.0, 30.0, 45.0, 60.0, 75.0, 90.0, 120.0, 170.0})
    for (double nearDistance : {0.001, 0.05, 0.1, 0.3, 1.0, 5.0}) cameras.push_back(cameraWith(fov, nearDistance));
  for (double u : {1e-3, 0.1, 1.0, 30.0}) {
    Camera c = base;
    c.metersToViewUnits = u;
    cameras.push_back(c);
  }
  for (double halfHeight : {0.01, 0.5, 2.0, 50.0}) {
    Camera c = orthographicCamera(halfHeight, kW, kH, 0.1, 100.0, ClipDepth::ZeroToOne, false);
    c.guardBand = kGuard;
    cameras.push_back(c);
  }
  Camera reversed = vulkanCamera(kW, kH, kGuard, INFINITY, true, true);
  cameras.push_back(reversed);
  cameras.push_back(openglCamera(kW, kH, kGuard));
  cameras.push_back(vulkanCamera(kW, kH, kGuard + 4));
  cameras.push_back(vulkanCamera(kW - 1, kH, kGuard));
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = outputOf(out);
  int accepted = 0, refused = 0;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    SCOPED_TRACE("camera " + std::to_string(i));
    Plan p;
    const DepthEncoding encoding = DepthEncoding::Hardware;
    const Status planned2 = sao::plan(cfg.settings, cameras[i], {encoding, {}, true, gen::Format::R16F}, p);
    ASSERT_TRUE(planned2.ok()) << planned2.message;
    const bool same = p.describe() == planned;
    Status st;
    ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = effect->record(cmd, inputs(*effect, &cameras[i]), &o); }).ok());
    EXPECT_EQ(st.ok(), same) << st.message << "\nplan of the camera:\n" << p.describe() << "effect's plan:\n" << planned;
    if (!same) {
      EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
    }
    (same ? accepted : refused)++;
  }
  EXPECT_GT(accepted, 5);
  EXPECT_GT(refused, 5);
  std::printf("%d cameras planned alike and were accepted, %d planned otherwise and were refused\n", accepted, refused);
  context().destroy(out);
}

}  // namespace
}  // namespace sao::vktest
