// The descriptor bindings a shader reads or writes: those of its set-0 resource variables
// that an instruction of its functions refers to. glslang lists every declared global in
// the entry point's interface, used or not, so the interface alone would say "all of them".
#pragma once
#include <cstdint>
#include <vector>

#include "vk/pipelines.h"

namespace raybudget::vk {

// Sorted binding numbers. A literal operand that happens to equal a variable's ID can add a
// binding the shader does not use (harmless: the layout then holds one more); none used is
// ever left out. Throws Error on malformed SPIR-V.
std::vector<uint32_t> usedBindings(Spirv code);

}  // namespace raybudget::vk
