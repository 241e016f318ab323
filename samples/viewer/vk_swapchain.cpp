#include "vk_swapchain.h"

#include <algorithm>

namespace sao::viewer {
namespace {

VkSurfaceFormatKHR pickFormat(const std::vector<VkSurfaceFormatKHR>& formats) {
  // UNORM: the composite writes display values itself and ImGui's colours are display values.
  for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const auto& f : formats)
      if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  return formats.front();
}

VkPresentModeKHR pickPresentMode(const std::vector<VkPresentModeKHR>& modes, bool vsync) {
  if (!vsync)
    for (VkPresentModeKHR want : {VK_PRESENT_MODE_IMMEDIATE_KHR, VK_PRESENT_MODE_MAILBOX_KHR})
      if (std::find(modes.begin(), modes.end(), want) != modes.end()) return want;
  return VK_PRESENT_MODE_FIFO_KHR;  // always there
}

}  // namespace

Status VkSwapchain::createRenderPass() {
  VkAttachmentDescription color{};
  color.format = format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  // The acquire semaphore is waited at COLOR_ATTACHMENT_OUTPUT: the layout transition waits too.
  VkSubpassDependency dep{};
  dep.srcSubpass = VK_SUBPASS_EXTERNAL;
  dep.dstSubpass = 0;
  dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  ci.attachmentCount = 1;
  ci.pAttachments = &color;
  ci.subpassCount = 1;
  ci.pSubpasses = &subpass;
  ci.dependencyCount = 1;
  ci.pDependencies = &dep;
  SAO_VIEWER_VK(vkCreateRenderPass(context_->device(), &ci, nullptr, &renderPass));
  return Status::success();
}

Status VkSwapchain::create(vk::headless::Context& context, std::uint32_t width, std::uint32_t height, bool vsync) {
  context_ = &context;
  VkPhysicalDevice pd = context.physicalDevice();
  VkSurfaceCapabilitiesKHR caps;
  SAO_VIEWER_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, context.surface(), &caps));
  std::uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, context.surface(), &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, context.surface(), &n, formats.data());
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, context.surface(), &n, nullptr);
  std::vector<VkPresentModeKHR> modes(n);
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, context.surface(), &n, modes.data());
  if (formats.empty()) return Status::error(StatusCode::DriverError, "the window surface offers no format");
  const VkSurfaceFormatKHR surfaceFormat = pickFormat(formats);
  if (renderPass && surfaceFormat.format != format)
    return Status::error(StatusCode::DriverError, "the window's surface format changed");
  format = surfaceFormat.format;
  bgra = format == VK_FORMAT_B8G8R8A8_UNORM || format == VK_FORMAT_B8G8R8A8_SRGB;
  if (!renderPass)
    if (Status s = createRenderPass(); !s) return s;

  extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {
    extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  minImageCount = std::max(caps.minImageCount + 1, 2u);
  if (caps.maxImageCount > 0) minImageCount = std::min(minImageCount, caps.maxImageCount);
  transferSrc = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = context.surface();
  ci.minImageCount = minImageCount;
  ci.imageFormat = format;
  ci.imageColorSpace = surfaceFormat.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (transferSrc ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                          ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                          : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  ci.presentMode = pickPresentMode(modes, vsync);
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = handle;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  SAO_VIEWER_VK(vkCreateSwapchainKHR(context.device(), &ci, nullptr, &created));
  destroyImages();
  if (handle) vkDestroySwapchainKHR(context.device(), handle, nullptr);
  handle = created;

  vkGetSwapchainImagesKHR(context.device(), handle, &n, nullptr);
  images.resize(n);
  vkGetSwapchainImagesKHR(context.device(), handle, &n, images.data());
  for (VkImage image : images) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    views_.push_back(VK_NULL_HANDLE);
    SAO_VIEWER_VK(vkCreateImageView(context.device(), &vi, nullptr, &views_.back()));
    VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fi.renderPass = renderPass;
    fi.attachmentCount = 1;
    fi.pAttachments = &views_.back();
    fi.width = extent.width;
    fi.height = extent.height;
    fi.layers = 1;
    framebuffers.push_back(VK_NULL_HANDLE);
    SAO_VIEWER_VK(vkCreateFramebuffer(context.device(), &fi, nullptr, &framebuffers.back()));
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    renderFinished.push_back(VK_NULL_HANDLE);
    SAO_VIEWER_VK(vkCreateSemaphore(context.device(), &si, nullptr, &renderFinished.back()));
  }
  return Status::success();
}

void VkSwapchain::destroyImages() {
  if (!context_) return;
  for (VkFramebuffer f : framebuffers) vkDestroyFramebuffer(context_->device(), f, nullptr);
  for (VkImageView v : views_) vkDestroyImageView(context_->device(), v, nullptr);
  for (VkSemaphore s : renderFinished) vkDestroySemaphore(context_->device(), s, nullptr);
  framebuffers.clear();
  views_.clear();
  renderFinished.clear();
  images.clear();
}

void VkSwapchain::destroy() {
  if (!context_) return;
  destroyImages();
  if (handle) vkDestroySwapchainKHR(context_->device(), handle, nullptr);
  if (renderPass) vkDestroyRenderPass(context_->device(), renderPass, nullptr);
  handle = VK_NULL_HANDLE;
  renderPass = VK_NULL_HANDLE;
}

}  // namespace sao::viewer
