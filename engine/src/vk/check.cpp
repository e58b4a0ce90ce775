#include "vk/check.h"

namespace raybudget::vk {

const char* resultName(VkResult result) {
  switch (result) {
#define RB_CASE(x) \
  case x: return #x;
    RB_CASE(VK_SUCCESS)
    RB_CASE(VK_NOT_READY)
    RB_CASE(VK_TIMEOUT)
    RB_CASE(VK_INCOMPLETE)
    RB_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    RB_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    RB_CASE(VK_ERROR_INITIALIZATION_FAILED)
    RB_CASE(VK_ERROR_DEVICE_LOST)
    RB_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    RB_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    RB_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    RB_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    RB_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    RB_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    RB_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    RB_CASE(VK_ERROR_FRAGMENTED_POOL)
    RB_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    RB_CASE(VK_ERROR_UNKNOWN)
#undef RB_CASE
    default: return "VK_ERROR_(unlisted)";
  }
}

void throwVkError(const char* call, VkResult result, const char* file, int line) {
  throw Error(std::string(call) + " failed with " + resultName(result) + " (" + std::to_string(int(result)) + ") at " + file + ":" +
              std::to_string(line));
}

}  // namespace raybudget::vk
