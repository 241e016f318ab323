// A small device-memory allocator: every image and buffer of one configuration in one
// VkDeviceMemory per memory type, bound at aligned offsets. Each VkDeviceMemory is a Block that
// frees itself. Counts what it holds, per allocator and for the whole process (the tests check that
// nothing grows).
#pragma once
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <span>
#include <vector>

#include "dispatch.h"
#include "handle.h"
#include "sao/vulkan/effect.h"

namespace sao::vk {

class Allocator {
 public:
  struct Request {
    VkImage image = VK_NULL_HANDLE;    // one of the two
    VkBuffer buffer = VK_NULL_HANDLE;
    // Host-visible and coherent, persistently mapped; *mapped receives the resource's address.
    void** mapped = nullptr;
  };
  // One VkDeviceMemory, freed (implicitly unmapped) and uncounted when the block goes. The
  // allocator must outlive its blocks.
  class Block {
   public:
    Block() = default;
    Block(Block&& other) noexcept = default;
    Block& operator=(Block&& other) noexcept;
    ~Block() { release(); }

   private:
    friend class Allocator;
    void release() noexcept;
    Allocator* owner_ = nullptr;
    Handle<VkDeviceMemory> memory_;
    VkDeviceSize size_ = 0;
  };

  void init(const Dispatch* dispatch, VkDevice device, const VkPhysicalDeviceMemoryProperties& memory,
            VkDeviceSize bufferImageGranularity, const VkAllocationCallbacks* callbacks);

  // Allocates and binds every request (device-local memory where the type bits allow it; mapped
  // requests in host-visible coherent memory, device-local too where there is such a type). On
  // error nothing stays allocated and `out` is unchanged.
  Status allocateAndBind(std::span<const Request> requests, std::vector<Block>& out);

  MemoryStats stats() const { return stats_; }

 private:
  int chooseType(std::uint32_t typeBits, VkMemoryPropertyFlags required) const;

  void count(VkDeviceSize size) noexcept;
  void uncount(VkDeviceSize size) noexcept;

  const Dispatch* d_ = nullptr;
  Owner owner_;
  VkPhysicalDeviceMemoryProperties memory_{};
  VkDeviceSize granularity_ = 1;
  MemoryStats stats_;
};

}  // namespace sao::vk
