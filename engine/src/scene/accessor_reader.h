// Bounds-checked reading of glTF accessors. Every byte range is checked against its buffer
// before it is touched, so a short or lying file becomes an Error, never a read overrun.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tinygltf {
class Model;
}

namespace raybudget::gltf {

// Reads a float accessor of up to 4 components (normalized integers are converted as
// glTF specifies); missing components are filled from `fill`. `where` names the accessor
// in error messages.
std::vector<glm::vec4> readVec4(const tinygltf::Model& model, int accessor, const std::string& where,
                                glm::vec4 fill = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));

// Reads an index accessor (unsigned byte, short or int).
std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor, const std::string& where);

// Where an accessor's elements lie, after its index, range and alignment checks: their
// count, the first one's byte in its buffer and the bytes from one to the next (an accessor
// without a bufferView, all zeros, has offset and stride 0).
struct AccessorLayout {
  size_t count = 0;
  size_t byteOffset = 0;
  size_t stride = 0;
};
AccessorLayout accessorLayout(const tinygltf::Model& model, int accessor, const std::string& where);

}  // namespace raybudget::gltf
