// The camera per record (TAA jitter, an animated field of view, a new view rotation for world-space
// normals), under validation and synchronization validation: record()'s camera is written into
// the record's own ring slot, so an effect planned with camera A and recorded with camera B writes
// exactly (every texel, bit for bit) what a fresh effect recorded with B writes (record() and
// measure()); two command buffers in flight each keep their own camera; a camera that keeps the
// plan records without a new plan and allocates nothing in the library; a camera that changes the
// plan (size, guard band, csz levels) plans again within the call while the frame in flight keeps
// its camera and output; an invalid camera is refused as a fresh effect refuses it, and the effect
// stays usable. record() plans again exactly when sao::plan() of the camera differs from the
// effect's plan.
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
constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

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
    ASSERT_TRUE(context().uploadDepth(depth, VK_FORMAT_D32_SFLOAT, kRead, depthImage).ok());
    // World-space normals written with rotation R0. The same texels serve every camera: each
    // comparison is between two effects on the same inputs.
    const FloatImage n = test::encodeNormals(test::renderNormals(scene, base), NormalsEncoding::WorldXyz, r0);
    ASSERT_TRUE(context().uploadColor(n, kNormalsFormat, kRead, normalsImage).ok());
  }
  void TearDown() override {
    for (Image* i : {&depthImage, &normalsImage, &otherDepthImage, &otherNormalsImage}) context().destroy(*i);
    VkTest::TearDown();
  }

  // The inputs for `camera`: the depth, and the world-space normals when the camera reads them.
  // Cameras of another size or guard band get the images of prepareOtherGeometry().
  static bool baseGeometry(const Camera& camera) {
    return camera.width == kW && camera.height == kH && camera.guardBand == kGuard;
  }
  vk::Inputs inputs(const Camera& camera) const {
    vk::Inputs in;
    const bool own = baseGeometry(camera);
    const Image& d = own ? depthImage : otherDepthImage;
    in.depth = {d.view, kRead, d.extent, VK_FORMAT_D32_SFLOAT};
    if (camera.normalsEncoding == NormalsEncoding::WorldXyz) {
      const Image& n = own ? normalsImage : otherNormalsImage;
      in.normals = {n.view, kRead, n.extent, kNormalsFormat};
    }
    return in;
  }
  // Depth and normals for a camera of another size or guard band (the one other geometry a test
  // uses at a time), rendered from the same scene.
  void prepareOtherGeometry(const Camera& camera) {
    context().destroy(otherDepthImage);
    context().destroy(otherNormalsImage);
    const test::Scene scene = test::sphereOnPlaneScene();
    ASSERT_TRUE(context()
                    .uploadDepth(test::renderDepth(scene, camera, DepthFormat::D32F), VK_FORMAT_D32_SFLOAT, kRead,
                                 otherDepthImage)
                    .ok());
    const FloatImage n = test::encodeNormals(test::renderNormals(scene, camera), NormalsEncoding::WorldXyz, r0);
    ASSERT_TRUE(context().uploadColor(n, kNormalsFormat, kRead, otherNormalsImage).ok());
  }
  static std::unique_ptr<vk::Effect> create(const vk::Config& c = {}) {
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_TRUE(st.ok()) << st.message;
    return e;
  }
  static vk::OutputImage outputOf(const Image& out) {
    return {out.image, out.view, VK_FORMAT_R16_SFLOAT, out.extent, VK_IMAGE_LAYOUT_UNDEFINED};
  }
  static FloatImage read(const vk::Effect& e, const Image& out) {
    FloatImage ao;
    const vk::Config& c = e.config();
    const Status st = context().readback(out.image, VK_FORMAT_R16_SFLOAT, out.extent, 0, c.outputLayout,
                                         c.outputDstStages, c.outputDstAccess, ao);
    EXPECT_TRUE(st.ok()) << st.message;
    return ao;
  }
  // One record of `e` with `camera` into a new output image (every result in an image of its
  // own, the camera's viewport), submitted, read back.
  FloatImage run(vk::Effect& e, const Camera& camera) const {
    Image out;
    EXPECT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {camera.width, camera.height}, out).ok());
    const vk::OutputImage o = outputOf(out);
    Status recorded;
    const vk::Inputs in = inputs(camera);
    EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = e.record(cmd, camera, settings, in, &o); }).ok());
    EXPECT_TRUE(recorded.ok()) << recorded.message;
    FloatImage ao = read(e, out);
    context().destroy(out);
    return ao;
  }
  // The reference: a fresh effect whose first record (the one that plans) has `camera`.
  FloatImage fresh(const Camera& camera, Plan* plan = nullptr, ParamBlock* params = nullptr) const {
    auto e = create();
    if (!e) return {};
    FloatImage ao = run(*e, camera);
    if (plan) *plan = e->plan();
    if (params) *params = e->params();
    return ao;
  }

  const std::array<double, 9> r0 = test::viewRotation(0.7, -0.4, 0.25);
  const std::array<double, 9> r1 = test::viewRotation(-0.3, 0.5, -0.6);
  const Settings settings = presetSettings(Preset::Medium);
  Camera base;
  DepthImage depth;
  Image depthImage, normalsImage;
  Image otherDepthImage, otherNormalsImage;  // prepareOtherGeometry()
};

TEST_F(PerRecordCamera, MatchesAFreshEffectOfThatCamera) {
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
    ParamBlock freshParamsB{};
    const FloatImage expectedA = fresh(c.a, &planA);
    const FloatImage expectedB = fresh(c.b, &planB, &freshParamsB);
    ASSERT_EQ(planA.describe(), planB.describe()) << "the case must not change the plan";
    auto effect = create();
    ASSERT_TRUE(effect);
    // Planned with A (ring slot 0), then B in slot 1: no new plan.
    EXPECT_EQ(differences(run(*effect, c.a), expectedA), 0u) << "slot 0, camera A (the record that plans)";
    const ParamBlock paramsA = effect->params();
    const FloatImage actual = run(*effect, c.b);
    EXPECT_EQ(differences(actual, expectedB), 0u) << "texels unlike the fresh effect with camera B";
    EXPECT_GT(differences(actual, expectedA), 0u) << "camera B changed nothing: the test would prove nothing";
    EXPECT_EQ(effect->plans(), 1u) << "camera B keeps the plan: no new plan";
    // params() is the last record's block: camera B's, as the fresh effect with B has it.
    EXPECT_EQ(std::memcmp(&effect->params(), &freshParamsB, sizeof(ParamBlock)), 0);
    // Back to A: slot 0 again, then slot 1 (the slot that held B's block), and so does params().
    EXPECT_EQ(differences(run(*effect, c.a), expectedA), 0u) << "slot 0 again with camera A";
    EXPECT_EQ(std::memcmp(&effect->params(), &paramsA, sizeof(ParamBlock)), 0);
    EXPECT_EQ(differences(run(*effect, c.a), expectedA), 0u) << "slot 1 (B's) with camera A";
    EXPECT_EQ(effect->plans(), 1u);
    expectNoMessages(c.name);
  }
}

// measure() takes the camera like record(): its run uses it, on the plan it has.
TEST_F(PerRecordCamera, MeasureUsesTheCamera) {
  const Camera a = worldNormals(base, r0);
  const Camera b = worldNormals(jittered(cameraWith(65, 0.1), 0.3, -0.3), r1);
  const FloatImage expected = fresh(b);
  auto effect = create();
  ASSERT_TRUE(effect);
  run(*effect, a);  // planned with camera A
  for (vk::MeasureMethod method : {vk::MeasureMethod::Auto, vk::MeasureMethod::FenceClock}) {
    Image out;
    ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
    const vk::OutputImage o = outputOf(out);
    Timings t;
    const Status st = effect->measure(context().queue(), b, settings, inputs(b), &o, t, method);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(differences(read(*effect, out), expected), 0u) << "method " << int(method);
    context().destroy(out);
  }
  EXPECT_EQ(effect->plans(), 1u) << "camera B keeps camera A's plan";
  Camera bad = b;
  bad.projection[0] = INFINITY;
  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = outputOf(out);
  Timings t;
  const Status st = effect->measure(context().queue(), bad, settings, inputs(bad), &o, t);
  EXPECT_EQ(st.code, StatusCode::InvalidCamera) << st.message;
  EXPECT_NE(st.message.find("non-finite element P00"), std::string::npos) << st.message;
  context().destroy(out);
}

// Records `cameras[i]` into command buffer i (ring slots in turn, every record pending at once)
// with output `outputs[i]`, submits them together and waits.
void recordInFlight(vk::Effect& effect, const Settings& settings, const Camera* const* cameras,
                    const vk::Inputs* inputs, const vk::OutputImage* outputs, std::uint32_t n) {
  vk::headless::Context& ctx = context();
  const VkDevice device = ctx.device();
  std::vector<VkCommandBuffer> cmds(n);
  ASSERT_TRUE(ctx.allocateCommandBuffers(cmds.data(), n).ok());
  VkFence fence = VK_NULL_HANDLE;
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  ASSERT_EQ(vkCreateFence(device, &fi, nullptr, &fence), VK_SUCCESS);
  for (std::uint32_t i = 0; i < n; ++i) {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ASSERT_EQ(vkBeginCommandBuffer(cmds[i], &bi), VK_SUCCESS);
    const Status st = effect.record(cmds[i], *cameras[i], settings, inputs[i], &outputs[i]);
    ASSERT_EQ(vkEndCommandBuffer(cmds[i]), VK_SUCCESS);
    ASSERT_TRUE(st.ok()) << "record " << i << ": " << st.message;
  }
  std::vector<VkSubmitInfo> si(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    si[i] = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si[i].commandBufferCount = 1;
    si[i].pCommandBuffers = &cmds[i];
  }
  ASSERT_EQ(vkQueueSubmit(ctx.queue(), n, si.data(), fence), VK_SUCCESS);
  ASSERT_EQ(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), VK_SUCCESS);
  vkDestroyFence(device, fence, nullptr);
  vkFreeCommandBuffers(device, ctx.commandPool(), n, cmds.data());
}

// Two command buffers recorded with cameras B and C (ring slots 1 and 0 after the record that
// planned with A), both pending at once, submitted together: each output is its camera's fresh
// result.
TEST_F(PerRecordCamera, TwoFramesInFlightKeepTheirCameras) {
  const Camera a = worldNormals(base, r0);
  const Camera b = worldNormals(jittered(cameraWith(55, 0.1), 0.25, 0.25), r1);
  const Camera c = worldNormals(jittered(base, -0.25, 0.4), test::viewRotation(1.1, 0.2, 0.0));
  const FloatImage expectedB = fresh(b), expectedC = fresh(c);
  ASSERT_GT(differences(expectedB, expectedC), 0u);
  vk::Config cfg;
  cfg.framesInFlight = 2;
  auto effect = create(cfg);
  ASSERT_TRUE(effect);
  run(*effect, a);  // planned with camera A

  vk::headless::Context& ctx = context();
  Image outB, outC;
  ASSERT_TRUE(ctx.createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, outB).ok());
  ASSERT_TRUE(ctx.createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, outC).ok());
  const Camera* cameras[2] = {&b, &c};
  const vk::Inputs in[2] = {inputs(b), inputs(c)};
  const vk::OutputImage outputs[2] = {outputOf(outB), outputOf(outC)};
  recordInFlight(*effect, settings, cameras, in, outputs, 2);
  EXPECT_EQ(effect->plans(), 1u) << "cameras B and C keep A's plan";
  EXPECT_EQ(differences(read(*effect, outB), expectedB), 0u) << "slot 1, camera B";
  EXPECT_EQ(differences(read(*effect, outC), expectedC), 0u) << "slot 0, camera C";
  ctx.destroy(outB);
  ctx.destroy(outC);
}

// A camera per record allocates nothing in the library once warm (the allocation counter of
// tests/common/library_allocations.h) and plans nothing: 64 jittered frames with an animated field
// of view and view rotation.
TEST_F(PerRecordCamera, NoAllocationPerRecord) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  vk::Config cfg;
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
                      const vk::Inputs in = inputs(camera);
                      test::startCountingAllocations();
                      recorded = effect->record(cmd, camera, settings, in, &o);
                      test::stopCountingAllocations();
                      if (f >= kWarmUp) counted += test::countedAllocations();
                    })
                    .ok());
    ASSERT_TRUE(recorded.ok()) << "frame " << f << ": " << recorded.message;
    last = camera;
  }
  EXPECT_EQ(counted, 0) << "library allocations in " << kFrames << " record() calls with a camera each";
  EXPECT_EQ(effect->plans(), 1u) << "every camera kept the first frame's plan";
  // params() is the last record's block: its camera's, as a fresh effect with it has it.
  ParamBlock withLast{};
  fresh(last, nullptr, &withLast);
  EXPECT_EQ(std::memcmp(&effect->params(), &withLast, sizeof(ParamBlock)), 0);
  // The counter sees the library: a camera of another size plans again, which allocates.
  const Camera other = worldNormals(cameraWith(60, 0.1, kW + 2), r0);
  prepareOtherGeometry(other);
  Image otherOut;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW + 2, kH}, otherOut).ok());
  const vk::OutputImage oo = outputOf(otherOut);
  Status replanned;
  ASSERT_TRUE(context()
                  .submit([&](VkCommandBuffer cmd) {
                    const vk::Inputs in = inputs(other);
                    test::startCountingAllocations();
                    replanned = effect->record(cmd, other, settings, in, &oo);
                    test::stopCountingAllocations();
                  })
                  .ok());
  EXPECT_TRUE(replanned.ok()) << replanned.message;
  EXPECT_EQ(effect->plans(), 2u);
  EXPECT_GT(test::countedAllocations(), 0);
  context().destroy(otherOut);
  context().destroy(out);
}

// A camera that changes the plan (size, guard band, csz levels) plans again within the call: it
// records while the previous frame (planned with A, recorded with a jittered camera into another
// command buffer) is still pending, both submitted together; each output is its camera's fresh
// result (under synchronization validation: the old plan's images live until that frame is done),
// and the next record with the jittered camera plans back, again equal to a fresh effect.
TEST_F(PerRecordCamera, CamerasThatChangeThePlanPlanAgainWhileFramesAreInFlight) {
  const Camera a = worldNormals(base, r0);
  const Camera valid = worldNormals(jittered(base, 0.2, 0.1), r1);
  const FloatImage expectedValid = fresh(valid);
  Camera orthographic = orthographicCamera(2.0, kW, kH, 0.1, 100.0, ClipDepth::ZeroToOne, false);
  orthographic.guardBand = kGuard;
  orthographic = worldNormals(orthographic, r0);
  struct Case {
    const char* name;
    Camera camera;
  };
  const Case cases[] = {
      {"another size", worldNormals(cameraWith(60, 0.1, kW + 2, kH), r0)},
      {"another guard band", worldNormals(cameraWith(60, 0.1, kW, kH, kGuard + 1), r0)},
      {"a near plane that needs fewer csz levels", worldNormals(cameraWith(60, 1.0), r0)},
      {"orthographic (fewer csz levels here)", orthographic},
  };
  vk::Config cfg;
  cfg.framesInFlight = 2;
  auto effect = create(cfg);
  ASSERT_TRUE(effect);
  run(*effect, a);
  const std::string planA = effect->plan().describe();
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    if (!baseGeometry(c.camera)) prepareOtherGeometry(c.camera);
    Plan expectedPlan;
    const FloatImage expected = fresh(c.camera, &expectedPlan);
    ASSERT_NE(expectedPlan.describe(), planA) << "the case must change the plan";
    Image outValid, outOther;
    ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, outValid).ok());
    ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {c.camera.width, c.camera.height}, outOther).ok());
    const std::uint64_t plansBefore = effect->plans();
    const Camera* cameras[2] = {&valid, &c.camera};
    const vk::Inputs in[2] = {inputs(valid), inputs(c.camera)};
    const vk::OutputImage outputs[2] = {outputOf(outValid), outputOf(outOther)};
    recordInFlight(*effect, settings, cameras, in, outputs, 2);
    EXPECT_EQ(effect->plans(), plansBefore + 1) << "the camera planned again, once";
    EXPECT_EQ(effect->plan().describe(), expectedPlan.describe());
    EXPECT_EQ(differences(read(*effect, outValid), expectedValid), 0u) << "the frame in flight on the old plan";
    EXPECT_EQ(differences(read(*effect, outOther), expected), 0u) << "the frame on the new plan";
    context().destroy(outValid);
    context().destroy(outOther);
    EXPECT_EQ(differences(run(*effect, valid), expectedValid), 0u) << "the next record, planned back";
    EXPECT_EQ(effect->plans(), plansBefore + 2);
    EXPECT_EQ(effect->plan().describe(), planA);
    expectNoMessages(c.name);
  }
}

// An invalid camera: the code and message a fresh effect's first record gives (the same check
// whether or not a plan exists), naming what is wrong; nothing recorded, no new plan, and the
// effect records the next valid camera exactly as a fresh effect does.
TEST_F(PerRecordCamera, RefusesInvalidCameras) {
  const Camera a = worldNormals(base, r0);
  auto effect = create();
  ASSERT_TRUE(effect);
  const Camera valid = worldNormals(jittered(base, 0.2, 0.1), r1);
  const FloatImage expectedValid = fresh(valid);
  run(*effect, a);

  Image out;
  ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
  const vk::OutputImage o = outputOf(out);
  // A fresh effect's first record of a camera: its code and message, or ok.
  auto freshStatus = [&](const Camera& camera) {
    auto e = create();
    Status st;
    const vk::Inputs in = inputs(camera);
    EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = e->record(cmd, camera, settings, in, &o); }).ok());
    EXPECT_EQ(e->plans(), 0u);
    return st;
  };
  Camera nonFinite = a;
  nonFinite.projection[5] = NAN;
  Camera noRotation = a;
  noRotation.viewRotation.reset();
  Camera scaled = a;
  for (int i = 0; i < 3; ++i) (*scaled.viewRotation)[std::size_t(i)] *= 1.5;
  struct Case {
    const char* name;
    Camera camera;
    StatusCode code;
    std::string says;  // in the message
  };
  const Case cases[] = {
      {"a non-finite projection", nonFinite, StatusCode::InvalidCamera, "non-finite element P11"},
      {"world normals without a rotation", noRotation, StatusCode::InvalidCamera, "needs Camera::viewRotation"},
      {"a scaled rotation", scaled, StatusCode::InvalidCamera, "is not a rotation"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Status st;
    const vk::Inputs in = inputs(c.camera);
    ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = effect->record(cmd, c.camera, settings, in, &o); }).ok());
    EXPECT_EQ(st.code, c.code) << st.message;
    EXPECT_NE(st.message.find(c.says), std::string::npos) << st.message;
    const Status refusedFresh = freshStatus(c.camera);
    EXPECT_EQ(refusedFresh.code, st.code) << refusedFresh.message;
    EXPECT_FALSE(refusedFresh.message.empty());
    EXPECT_EQ(st.message, refusedFresh.message) << "a fresh effect refuses it alike";
    EXPECT_EQ(effect->plans(), 1u) << "a refused camera plans nothing";
    EXPECT_EQ(differences(run(*effect, valid), expectedValid), 0u) << "the next valid record";
  }

  // The normals contract: a camera whose encoding reads more channels than the normals' format
  // (InputImage::format) has.
  Camera octahedral = a;
  octahedral.normalsEncoding = NormalsEncoding::CameraOctahedral;
  Image rgNormals;
  ASSERT_TRUE(context().uploadColor(FloatImage(depth.extent, 2), VK_FORMAT_R16G16_SFLOAT, kRead, rgNormals).ok());
  auto rgEffect = create();
  ASSERT_TRUE(rgEffect);
  vk::Inputs in = inputs(a);  // a: WorldXyz, three channels
  in.normals = {rgNormals.view, kRead, depth.extent, VK_FORMAT_R16G16_SFLOAT};
  Status st;
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = rgEffect->record(cmd, octahedral, settings, in, &o); }).ok());
  ASSERT_TRUE(st.ok()) << st.message;  // planned with the octahedral camera, which reads .xy
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = rgEffect->record(cmd, a, settings, in, &o); }).ok());
  EXPECT_EQ(st.code, StatusCode::UnsupportedFormat) << st.message;
  EXPECT_NE(st.message.find("Inputs::normals.format is VK_FORMAT_R16G16_SFLOAT (two channels)"), std::string::npos)
      << st.message;
  EXPECT_EQ(rgEffect->plans(), 1u);
  auto refused = create();
  Status created;
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { created = refused->record(cmd, a, settings, in, &o); }).ok());
  EXPECT_EQ(created.code, StatusCode::UnsupportedFormat) << created.message;
  EXPECT_EQ(refused->plans(), 0u);
  EXPECT_EQ(st.message, created.message) << "a fresh effect refuses it alike";
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = rgEffect->record(cmd, octahedral, settings, in, &o); }).ok());
  EXPECT_TRUE(st.ok()) << st.message;
  context().destroy(rgNormals);
  context().destroy(out);
}

// record() plans again exactly when sao::plan() of the camera differs from the effect's current
// plan, over fields of view, near planes, units, projection kinds and conventions; and a camera
// that plans alike records without any library allocation (core's cameraKeepsPlan decides
// without calling sao::plan(), which allocates).
TEST_F(PerRecordCamera, PlansAgainExactlyForTheCamerasThatPlanOtherwise) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  auto effect = create();
  ASSERT_TRUE(effect);
  run(*effect, base);
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
  // Back to the base camera, then two that change the size or guard band (their own depth).
  cameras.push_back(base);
  cameras.push_back(vulkanCamera(kW, kH, kGuard + 4));
  cameras.push_back(vulkanCamera(kW - 1, kH, kGuard));
  int kept = 0, replanned = 0;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    SCOPED_TRACE("camera " + std::to_string(i));
    const Camera& camera = cameras[i];
    if (!baseGeometry(camera)) prepareOtherGeometry(camera);
    Plan p;
    const Status planned = sao::plan(settings, camera, {DepthEncoding::Hardware, {}, true, gen::Format::R16F}, p);
    ASSERT_TRUE(planned.ok()) << planned.message;
    const std::string current = effect->plan().describe();
    const bool same = p.describe() == current;
    const std::uint64_t plansBefore = effect->plans();
    Image out;
    ASSERT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {camera.width, camera.height}, out).ok());
    const vk::OutputImage o = outputOf(out);
    const vk::Inputs in = inputs(camera);
    Status st;
    ASSERT_TRUE(context()
                    .submit([&](VkCommandBuffer cmd) {
                      test::startCountingAllocations();
                      st = effect->record(cmd, camera, settings, in, &o);
                      test::stopCountingAllocations();
                    })
                    .ok());
    context().destroy(out);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(effect->plans() - plansBefore, same ? 0u : 1u)
        << "plan of the camera:\n" << p.describe() << "effect's plan:\n" << current;
    EXPECT_EQ(effect->plan().describe(), p.describe());
    if (same) {
      EXPECT_EQ(test::countedAllocations(), 0) << "a camera that keeps the plan allocates nothing";
    }
    (same ? kept : replanned)++;
  }
  EXPECT_GT(kept, 5);
  EXPECT_GT(replanned, 5);
  std::printf("%d cameras planned alike and kept the plan, %d planned otherwise and planned again\n", kept, replanned);
}

}  // namespace
}  // namespace sao::vktest
