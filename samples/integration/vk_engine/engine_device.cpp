#include "engine_device.h"

namespace sao::vkengine {

Status vkFail(const std::string& what, VkResult r) {
  return Status::error(StatusCode::DriverError, what + " failed: VkResult " + std::to_string(int(r)));
}

Status Device::create(const DeviceHandles& handles, std::unique_ptr<Device>& out) {
  if (!handles.physical || !handles.device || !handles.queue)
    return Status::error(StatusCode::InvalidInput, "the engine needs a physical device, a device and a queue");
  std::unique_ptr<Device> d(new Device(handles));
  vkGetPhysicalDeviceProperties(handles.physical, &d->props_);
  vkGetPhysicalDeviceMemoryProperties(handles.physical, &d->memory_);
  // RESET_COMMAND_BUFFER: begin() resets the one command buffer for every submit.
  const VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                         VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, handles.queueFamily};
  SAO_ENGINE_VK_TRY(vkCreateCommandPool(handles.device, &poolInfo, nullptr, &d->pool_));
  const VkCommandBufferAllocateInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, d->pool_,
                                            VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  SAO_ENGINE_VK_TRY(vkAllocateCommandBuffers(handles.device, &cmdInfo, &d->cmd_));
  const VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  SAO_ENGINE_VK_TRY(vkCreateFence(handles.device, &fenceInfo, nullptr, &d->fence_));
  out = std::move(d);
  return Status::success();
}

Device::~Device() {
  // Every submit waited for its fence: nothing of ours is still running.
  vkDestroyFence(h_.device, fence_, nullptr);
  vkDestroyCommandPool(h_.device, pool_, nullptr);  // frees the command buffer
}

Status Device::allocate(VkMemoryRequirements needs, VkMemoryPropertyFlags want, VkDeviceMemory& out) const {
  std::uint32_t type = 0;
  while (type < memory_.memoryTypeCount &&
         !((needs.memoryTypeBits >> type & 1) && (memory_.memoryTypes[type].propertyFlags & want) == want))
    ++type;
  if (type == memory_.memoryTypeCount)
    return Status::error(StatusCode::DriverError, "no memory type with flags " + std::to_string(want));
  const VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, needs.size, type};
  SAO_ENGINE_VK_TRY(vkAllocateMemory(h_.device, &info, nullptr, &out));
  return Status::success();
}

bool Device::hasFeatures(VkFormat format, VkFormatFeatureFlags need) const {
  VkFormatProperties p{};
  vkGetPhysicalDeviceFormatProperties(h_.physical, format, &p);
  return (p.optimalTilingFeatures & need) == need;
}

VkCommandBuffer Device::begin() const {
  const VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                      VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  vkBeginCommandBuffer(cmd_, &info);  // a failure here fails vkEndCommandBuffer in submitAndWait()
  return cmd_;
}

Status Device::submitAndWait() const {
  SAO_ENGINE_VK_TRY(vkEndCommandBuffer(cmd_));
  const VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO, nullptr, 0, nullptr, nullptr, 1, &cmd_};
  SAO_ENGINE_VK_TRY(vkQueueSubmit(h_.queue, 1, &submit, fence_));
  SAO_ENGINE_VK_TRY(vkWaitForFences(h_.device, 1, &fence_, VK_TRUE, UINT64_MAX));
  SAO_ENGINE_VK_TRY(vkResetFences(h_.device, 1, &fence_));
  return Status::success();
}

Status Device::submitOnce(const std::function<void(VkCommandBuffer)>& record) const {
  record(begin());
  return submitAndWait();
}

}  // namespace sao::vkengine
