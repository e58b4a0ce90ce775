// A Vulkan (or GLFW) handle and the call that destroys it: move-only, destroyed once.
#pragma once
#include <functional>
#include <string>
#include <utility>

#include <vulkan/vulkan.h>

#include "raybudget/error.h"

namespace raybudget::editor {

template <typename T>
class Owned {
 public:
  Owned() = default;
  Owned(T handle, std::function<void(T)> destroy) : handle_(handle), destroy_(std::move(destroy)) {}
  ~Owned() { reset(); }
  Owned(Owned&& o) noexcept : handle_(std::exchange(o.handle_, T{})), destroy_(std::move(o.destroy_)) {}
  Owned& operator=(Owned&& o) noexcept {
    if (this != &o) {
      reset();
      handle_ = std::exchange(o.handle_, T{});
      destroy_ = std::move(o.destroy_);
    }
    return *this;
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;

  T get() const { return handle_; }
  operator T() const { return handle_; }
  const T* ptr() const { return &handle_; }
  void reset() {
    if (handle_ && destroy_) destroy_(handle_);
    handle_ = T{};
  }

 private:
  T handle_{};
  std::function<void(T)> destroy_;
};

// Throws raybudget::Error naming the call when a Vulkan call fails.
inline void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw Error(std::string("editor: ") + call + " failed with VkResult " + std::to_string(int(result)));
}

// Creates a device-level object with vkCreateX(device, &info, nullptr, &handle), owned.
template <typename T, typename Info>
Owned<T> make(VkDevice device, VkResult (*create)(VkDevice, const Info*, const VkAllocationCallbacks*, T*),
              void (*destroy)(VkDevice, T, const VkAllocationCallbacks*), const Info& info, const char* what) {
  T handle{};
  check(create(device, &info, nullptr, &handle), what);
  return Owned<T>(handle, [device, destroy](T h) { destroy(device, h, nullptr); });
}

}  // namespace raybudget::editor
