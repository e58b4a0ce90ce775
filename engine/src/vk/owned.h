// A move-only owner for one Vulkan handle: destroys it exactly once, on every path,
// including when a later step of a constructor throws.
#pragma once
#include <functional>
#include <utility>

namespace raybudget::vk {

template <typename T>
class Owned {
 public:
  Owned() = default;
  Owned(T handle, std::function<void(T)> destroy) : handle_(handle), destroy_(std::move(destroy)) {}
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
  ~Owned() { reset(); }

  void reset() {
    if (handle_ != T{} && destroy_) destroy_(handle_);
    handle_ = T{};
  }
  T get() const { return handle_; }
  operator T() const { return handle_; }  // NOLINT: handles are passed to vk* calls everywhere
  explicit operator bool() const { return handle_ != T{}; }

 private:
  T handle_{};
  std::function<void(T)> destroy_;
};

}  // namespace raybudget::vk
