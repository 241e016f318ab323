#include "allocator.h"

#include <algorithm>
#include <atomic>
#include <string>

namespace sao::vk {
namespace {

std::atomic<std::uint64_t> gLiveAllocations{0}, gLiveBytes{0}, gTotalAllocations{0};

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return a <= 1 ? v : (v + a - 1) / a * a; }

}  // namespace

MemoryStats processMemoryStats() {
  return {gLiveAllocations.load(), gLiveBytes.load(), gTotalAllocations.load()};
}

void Allocator::init(const Dispatch* dispatch, VkDevice device, const VkPhysicalDeviceMemoryProperties& memory,
                     VkDeviceSize bufferImageGranularity, const VkAllocationCallbacks* callbacks) {
  d_ = dispatch;
  owner_ = {device, callbacks};
  memory_ = memory;
  granularity_ = std::max<VkDeviceSize>(1, bufferImageGranularity);
}

void Allocator::count(VkDeviceSize size) noexcept {
  ++stats_.liveAllocations;
  ++stats_.totalAllocations;
  stats_.liveBytes += size;
  ++gLiveAllocations;
  ++gTotalAllocations;
  gLiveBytes += size;
}

void Allocator::uncount(VkDeviceSize size) noexcept {
  --stats_.liveAllocations;
  stats_.liveBytes -= size;
  --gLiveAllocations;
  gLiveBytes -= size;
}

Allocator::Block& Allocator::Block::operator=(Block&& other) noexcept {
  if (this != &other) {
    release();
    owner_ = other.owner_;
    memory_ = std::move(other.memory_);
    size_ = other.size_;
  }
  return *this;
}

void Allocator::Block::release() noexcept {
  if (!memory_) return;
  memory_.reset();
  owner_->uncount(size_);
}

int Allocator::chooseType(std::uint32_t typeBits, VkMemoryPropertyFlags required) const {
  constexpr VkMemoryPropertyFlags avoid = VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT | VK_MEMORY_PROPERTY_PROTECTED_BIT;
  for (const VkMemoryPropertyFlags want : {required | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, required})
    for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
      const VkMemoryPropertyFlags f = memory_.memoryTypes[i].propertyFlags;
      if ((typeBits & (1u << i)) && (f & want) == want && !(f & avoid)) return static_cast<int>(i);
    }
  return -1;
}

Status Allocator::allocateAndBind(std::span<const Request> requests, std::vector<Block>& out) {
  struct Placed {
    const Request* request;
    VkMemoryRequirements req;
    int type;
    VkDeviceSize offset;
  };
  std::vector<Placed> placed;
  placed.reserve(requests.size());
  for (const auto& r : requests) {
    Placed p{&r, {}, -1, 0};
    if (r.image) d_->vkGetImageMemoryRequirements(owner_.device, r.image, &p.req);
    else d_->vkGetBufferMemoryRequirements(owner_.device, r.buffer, &p.req);
    constexpr VkMemoryPropertyFlags hostCoherent =
        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    p.type = chooseType(p.req.memoryTypeBits, r.mapped ? hostCoherent : 0);
    if (p.type < 0)
      return Status::error(StatusCode::DriverError, std::string("no usable ") + (r.mapped ? "host-visible coherent " : "") +
                                                        "memory type for memoryTypeBits " +
                                                        std::to_string(p.req.memoryTypeBits));
    placed.push_back(p);
  }
  // Buffers before images in each block; every offset aligned to the resource's alignment and the
  // buffer-image granularity, so linear and optimal resources never share a granularity page.
  std::stable_sort(placed.begin(), placed.end(), [](const Placed& a, const Placed& b) {
    return (a.request->buffer != VK_NULL_HANDLE) > (b.request->buffer != VK_NULL_HANDLE);
  });
  std::vector<Block> blocks;  // freed on any early return
  blocks.reserve(memory_.memoryTypeCount);
  for (std::uint32_t type = 0; type < memory_.memoryTypeCount; ++type) {
    VkDeviceSize size = 0;
    for (auto& p : placed) {
      if (p.type != static_cast<int>(type)) continue;
      p.offset = alignUp(size, std::max(p.req.alignment, granularity_));
      size = p.offset + p.req.size;
    }
    if (size == 0) continue;
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, size, type};
    Block block;
    if (VkResult r = make(owner_, d_->vkAllocateMemory, d_->vkFreeMemory, info, block.memory_); r != VK_SUCCESS)
      return vkError(("vkAllocateMemory(" + std::to_string(size) + " bytes)").c_str(), r);
    block.owner_ = this;
    block.size_ = size;
    count(size);
    const VkDeviceMemory memory = block.memory_.get();
    blocks.push_back(std::move(block));  // reserved: cannot throw
    void* base = nullptr;
    for (auto& p : placed)
      if (p.type == static_cast<int>(type) && p.request->mapped && !base)
        if (VkResult r = d_->vkMapMemory(owner_.device, memory, 0, VK_WHOLE_SIZE, 0, &base); r != VK_SUCCESS)
          return vkError("vkMapMemory", r);
    for (auto& p : placed) {
      if (p.type != static_cast<int>(type)) continue;
      if (p.request->mapped) *p.request->mapped = static_cast<char*>(base) + p.offset;
      const VkResult r = p.request->image ? d_->vkBindImageMemory(owner_.device, p.request->image, memory, p.offset)
                                          : d_->vkBindBufferMemory(owner_.device, p.request->buffer, memory, p.offset);
      if (r != VK_SUCCESS) return vkError(p.request->image ? "vkBindImageMemory" : "vkBindBufferMemory", r);
    }
  }
  out = std::move(blocks);
  return Status::success();
}

}  // namespace sao::vk
