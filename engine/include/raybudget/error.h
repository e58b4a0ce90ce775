// The one exception type raybudget throws across its API: bad input, a failed Vulkan
// call or a missing capability. Its message names the file or call and what is wrong.
#pragma once
#include <stdexcept>
#include <string>

namespace raybudget {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace raybudget
