// A small device-memory allocator: every image and buffer of one configuration in one
// VkDeviceMemory per memory type, bound at aligned offsets, freed together. Counts what it holds,
// per allocator and for the whole process (the tests check that nothing grows).
#pragma once
#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <span>
#include <vector>

#include "dispatch.h"
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
  struct Block {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    std::uint32_t memoryType = 0;
    bool mapped = false;
  };

  void init(const Dispatch* dispatch, VkDevice device, const VkPhysicalDeviceMemoryProperties& memory,
            VkDeviceSize bufferImageGranularity, const VkAllocationCallbacks* callbacks);

  // Allocates and binds every request (device-local memory where the type bits allow it; mapped
  // requests in host-visible coherent memory, device-local too where there is such a type). On
  // error nothing stays allocated and `out` is empty.
  Status allocateAndBind(std::span<const Request> requests, std::vector<Block>& out);
  void free(std::vector<Block>& blocks);

  MemoryStats stats() const { return stats_; }

 private:
  int chooseType(std::uint32_t typeBits, VkMemoryPropertyFlags required) const;

  const Dispatch* d_ = nullptr;
  VkDevice device_ = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory_{};
  VkDeviceSize granularity_ = 1;
  const VkAllocationCallbacks* callbacks_ = nullptr;
  MemoryStats stats_;
};

}  // namespace sao::vk
