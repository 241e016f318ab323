#include "engine_transfer.h"

#include <cstring>
#include <string>

#include "sao/plan.h"

namespace sao::vkengine {
namespace {

// Frees its buffer on every path out of a transfer.
struct StagingBuffer {
  const Device& device;
  Buffer buffer;
  ~StagingBuffer() { buffer.destroy(device.device()); }
};

}  // namespace

Status uploadDepth(const Device& device, const DepthImage& depth, Image& out) {
  if (depth.samples > 1 || (depth.format != DepthFormat::D32F && depth.format != DepthFormat::LinearZ))
    return Status::error(StatusCode::UnsupportedFormat, "the engine uploads single-sampled D32F or LinearZ depth, not " +
                                                            std::string(toString(depth.format)) + " of " +
                                                            std::to_string(depth.samples) + " sample(s)");
  const bool linear = depth.format == DepthFormat::LinearZ;
  const VkImageAspectFlags aspect = linear ? VK_IMAGE_ASPECT_COLOR_BIT : VK_IMAGE_ASPECT_DEPTH_BIT;
  const VkFormat format = linear ? VK_FORMAT_R32_SFLOAT : VK_FORMAT_D32_SFLOAT;
  if (!device.hasFeatures(format, VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT))
    return Status::error(StatusCode::UnsupportedFormat, "the device cannot sample VkFormat " + std::to_string(format));
  if (Status st = makeImage(device, format, aspect, depth.extent, 1,
                            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, out);
      !st)
    return st;
  const VkDeviceSize bytes = depth.texels.size() * sizeof(std::uint32_t);  // D32F and LinearZ: the floats' bits
  StagingBuffer staging{device, {}};
  if (Status st = makeBuffer(device, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, staging.buffer); !st) return st;
  std::memcpy(staging.buffer.mapped, depth.texels.data(), bytes);
  return device.submitOnce([&](VkCommandBuffer cmd) {
    cmdBarriers(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                {imageBarrier(out.image, aspect, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                              VK_ACCESS_TRANSFER_WRITE_BIT)});
    const VkBufferImageCopy region{0, 0, 0, {aspect, 0, 0, 1}, {}, {depth.extent.width, depth.extent.height, 1}};
    vkCmdCopyBufferToImage(cmd, staging.buffer.buffer, out.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    cmdBarriers(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                {imageBarrier(out.image, aspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT, 0)});
  });
}

Status readImage(const Device& device, const Image& image, gen::Format format, std::uint32_t level, FloatImage& out) {
  const gen::FormatInfo& info = gen::formatInfo(format);
  const std::uint32_t componentBytes = info.colour ? info.bytesPerTexel / info.channels : 0;
  if (componentBytes != 4 && componentBytes != 2 && !(componentBytes == 1 && info.unorm))
    return Status::error(StatusCode::UnsupportedFormat, "the engine cannot read back " + std::string(info.name));
  if (level >= image.levels.size())
    return Status::error(StatusCode::InvalidInput, "level " + std::to_string(level) + " of an image of " +
                                                       std::to_string(image.levels.size()) + " level(s)");
  const Extent extent = levelExtent(image.extent, level);
  out = FloatImage(extent, info.channels);
  StagingBuffer host{device, {}};
  if (Status st = makeBuffer(device, out.data.size() * componentBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, host.buffer);
      !st)
    return st;
  constexpr VkPipelineStageFlags compute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  constexpr VkPipelineStageFlags transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
  const Status st = device.submitOnce([&](VkCommandBuffer cmd) {
    // After the frame's stores (compute) or an earlier readback's return to GENERAL (whose second
    // scope is compute): the source stages name both, so the chain holds either way.
    cmdBarriers(cmd, compute | transfer, transfer,
                {imageBarrier(image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                              VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_SHADER_WRITE_BIT,
                              VK_ACCESS_TRANSFER_READ_BIT, level, 1)});
    const VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1}, {}, {extent.width, extent.height, 1}};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host.buffer.buffer, 1, &region);
    // Back in GENERAL before the next frame's loads and stores.
    cmdBarriers(cmd, transfer, compute,
                {imageBarrier(image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                              level, 1)});
    const VkBufferMemoryBarrier toHost{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                                       VK_ACCESS_HOST_READ_BIT, VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED,
                                       host.buffer.buffer, 0, VK_WHOLE_SIZE};
    vkCmdPipelineBarrier(cmd, transfer, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &toHost, 0, nullptr);
  });
  if (!st) return st;
  const auto* bytes = static_cast<const unsigned char*>(host.buffer.mapped);
  for (std::size_t i = 0; i < out.data.size(); ++i) {
    if (componentBytes == 4) {
      std::memcpy(&out.data[i], bytes + 4 * i, 4);
    } else if (componentBytes == 2) {
      std::uint16_t half;
      std::memcpy(&half, bytes + 2 * i, 2);
      out.data[i] = halfToFloat(half);
    } else {
      out.data[i] = float(bytes[i]) / 255.0f;
    }
  }
  return Status::success();
}

}  // namespace sao::vkengine
