// VK_CHECK: every Vulkan call that returns a VkResult goes through it; a failure becomes a
// raybudget::Error naming the call, the result and the source location.
#pragma once
#include <string>

#include <vulkan/vulkan.h>

#include "raybudget/error.h"

namespace raybudget::vk {

const char* resultName(VkResult result);

[[noreturn]] void throwVkError(const char* call, VkResult result, const char* file, int line);

}  // namespace raybudget::vk

#define VK_CHECK(call)                                                                        \
  do {                                                                                        \
    const VkResult vkCheckResult_ = (call);                                                   \
    if (vkCheckResult_ != VK_SUCCESS) ::raybudget::vk::throwVkError(#call, vkCheckResult_, __FILE__, __LINE__); \
  } while (0)
