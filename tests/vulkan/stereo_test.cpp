// Stereo on Vulkan (issue 19): two eyes in the two array layers of one depth image and one output
// image, processed by ONE effect recorded twice into one command buffer, each record with its
// eye's per-layer views, OutputImage::layer and Inputs::camera (a mirrored off-axis projection, as
// VR runtimes give). Under validation and synchronization validation (any message fails): each
// output layer is bit for bit what a single-eye effect created with that eye's camera writes from
// plain 2D images, and agrees with the CPU reference within reference_test.cpp's bounds; the stereo
// effect holds exactly one eye's fixed costs (device memory, pipelines), not two; a loop of stereo
// frames allocates nothing in the library; a layer no image can have is refused.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "analytic_scenes.h"
#include "library_allocations.h"
#include "sao/frame.h"
#include "sao/cpu/reference.h"
#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

using vk::headless::Buffer;
using vk::headless::Image;

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8, kEyes = 2;
constexpr double kWithin = 2.0 / 255.0, kNever = 4.0 / 255.0;  // reference_test.cpp's bounds
constexpr double kEyeShift = 0.04;  // projection (row 0, column 2): the off-axis frustum's shift

// The left (eye 0) and right (eye 1) cameras: mirrored asymmetric frusta.
Camera eyeCamera(std::uint32_t eye) {
  Camera c = vulkanCamera(kW, kH, kGuard);
  c.projection[2 * 4 + 0] += eye == 0 ? kEyeShift : -kEyeShift;
  return c;
}

// A 2-layer image with one VK_IMAGE_VIEW_TYPE_2D view per layer, left UNDEFINED.
struct ArrayImage {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView views[kEyes]{};
};

Status vkFail(const char* what, VkResult r) {
  return Status::error(StatusCode::DriverError, std::string(what) + " failed: VkResult " + std::to_string(int(r)));
}

void destroy(ArrayImage& a) {
  const VkDevice device = context().device();
  for (VkImageView v : a.views)
    if (v) vkDestroyImageView(device, v, nullptr);
  if (a.image) vkDestroyImage(device, a.image, nullptr);
  if (a.memory) vkFreeMemory(device, a.memory, nullptr);
  a = ArrayImage{};
}

Status createArrayImage(VkFormat format, Extent extent, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                        ArrayImage& out) {
  const VkDevice device = context().device();
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {extent.width, extent.height, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = kEyes;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (VkResult r = vkCreateImage(device, &ci, nullptr, &out.image); r != VK_SUCCESS) return vkFail("vkCreateImage", r);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, out.image, &req);
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(context().physicalDevice(), &mp);
  std::uint32_t type = 0;
  while (type < mp.memoryTypeCount && !(req.memoryTypeBits & (1u << type))) ++type;
  if (type == mp.memoryTypeCount) return Status::error(StatusCode::DriverError, "no memory type for the array image");
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
  if (VkResult r = vkAllocateMemory(device, &ai, nullptr, &out.memory); r != VK_SUCCESS)
    return vkFail("vkAllocateMemory", r);
  if (VkResult r = vkBindImageMemory(device, out.image, out.memory, 0); r != VK_SUCCESS)
    return vkFail("vkBindImageMemory", r);
  for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = out.image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {aspect, 0, 1, eye, 1};
    if (VkResult r = vkCreateImageView(device, &vi, nullptr, &out.views[eye]); r != VK_SUCCESS)
      return vkFail("vkCreateImageView", r);
  }
  return Status::success();
}

VkImageMemoryBarrier layerBarrier(VkImage image, VkImageAspectFlags aspect, std::uint32_t layer, std::uint32_t layers,
                                  VkImageLayout from, VkImageLayout to, VkAccessFlags src, VkAccessFlags dst) {
  VkImageMemoryBarrier b = vk::headless::imageBarrier(image, aspect, from, to, src, dst);
  b.subresourceRange.baseArrayLayer = layer;
  b.subresourceRange.layerCount = layers;
  return b;
}

// Layer i of a new 2-layer D32_SFLOAT image holds depth[i], in SHADER_READ_ONLY_OPTIMAL, visible to
// compute reads.
Status uploadDepthLayers(const DepthImage (&depth)[kEyes], ArrayImage& out) {
  const Extent extent = depth[0].extent;
  const std::size_t n = std::size_t(extent.width) * extent.height;
  if (Status st = createArrayImage(VK_FORMAT_D32_SFLOAT, extent,
                                   VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                   VK_IMAGE_ASPECT_DEPTH_BIT, out);
      !st)
    return st;
  Buffer staging;
  if (Status st = context().createBuffer(kEyes * n * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, staging); !st) return st;
  for (std::uint32_t eye = 0; eye < kEyes; ++eye)
    std::memcpy(static_cast<std::uint32_t*>(staging.mapped) + eye * n, depth[eye].texels.data(), n * 4);
  const Status st = context().submit([&](VkCommandBuffer cmd) {
    const auto toDst = layerBarrier(out.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, kEyes, VK_IMAGE_LAYOUT_UNDEFINED,
                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &toDst);
    VkBufferImageCopy copies[kEyes]{};
    for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
      copies[eye].bufferOffset = eye * n * 4;
      copies[eye].imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, eye, 1};
      copies[eye].imageExtent = {extent.width, extent.height, 1};
    }
    vkCmdCopyBufferToImage(cmd, staging.buffer, out.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kEyes, copies);
    const auto toRead = layerBarrier(out.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, kEyes, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                                     VK_ACCESS_SHADER_READ_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &toRead);
  });
  context().destroy(staging);
  return st;
}

// Layer `layer` of an R16_SFLOAT array image that record() left in `layout` (written at
// srcStages / srcAccess), read back as floats; the layer goes back to `layout`.
Status readLayer(const ArrayImage& image, std::uint32_t layer, VkImageLayout layout, VkPipelineStageFlags srcStages,
                 VkAccessFlags srcAccess, FloatImage& out) {
  const std::size_t n = std::size_t(kW) * kH;
  Buffer staging;
  if (Status st = context().createBuffer(n * 2, VK_BUFFER_USAGE_TRANSFER_DST_BIT, staging); !st) return st;
  const Status st = context().submit([&](VkCommandBuffer cmd) {
    const auto pre = layerBarrier(image.image, VK_IMAGE_ASPECT_COLOR_BIT, layer, 1, layout,
                                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, srcAccess, VK_ACCESS_TRANSFER_READ_BIT);
    vkCmdPipelineBarrier(cmd, srcStages, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &pre);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, layer, 1};
    copy.imageExtent = {kW, kH, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &copy);
    const auto post = layerBarrier(image.image, VK_IMAGE_ASPECT_COLOR_BIT, layer, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                   layout, 0, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &post);
    VkBufferMemoryBarrier host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    host.buffer = staging.buffer;
    host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &host, 0,
                         nullptr);
  });
  if (st) {
    out = FloatImage({kW, kH}, 1);
    for (std::size_t i = 0; i < n; ++i) out.data[i] = halfToFloat(static_cast<const std::uint16_t*>(staging.mapped)[i]);
  }
  context().destroy(staging);
  return st;
}

class Stereo : public VkTest {
 public:  // the helpers below the class use the fixture
  void SetUp() override {
    VkTest::SetUp();
    const test::Scene scene = test::sphereOnPlaneScene();
    for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
      cameras[eye] = eyeCamera(eye);
      depth[eye] = test::renderDepth(scene, cameras[eye], DepthFormat::D32F);
    }
    ASSERT_TRUE(uploadDepthLayers(depth, depthArray).ok());
    ASSERT_TRUE(createArrayImage(VK_FORMAT_R16_SFLOAT, {kW, kH},
                                 VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 VK_IMAGE_ASPECT_COLOR_BIT, outputArray)
                    .ok());
  }
  void TearDown() override {
    destroy(depthArray);
    destroy(outputArray);
    VkTest::TearDown();
  }

  static vk::Config config(const Camera& camera, std::uint32_t framesInFlight,
                           const Settings& settings = presetSettings(Preset::Medium)) {
    vk::Config c;
    c.settings = settings;
    c.camera = camera;
    c.depthFormat = VK_FORMAT_D32_SFLOAT;
    c.userOutput = true;  // stereo needs the caller's output: one layer per eye
    c.framesInFlight = framesInFlight;
    return c;
  }
  static std::unique_ptr<vk::Effect> create(const vk::Config& c) {
    std::unique_ptr<vk::Effect> e;
    const Status st = vk::Effect::create(context().deviceContext(), c, e);
    EXPECT_TRUE(st.ok()) << st.message;
    return e;
  }
  // The stereo effect: Config::camera is the left eye; 2 frames in flight x 2 eyes.
  static std::unique_ptr<vk::Effect> createStereo(const Settings& settings = presetSettings(Preset::Medium)) {
    return create(config(eyeCamera(0), 2 * kEyes, settings));
  }

  vk::Inputs eyeInputs(std::uint32_t eye) const {
    vk::Inputs in;
    in.depth = {depthArray.views[eye], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth[eye].extent, VK_FORMAT_D32_SFLOAT};
    in.camera = eye == 0 ? nullptr : &cameras[eye];  // the left eye is Config::camera
    return in;
  }
  vk::OutputImage eyeOutput(std::uint32_t eye) const {
    return {outputArray.image, outputArray.views[eye], VK_FORMAT_R16_SFLOAT, {kW, kH}, VK_IMAGE_LAYOUT_UNDEFINED, eye};
  }
  // Both eyes recorded into `cmd`: left then right.
  Status recordStereo(vk::Effect& e, VkCommandBuffer cmd) const {
    for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
      const vk::OutputImage o = eyeOutput(eye);
      if (Status st = e.record(cmd, eyeInputs(eye), &o); !st) return st;
    }
    return Status::success();
  }
  void readEyes(const vk::Effect& e, FloatImage (&out)[kEyes]) const {
    const vk::Config& c = e.config();
    for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
      const Status st = readLayer(outputArray, eye, c.outputLayout, c.outputDstStages, c.outputDstAccess, out[eye]);
      EXPECT_TRUE(st.ok()) << st.message;
    }
  }

  // A single-eye effect created with that eye's camera on plain 2D images: the reference.
  FloatImage mono(std::uint32_t eye, const Settings& settings) const {
    Image depthImage, out;
    EXPECT_TRUE(
        context().uploadDepth(depth[eye], VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depthImage).ok());
    EXPECT_TRUE(context().createStorageImage(VK_FORMAT_R16_SFLOAT, {kW, kH}, out).ok());
    FloatImage ao;
    if (auto e = create(config(cameras[eye], 2, settings))) {
      vk::Inputs in;
      in.depth = {depthImage.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth[eye].extent, VK_FORMAT_D32_SFLOAT};
      const vk::OutputImage o{out.image, out.view, VK_FORMAT_R16_SFLOAT, {kW, kH}};
      Status recorded;
      EXPECT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = e->record(cmd, in, &o); }).ok());
      EXPECT_TRUE(recorded.ok()) << recorded.message;
      const vk::Config& c = e->config();
      EXPECT_TRUE(
          context().readback(out.image, VK_FORMAT_R16_SFLOAT, {kW, kH}, 0, c.outputLayout, c.outputDstStages, c.outputDstAccess, ao)
              .ok());
    }
    context().destroy(depthImage);
    context().destroy(out);
    return ao;
  }

  Camera cameras[kEyes];
  DepthImage depth[kEyes];
  ArrayImage depthArray, outputArray;
};

// Texels whose bits differ.
std::size_t differences(const FloatImage& a, const FloatImage& b) {
  EXPECT_EQ(a.data.size(), b.data.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < std::min(a.data.size(), b.data.size()); ++i)
    n += std::memcmp(&a.data[i], &b.data[i], sizeof(float)) != 0;
  return n;
}

TEST_F(Stereo, EyesPlanAlike) {
  const vk::Config c = config(cameras[0], 2 * kEyes);
  const PlanInputs inputs{DepthEncoding::Hardware, false, false, true, gen::Format::R16F};
  Plan plans[kEyes];
  for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
    const Status st = sao::plan(c.settings, cameras[eye], inputs, plans[eye]);
    ASSERT_TRUE(st.ok()) << st.message;
  }
  EXPECT_EQ(plans[0].describe(), plans[1].describe());
  EXPECT_EQ(plans[0].totalBytes, plans[1].totalBytes);
  EXPECT_EQ(plans[0].cszLevels, plans[1].cszLevels);
  EXPECT_TRUE(cameraKeepsPlan(c.settings, cameras[0], cameras[1]));
  EXPECT_NE(cameras[0].projection, cameras[1].projection) << "the eyes must differ";
}

// One command buffer, both eyes: each layer is the single-eye effect's result bit for bit and
// agrees with the CPU reference.
// Both eyes of one effect equal two single-eye effects bit for bit, and the CPU reference within
// the agreement bounds, with `settings`.
void expectEyesMatchSingleEyeEffects(Stereo& t, const Settings& settings) {
  auto effect = Stereo::createStereo(settings);
  ASSERT_TRUE(effect);
  Status recorded;
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = t.recordStereo(*effect, cmd); }).ok());
  ASSERT_TRUE(recorded.ok()) << recorded.message;
  FloatImage stereo[kEyes];
  t.readEyes(*effect, stereo);
  expectNoMessages("recording and running both eyes");

  const char* names[kEyes] = {"left", "right"};
  FloatImage expected[kEyes];
  for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
    SCOPED_TRACE(names[eye]);
    expected[eye] = t.mono(eye, settings);
    EXPECT_EQ(differences(stereo[eye], expected[eye]), 0u) << "texels unlike the single-eye effect";

    cpu::Result ref;
    cpu::Inputs in;
    in.depth = &t.depth[eye];
    const Status cs = cpu::run(settings, t.cameras[eye], in, {cpu::Precision::Float, 2}, ref);
    ASSERT_TRUE(cs.ok()) << cs.message;
    std::string note;
    const Agreement a = compare(stereo[eye], ref.ao, 0, kWithin, kNever, std::string("vk_stereo_") + names[eye], &note);
    EXPECT_TRUE(acceptable(a)) << a.fractionWithin * 100 << "% within 2/255, " << a.beyond << " beyond 4/255, max "
                               << a.maxAbs * 255 << "/255. " << note;
    std::printf("%s eye vs CPU reference (float): max %.4f/255, p999 %.4f/255, %.3f%% within 2/255\n", names[eye],
                a.maxAbs * 255, a.p999 * 255, a.fractionWithin * 100);
  }
  EXPECT_GT(differences(stereo[0], stereo[1]), 0u) << "the eyes gave the same image: the test would prove nothing";
  for (const FloatImage& ao : stereo)
    EXPECT_LT(*std::min_element(ao.data.begin(), ao.data.end()), 0.5f) << "no occlusion: the test would prove little";
}

TEST_F(Stereo, OneEffectTwoLayersMatchesTwoSingleEyeEffects) {
  expectEyesMatchSingleEyeEffects(*this, presetSettings(Preset::Medium));
}

// The visibility estimator (estimator 1, with thickness from width) per eye as well.
TEST_F(Stereo, VisibilityEstimatorEyesMatchSingleEyeEffects) {
  Settings settings = presetSettings(Preset::Medium);
  settings.estimator = 1;
  settings.thickness_model = 1;
  expectEyesMatchSingleEyeEffects(*this, settings);
}

// The fixed costs of stereo are one eye's: the stereo effect holds exactly the device memory and
// pipelines of a single-eye effect with the same ring, and less memory than two single-eye effects
// (the VR renderer's alternative, one per eye with 2 frames in flight each).
TEST_F(Stereo, FixedCostsAreOneEffects) {
  auto stereo = createStereo();
  auto sameRing = create(config(cameras[1], 2 * kEyes));
  auto left = create(config(cameras[0], 2));
  auto right = create(config(cameras[1], 2));
  ASSERT_TRUE(stereo && sameRing && left && right);
  const vk::MemoryStats s = stereo->memoryStats(), m = sameRing->memoryStats();
  const std::uint64_t two = left->memoryStats().liveBytes + right->memoryStats().liveBytes;
  std::printf("device memory: stereo effect (framesInFlight 4) %llu bytes in %llu allocations; single-eye effect with "
              "framesInFlight 4: %llu bytes; two single-eye effects (framesInFlight 2 each) %llu bytes; stereo / two "
              "= %.3f\n",
              static_cast<unsigned long long>(s.liveBytes), static_cast<unsigned long long>(s.liveAllocations),
              static_cast<unsigned long long>(m.liveBytes), static_cast<unsigned long long>(two),
              double(s.liveBytes) / double(two));
  std::printf("pipelines: stereo %u, two single-eye effects %u\n", stereo->pipelineCount(),
              left->pipelineCount() + right->pipelineCount());
  EXPECT_EQ(s.liveBytes, m.liveBytes) << "the stereo effect is one effect's memory";
  EXPECT_EQ(s.liveAllocations, m.liveAllocations);
  EXPECT_LT(s.liveBytes, two);
  EXPECT_EQ(stereo->pipelineCount(), left->pipelineCount());
  EXPECT_EQ(left->pipelineCount(), right->pipelineCount());
  // Recording both eyes builds nothing more and allocates no device memory.
  Status recorded;
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = recordStereo(*stereo, cmd); }).ok());
  ASSERT_TRUE(recorded.ok()) << recorded.message;
  EXPECT_EQ(stereo->memoryStats().totalAllocations, s.totalAllocations);
  EXPECT_EQ(stereo->pipelineCount(), left->pipelineCount());
}

// Eight stereo frames, each submitted and waited for: no library allocation in any record() after
// the first frame, and every frame's layers are the first frame's bits.
TEST_F(Stereo, FrameLoopAllocatesNothing) {
  ASSERT_TRUE(test::watchLibraryOf(reinterpret_cast<const void*>(&vk::processMemoryStats)));
  auto effect = createStereo();
  ASSERT_TRUE(effect);
  FloatImage first[kEyes];
  long counted = 0;
  constexpr int kWarmUp = 1, kFrames = 8;
  for (int f = 0; f < kWarmUp + kFrames; ++f) {
    Status recorded;
    ASSERT_TRUE(context()
                    .submit([&](VkCommandBuffer cmd) {
                      test::startCountingAllocations();
                      recorded = recordStereo(*effect, cmd);
                      test::stopCountingAllocations();
                      if (f >= kWarmUp) counted += test::countedAllocations();
                    })
                    .ok());
    ASSERT_TRUE(recorded.ok()) << "frame " << f << ": " << recorded.message;
    FloatImage eyes[kEyes];
    readEyes(*effect, eyes);
    for (std::uint32_t eye = 0; eye < kEyes; ++eye) {
      if (f == 0) first[eye] = eyes[eye];
      else EXPECT_EQ(differences(eyes[eye], first[eye]), 0u) << "frame " << f << " eye " << eye;
    }
  }
  EXPECT_EQ(counted, 0) << "library allocations in " << 2 * kFrames << " stereo record() calls";
}

// A layer beyond the device's maxImageArrayLayers cannot be one of the image's: refused, nothing
// recorded; the next stereo frame is right.
TEST_F(Stereo, RefusesALayerNoImageHas) {
  auto effect = createStereo();
  ASSERT_TRUE(effect);
  vk::OutputImage o = eyeOutput(1);
  o.layer = context().properties().limits.maxImageArrayLayers;
  Status st;
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { st = effect->record(cmd, eyeInputs(1), &o); }).ok());
  EXPECT_EQ(st.code, StatusCode::InvalidInput) << st.message;
  EXPECT_NE(st.message.find("OutputImage::layer"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("maxImageArrayLayers"), std::string::npos) << st.message;
  Status recorded;
  ASSERT_TRUE(context().submit([&](VkCommandBuffer cmd) { recorded = recordStereo(*effect, cmd); }).ok());
  ASSERT_TRUE(recorded.ok()) << recorded.message;
  FloatImage eyes[kEyes];
  readEyes(*effect, eyes);
  EXPECT_EQ(differences(eyes[1], mono(1, presetSettings(Preset::Medium))), 0u);
}

}  // namespace
}  // namespace sao::vktest
