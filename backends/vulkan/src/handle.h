// Handle<T>: one Vulkan object owned by value. It holds the device, the destroy function (from the
// effect's dispatch table) and the allocation callbacks, and destroys the object when it goes out of
// scope or is replaced, so an early return or an exception leaves nothing behind and a failed
// plan only has to drop what it built.
#pragma once
#include <vulkan/vulkan_core.h>

#include <utility>

namespace sao::vk {

// Where an object lives: what every create and destroy call needs besides the object.
struct Owner {
  VkDevice device = VK_NULL_HANDLE;
  const VkAllocationCallbacks* callbacks = nullptr;
};

template <typename T>
class Handle {
 public:
  using Destroy = void(VKAPI_PTR*)(VkDevice, T, const VkAllocationCallbacks*);

  Handle() = default;
  // Takes `object` (VK_NULL_HANDLE: holds nothing); `destroy` is vkDestroy* or vkFreeMemory.
  Handle(const Owner& owner, Destroy destroy, T object) noexcept : owner_(owner), destroy_(destroy), object_(object) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept
      : owner_(other.owner_), destroy_(other.destroy_), object_(std::exchange(other.object_, T{})) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      owner_ = other.owner_;
      destroy_ = other.destroy_;
      object_ = std::exchange(other.object_, T{});
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  T get() const noexcept { return object_; }
  explicit operator bool() const noexcept { return object_ != T{}; }
  void reset() noexcept {
    if (object_ != T{}) destroy_(owner_.device, object_, owner_.callbacks);
    object_ = T{};
  }

 private:
  Owner owner_;
  Destroy destroy_ = nullptr;
  T object_{};
};

// Calls `create(device, &info, callbacks, &object)` and hands the object to `out` (replacing what
// it held). On failure `out` is left as it was and the VkResult is returned.
template <typename T, typename Info>
VkResult make(const Owner& owner, VkResult(VKAPI_PTR* create)(VkDevice, const Info*, const VkAllocationCallbacks*, T*),
              typename Handle<T>::Destroy destroy, const Info& info, Handle<T>& out) {
  T object{};
  const VkResult r = create(owner.device, &info, owner.callbacks, &object);
  if (r == VK_SUCCESS) out = Handle<T>(owner, destroy, object);
  return r;
}

}  // namespace sao::vk
