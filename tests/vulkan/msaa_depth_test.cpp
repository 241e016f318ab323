// A multisampled depth input, Vulkan only (InputImage::samples): record() refuses a count that is
// not one sample bit and counts the device cannot sample, and plans DEPTH_MULTISAMPLE with the
// count for those it can. Both policies against the CPU reference and the single-sample runs, and
// the second-layer refusal: tests/executors/msaa_depth_test.cpp.
#include <cstdio>
#include <string>
#include <tuple>

#include "sao/presets.h"
#include "vk_support.h"

namespace sao::vktest {
namespace {

constexpr std::uint32_t kW = 160, kH = 90, kGuard = 8;
constexpr auto kMultisample = static_cast<std::size_t>(gen::VariantId::DEPTH_MULTISAMPLE);
constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

class MsaaDepth : public VkTest {};

// A `format` image (D32_SFLOAT or R32_SFLOAT) of `samples` samples, every sample cleared to
// `value` (the count and format are what this test is about, not the values), left in kRead and
// visible to compute-shader reads; free it with ctx.destroy(out). Cleared because a multisampled
// image cannot be filled by a buffer copy.
Status clearedImage(VkFormat format, Extent extent, VkSampleCountFlagBits samples, float value,
                    vk::headless::Image& out) {
  vk::headless::Context& ctx = context();
  const VkDevice d = ctx.device();
  const bool depth = format == VK_FORMAT_D32_SFLOAT;
  const VkImageAspectFlags aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  out = {};
  out.format = format;
  out.extent = extent;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {extent.width, extent.height, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = 1;
  ci.samples = samples;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImageFormatProperties ip{};
  if (VkResult r = vkGetPhysicalDeviceImageFormatProperties(ctx.physicalDevice(), format, ci.imageType, ci.tiling,
                                                            ci.usage, 0, &ip);
      r != VK_SUCCESS || !(ip.sampleCounts & samples))
    return Status::error(StatusCode::UnsupportedFormat, "this device makes no sampled, transfer-destination image of " +
                                                            std::to_string(int(samples)) + " samples in this format");
  // A failed call: what was made so far destroyed, the call named.
  auto failed = [&](const char* call, VkResult r) {
    ctx.destroy(out);
    return Status::error(StatusCode::DriverError, std::string(call) + " failed (VkResult " + std::to_string(r) + ")");
  };
  if (VkResult r = vkCreateImage(d, &ci, nullptr, &out.image); r != VK_SUCCESS) return failed("vkCreateImage", r);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(d, out.image, &req);
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &mem);
  std::uint32_t type = 0;
  while (type < mem.memoryTypeCount && !(req.memoryTypeBits & (1u << type))) ++type;
  const VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
  if (VkResult r = vkAllocateMemory(d, &ai, nullptr, &out.memory); r != VK_SUCCESS)
    return failed("vkAllocateMemory", r);
  if (VkResult r = vkBindImageMemory(d, out.image, out.memory, 0); r != VK_SUCCESS)
    return failed("vkBindImageMemory", r);
  const VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, nullptr, 0, out.image, VK_IMAGE_VIEW_TYPE_2D,
                                 format, {}, {aspect, 0, 1, 0, 1}};
  if (VkResult r = vkCreateImageView(d, &vi, nullptr, &out.view); r != VK_SUCCESS)
    return failed("vkCreateImageView", r);
  const VkImage image = out.image;
  Status st = ctx.submit([&](VkCommandBuffer cmd) {
    VkImageMemoryBarrier toDst = vk::headless::imageBarrier(image, aspect, VK_IMAGE_LAYOUT_UNDEFINED,
                                                            VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                                                            VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &toDst);
    const VkImageSubresourceRange range{aspect, 0, 1, 0, 1};
    if (depth) {
      const VkClearDepthStencilValue v{value, 0};
      vkCmdClearDepthStencilImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
    } else {
      VkClearColorValue v{};
      v.float32[0] = value;
      vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
    }
    VkImageMemoryBarrier toRead = vk::headless::imageBarrier(image, aspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kRead,
                                                             VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                         nullptr, 1, &toRead);
  });
  if (!st) ctx.destroy(out);
  return st;
}

// One record of a fresh effect with a depth of `format` declared as `samples` samples (the image
// has them where the device can sample them, else one: a refused record never reads it).
struct Recorded {
  Status status;
  std::unique_ptr<vk::Effect> effect;
};
Recorded recordWithSamples(VkFormat format, VkSampleCountFlagBits samples, bool sampleable) {
  const Camera camera = vulkanCamera(kW, kH, kGuard, 100.0);
  const Extent extent{kW + 2 * kGuard, kH + 2 * kGuard};
  Recorded r;
  vk::headless::Image image;
  // Hardware depth 0.5; linear z 5 m in front of the camera.
  const float value = format == VK_FORMAT_R32_SFLOAT ? -5.0f : 0.5f;
  r.status = clearedImage(format, extent, sampleable ? samples : VK_SAMPLE_COUNT_1_BIT, value, image);
  if (!r.status) return r;
  r.status = vk::Effect::create(context().deviceContext(), {}, r.effect);
  vk::Inputs in;
  in.depth = {image.view, kRead, extent, format, samples};
  const Settings settings = presetSettings(Preset::Medium);
  if (r.status)
    r.status = submitRecord([&](VkCommandBuffer cmd) { return r.effect->record(cmd, camera, settings, in); });
  context().destroy(image);
  return r;
}

TEST_F(MsaaDepth, RecordRefusesBadSampleCounts) {
  {
    const Recorded r = recordWithSamples(VK_FORMAT_D32_SFLOAT, static_cast<VkSampleCountFlagBits>(3), false);
    expectStatus(r.status, StatusCode::InvalidInput, "Inputs::depth.samples");
    ASSERT_TRUE(r.effect);
    EXPECT_EQ(r.effect->plans(), 0u) << "a refused record plans nothing";
  }
  // Each count against the device's limit for the format: refused exactly where it cannot sample it.
  const auto& limits = context().properties().limits;
  for (const auto& [format, counts, what] :
       {std::tuple{VK_FORMAT_D32_SFLOAT, limits.sampledImageDepthSampleCounts, "D32_SFLOAT"},
        std::tuple{VK_FORMAT_R32_SFLOAT, limits.sampledImageColorSampleCounts, "R32_SFLOAT"}}) {
    std::printf("%s: sampled image sample counts 0x%x\n", what, unsigned(counts));
    for (std::uint32_t n = 2; n <= 64; n *= 2) {
      SCOPED_TRACE(std::string(what) + " " + std::to_string(n) + " samples");
      const bool sampleable = (counts & n) != 0;
      const Recorded r = recordWithSamples(format, static_cast<VkSampleCountFlagBits>(n), sampleable);
      ASSERT_TRUE(r.effect) << r.status.message;
      if (sampleable) {
        ASSERT_TRUE(r.status.ok()) << r.status.message;
        EXPECT_EQ(r.effect->plan().variants[kMultisample], 1);
        EXPECT_EQ(r.effect->params().depth_samples, int(n));
      } else {
        expectStatus(r.status, StatusCode::UnsupportedFormat, "Inputs::depth.samples");
        EXPECT_EQ(r.effect->plans(), 0u) << "a refused record plans nothing";
      }
    }
  }
}

}  // namespace
}  // namespace sao::vktest
