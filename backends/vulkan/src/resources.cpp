// Effect-owned images as FrameState asks for them (sao/executor.h), their memory and views, and the
// parameter buffer.
#include <algorithm>
#include <string>
#include <utility>

#include "effect_impl.h"

namespace sao::vk {

VkFormat vkFormat(gen::Format format) { return static_cast<VkFormat>(gen::formatInfo(format).vkFormat); }

gen::Format outputFormatOf(VkFormat format) {
  for (gen::Format f : outputFormats())
    if (vkFormat(f) == format) return f;
  return gen::Format::Depth;
}

namespace {

Status createView(const EffectState& e, VkImage image, VkFormat format, std::uint32_t baseLevel, std::uint32_t levels,
                  Handle<VkImageView>& out) {
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.image = image;
  info.viewType = VK_IMAGE_VIEW_TYPE_2D;
  info.format = format;
  info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, baseLevel, levels, 0, 1};
  if (VkResult r = make(e.owner, e.d.vkCreateImageView, e.d.vkDestroyImageView, info, out); r != VK_SUCCESS)
    return vkError("vkCreateImageView", r);
  return Status::success();
}

}  // namespace

Status createImages(EffectState& e, const PlannedImage& planned) {
  const auto& info = gen::kResources[static_cast<std::size_t>(planned.resource)];
  const VkFormat format = vkFormat(planned.format);
  VkFormatProperties fp{};
  e.d.vkGetPhysicalDeviceFormatProperties(e.ctx.physicalDevice, format, &fp);
  constexpr VkFormatFeatureFlags need = VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
  if ((fp.optimalTilingFeatures & need) != need)
    return Status::error(StatusCode::UnsupportedFormat,
                         "the device cannot use format " + std::to_string(format) + " of image '" +
                             std::string(info.name) + "' as an optimal-tiling storage and sampled image");
  std::vector<OwnedImage> made;
  made.reserve(planned.copies);
  for (std::uint32_t copy = 0; copy < planned.copies; ++copy) {
    OwnedImage img;
    img.planned = planned;
    img.copy = copy;
    img.format = format;
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {planned.extent.width, planned.extent.height, 1};
    ci.mipLevels = planned.mipLevels;
    ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    if (VkResult r = make(e.owner, e.d.vkCreateImage, e.d.vkDestroyImage, ci, img.image); r != VK_SUCCESS)
      return vkError(("vkCreateImage('" + std::string(info.name) + "')").c_str(), r);
    made.push_back(std::move(img));
  }
  e.res.images.reserve(e.res.images.size() + made.size());
  for (OwnedImage& img : made) e.res.images.push_back(std::move(img));  // cannot throw: reserved
  return Status::success();
}

Status bindImages(EffectState& e) {
  std::vector<Allocator::Request> requests;
  for (const OwnedImage& img : e.res.images)
    if (!img.bound) requests.push_back({img.image.get(), VK_NULL_HANDLE});
  if (requests.empty()) return Status::success();
  std::vector<Allocator::Block> blocks;
  if (Status st = e.allocator.allocateAndBind(requests, blocks); !st) return st;
  // Each new image keeps every block of its plan (a block serves the images of its memory type):
  // a block goes with the last image that shares it.
  std::vector<std::shared_ptr<Allocator::Block>> shared;
  for (Allocator::Block& b : blocks) shared.push_back(std::make_shared<Allocator::Block>(std::move(b)));
  for (OwnedImage& img : e.res.images) {
    if (img.bound) continue;
    const std::uint32_t levels = img.planned.mipLevels;
    if (Status st = createView(e, img.image.get(), img.format, 0, levels, img.fullView); !st) return st;
    img.levelViews.resize(levels);
    for (std::uint32_t m = 0; m < levels; ++m)
      if (Status st = createView(e, img.image.get(), img.format, m, 1, img.levelViews[m]); !st) return st;
  }
  // Only now that nothing can fail: the memory goes with the images.
  for (OwnedImage& img : e.res.images) {
    if (img.bound) continue;
    img.memoryBlocks = shared;
    img.bound = true;
  }
  return Status::success();
}

Status createParamBuffer(EffectState& e, std::uint32_t slots, ParamBuffer& out) {
  ParamBuffer ubo;
  const VkDeviceSize align = std::max<VkDeviceSize>(1, e.props.limits.minUniformBufferOffsetAlignment);
  ubo.stride = (sizeof(ParamBlock) + align - 1) / align * align;
  ubo.written.assign(slots, ParamBlock{});
  ubo.valid.assign(slots, false);
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = ubo.stride * slots;
  bi.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  if (VkResult r = make(e.owner, e.d.vkCreateBuffer, e.d.vkDestroyBuffer, bi, ubo.buffer); r != VK_SUCCESS)
    return vkError("vkCreateBuffer(parameter block)", r);
  void* mapped = nullptr;
  const Allocator::Request request{VK_NULL_HANDLE, ubo.buffer.get(), &mapped};
  if (Status st = e.allocator.allocateAndBind({&request, 1}, ubo.memory); !st) return st;
  ubo.mapped = static_cast<char*>(mapped);
  std::swap(out, ubo);  // the old buffer goes before its memory
  return Status::success();
}

}  // namespace sao::vk
