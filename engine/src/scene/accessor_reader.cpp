#include "scene/accessor_reader.h"

#include <cstring>

#include <tiny_gltf.h>

#include "raybudget/error.h"

namespace raybudget::gltf {
namespace {

size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

// A checked view of an accessor's bytes: element i starts at data + i * stride.
struct View {
  const uint8_t* data = nullptr;  // null: no bufferView, every element is zero
  size_t offset = 0;              // data's byte in its buffer
  size_t count = 0;
  size_t stride = 0;
  int componentType = 0;
  int components = 0;
  bool normalized = false;
};

View checkedView(const tinygltf::Model& model, int index, const std::string& where) {
  if (index < 0 || size_t(index) >= model.accessors.size())
    throw Error(where + ": accessor " + std::to_string(index) + " does not exist (the file has " +
                std::to_string(model.accessors.size()) + ")");
  const tinygltf::Accessor& acc = model.accessors[size_t(index)];
  const std::string name = where + ": accessor " + std::to_string(index);
  if (acc.sparse.isSparse) throw Error(name + " is sparse, which raybudget does not support");
  View v;
  v.count = acc.count;
  v.componentType = acc.componentType;
  v.components = componentCount(acc.type);
  v.normalized = acc.normalized;
  const size_t csize = componentSize(acc.componentType);
  if (csize == 0 || v.components == 0)
    throw Error(name + " has an invalid component type " + std::to_string(acc.componentType) + " or type " +
                std::to_string(acc.type));
  const size_t elementSize = csize * size_t(v.components);
  if (acc.count == 0) throw Error(name + " has count 0; glTF requires at least one element");
  if (acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    throw Error(name + " is normalized, which glTF allows only for (unsigned) byte and short components (ACCESSOR_NORMALIZED_INVALID)");
  if (acc.byteOffset % csize != 0)
    throw Error(name + ": byteOffset " + std::to_string(acc.byteOffset) + " is not a multiple of its component size " +
                std::to_string(csize) + " (ACCESSOR_OFFSET_ALIGNMENT)");
  if (acc.bufferView < 0) return v;  // glTF: all zeros
  if (size_t(acc.bufferView) >= model.bufferViews.size())
    throw Error(name + " refers to bufferView " + std::to_string(acc.bufferView) + ", which does not exist");
  const tinygltf::BufferView& bv = model.bufferViews[size_t(acc.bufferView)];
  if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size())
    throw Error(name + ": bufferView " + std::to_string(acc.bufferView) + " refers to missing buffer " +
                std::to_string(bv.buffer));
  const tinygltf::Buffer& buf = model.buffers[size_t(bv.buffer)];
  if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
    throw Error(name + ": bufferView " + std::to_string(acc.bufferView) + " (offset " +
                std::to_string(bv.byteOffset) + ", length " + std::to_string(bv.byteLength) +
                ") runs past the end of buffer " + std::to_string(bv.buffer) + " (" +
                std::to_string(buf.data.size()) + " bytes): the buffer is short or missing");
  if ((bv.byteOffset + acc.byteOffset) % csize != 0)
    throw Error(name + " starts at byte " + std::to_string(bv.byteOffset + acc.byteOffset) +
                " of its buffer, not a multiple of its component size " + std::to_string(csize) + " (ACCESSOR_TOTAL_OFFSET_ALIGNMENT)");
  if (bv.byteStride != 0 && (bv.byteStride < 4 || bv.byteStride > 252 || bv.byteStride % 4 != 0))
    throw Error(name + ": bufferView " + std::to_string(acc.bufferView) + " has byteStride " + std::to_string(bv.byteStride) +
                "; glTF allows 4 to 252 in steps of 4");
  v.stride = bv.byteStride != 0 ? bv.byteStride : elementSize;
  if (v.stride < elementSize)
    throw Error(name + ": byteStride " + std::to_string(v.stride) + " is smaller than an element");
  if (v.count > 0) {
    const size_t last = acc.byteOffset + (v.count - 1) * v.stride + elementSize;
    if (acc.byteOffset > bv.byteLength || (v.count - 1) > (bv.byteLength / v.stride) || last > bv.byteLength)
      throw Error(name + " (" + std::to_string(v.count) + " elements from offset " +
                  std::to_string(acc.byteOffset) + ") runs past the end of its bufferView (" +
                  std::to_string(bv.byteLength) + " bytes)");
  }
  v.offset = bv.byteOffset + acc.byteOffset;
  v.data = buf.data.data() + v.offset;
  return v;
}

float componentAsFloat(const uint8_t* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(*p) / 255.0f : float(*p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float f = float(int8_t(*p));
      return normalized ? glm::max(f / 127.0f, -1.0f) : f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t s;
      std::memcpy(&s, p, 2);
      return normalized ? float(s) / 65535.0f : float(s);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t s;
      std::memcpy(&s, p, 2);
      return normalized ? glm::max(float(s) / 32767.0f, -1.0f) : float(s);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t u;
      std::memcpy(&u, p, 4);
      return float(u);
    }
  }
  return 0.0f;
}

}  // namespace

AccessorLayout accessorLayout(const tinygltf::Model& model, int accessor, const std::string& where) {
  const View v = checkedView(model, accessor, where);
  return {v.count, v.data ? v.offset : 0, v.data ? v.stride : 0};
}

std::vector<glm::vec4> readVec4(const tinygltf::Model& model, int accessor, const std::string& where,
                                glm::vec4 fill) {
  const View v = checkedView(model, accessor, where);
  if (v.components > 4) throw Error(where + ": accessor " + std::to_string(accessor) + " is a matrix, not a vector");
  std::vector<glm::vec4> out(v.count, fill);
  if (!v.data) {
    for (glm::vec4& e : out)
      for (int c = 0; c < v.components; ++c) e[c] = 0.0f;
    return out;
  }
  const size_t csize = componentSize(v.componentType);
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* element = v.data + i * v.stride;
    for (int c = 0; c < v.components; ++c) out[i][c] = componentAsFloat(element + size_t(c) * csize, v.componentType, v.normalized);
  }
  return out;
}

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor, const std::string& where) {
  const View v = checkedView(model, accessor, where);
  if (v.components != 1 || v.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
      v.componentType == TINYGLTF_COMPONENT_TYPE_BYTE || v.componentType == TINYGLTF_COMPONENT_TYPE_SHORT)
    throw Error(where + ": index accessor " + std::to_string(accessor) + " is not an unsigned scalar");
  std::vector<uint32_t> out(v.count, 0u);
  if (!v.data) return out;
  for (size_t i = 0; i < v.count; ++i) {
    const uint8_t* p = v.data + i * v.stride;
    switch (v.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = *p; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t s;
        std::memcpy(&s, p, 2);
        out[i] = s;
        break;
      }
      default: std::memcpy(&out[i], p, 4); break;
    }
  }
  return out;
}

}  // namespace raybudget::gltf
