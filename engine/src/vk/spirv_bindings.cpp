#include "vk/spirv_bindings.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "raybudget/error.h"

namespace raybudget::vk {
namespace {

constexpr uint32_t kMagic = 0x07230203;
constexpr uint32_t kOpFunction = 54, kOpFunctionEnd = 56, kOpVariable = 59, kOpDecorate = 71;
constexpr uint32_t kDecorationBinding = 33, kDecorationDescriptorSet = 34;

}  // namespace

std::vector<uint32_t> usedBindings(Spirv code) {
  if (code.size() < 5 || code[0] != kMagic) throw Error("not SPIR-V (bad header)");
  std::unordered_map<uint32_t, uint32_t> binding, set;  // variable ID -> decoration
  std::unordered_set<uint32_t> variables, used;
  // First pass: decorations and variables; second: references inside functions.
  for (int pass = 0; pass < 2; ++pass) {
    bool inFunction = false;
    for (size_t i = 5; i < code.size();) {
      const uint32_t words = code[i] >> 16, op = code[i] & 0xFFFFu;
      if (words == 0 || i + words > code.size()) throw Error("malformed SPIR-V: an instruction runs past the end");
      if (pass == 0) {
        if (op == kOpDecorate && words >= 4 && code[i + 2] == kDecorationBinding) binding[code[i + 1]] = code[i + 3];
        if (op == kOpDecorate && words >= 4 && code[i + 2] == kDecorationDescriptorSet) set[code[i + 1]] = code[i + 3];
        if (op == kOpVariable && words >= 4) variables.insert(code[i + 2]);
      } else {
        if (op == kOpFunction) inFunction = true;
        if (inFunction)
          for (uint32_t w = 1; w < words; ++w)
            if (binding.count(code[i + w])) used.insert(code[i + w]);
        if (op == kOpFunctionEnd) inFunction = false;
      }
      i += words;
    }
  }
  std::vector<uint32_t> out;
  for (uint32_t id : used)
    if (variables.count(id) && set[id] == 0) out.push_back(binding[id]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace raybudget::vk
