#include "scene/gltf_rules.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <set>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "raybudget/error.h"
#include "scene/accessor_reader.h"

namespace raybudget::gltf {
namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;

std::string componentName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case kUByte: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case kUShort: return "UNSIGNED_SHORT";
    case kUInt: return "UNSIGNED_INT";
    case kFloat: return "FLOAT";
    default: return std::to_string(componentType);
  }
}

std::string typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return std::to_string(type);
  }
}

// One format a semantic allows: a type and a component type, normalized or not.
struct Format {
  int type;
  int componentType;
  bool normalized;
};

std::string formatName(int type, int componentType, bool normalized) {
  return typeName(type) + " " + componentName(componentType) + (normalized ? " normalized" : "");
}

// The formats glTF 2.0 allows each vertex attribute semantic (without its _n suffix);
// empty for an unknown one.
std::vector<Format> allowedFormats(const std::string& semantic) {
  using F = Format;
  if (semantic == "POSITION" || semantic == "NORMAL") return {F{TINYGLTF_TYPE_VEC3, kFloat, false}};
  if (semantic == "TANGENT") return {F{TINYGLTF_TYPE_VEC4, kFloat, false}};
  if (semantic == "TEXCOORD")
    return {F{TINYGLTF_TYPE_VEC2, kFloat, false}, F{TINYGLTF_TYPE_VEC2, kUByte, true}, F{TINYGLTF_TYPE_VEC2, kUShort, true}};
  if (semantic == "COLOR")
    return {F{TINYGLTF_TYPE_VEC3, kFloat, false}, F{TINYGLTF_TYPE_VEC3, kUByte, true}, F{TINYGLTF_TYPE_VEC3, kUShort, true},
            F{TINYGLTF_TYPE_VEC4, kFloat, false}, F{TINYGLTF_TYPE_VEC4, kUByte, true}, F{TINYGLTF_TYPE_VEC4, kUShort, true}};
  if (semantic == "JOINTS") return {F{TINYGLTF_TYPE_VEC4, kUByte, false}, F{TINYGLTF_TYPE_VEC4, kUShort, false}};
  if (semantic == "WEIGHTS")
    return {F{TINYGLTF_TYPE_VEC4, kFloat, false}, F{TINYGLTF_TYPE_VEC4, kUByte, true}, F{TINYGLTF_TYPE_VEC4, kUShort, true}};
  return {};
}

// "TEXCOORD_1" -> ("TEXCOORD", 1); a name without a numeric suffix -> (name, -1).
std::pair<std::string, int> splitSemantic(const std::string& name) {
  const size_t underscore = name.rfind('_');
  if (underscore == std::string::npos || underscore == 0 || underscore + 1 == name.size()) return {name, -1};
  const std::string digits = name.substr(underscore + 1);
  if (digits.size() > 4 || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) return {name, -1};
  return {name.substr(0, underscore), std::stoi(digits)};
}

bool indexedSemantic(const std::string& base) { return base == "TEXCOORD" || base == "COLOR" || base == "JOINTS" || base == "WEIGHTS"; }

// The accessor `index` in one of the formats `allowed` for `use` (a semantic), else an Error
// naming them and the validator's `code`.
const tinygltf::Accessor& requireFormat(const tinygltf::Model& model, int index, const std::vector<Format>& allowed, const std::string& use,
                                        const std::string& name, const char* code) {
  const tinygltf::Accessor& acc = model.accessors[size_t(index)];
  if (std::none_of(allowed.begin(), allowed.end(), [&](const Format& f) {
        return f.type == acc.type && f.componentType == acc.componentType && f.normalized == acc.normalized;
      })) {
    std::string list;
    for (const Format& f : allowed) list += (list.empty() ? "" : ", ") + formatName(f.type, f.componentType, f.normalized);
    throw Error(name + " is " + formatName(acc.type, acc.componentType, acc.normalized) + "; glTF allows " + use + " only as " + list + " (" +
                code + ")");
  }
  return acc;
}

void checkVertexAttribute(const tinygltf::Model& model, int index, const std::string& semantic, const std::string& at) {
  const std::string where = at + " " + semantic;
  const AccessorLayout layout = accessorLayout(model, index, where);  // the accessor's own checks: it exists, it fits, it is aligned
  const std::string name = where + ": accessor " + std::to_string(index);
  requireFormat(model, index, allowedFormats(splitSemantic(semantic).first), semantic, name, "MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT");
  if (layout.byteOffset % 4 != 0 || layout.stride % 4 != 0)
    throw Error(name + " starts at byte " + std::to_string(layout.byteOffset) + " of its buffer with elements " +
                std::to_string(layout.stride) + " bytes apart; vertex attributes must be aligned to 4 bytes (MESH_PRIMITIVE_ACCESSOR_UNALIGNED)");
}

bool oneOf(const std::string& key, std::initializer_list<const char*> keys) {
  return std::any_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; });
}

// "FILE: AT is VALUE": how every rule below names the value it found.
std::string found(const std::string& file, const std::string& at, const nlohmann::json& v) { return file + ": " + at + " is " + v.dump().substr(0, 40); }

bool isIndexKey(const std::string& key) {
  return oneOf(key, {"scene", "mesh", "camera", "skin", "material", "indices", "bufferView", "buffer", "source", "sampler", "index", "light",
                     "node", "input", "output"});
}

void requireIndex(const nlohmann::json& v, const std::string& where, const std::string& file) {
  if (!v.is_number_integer() || v.get<int64_t>() < 0) throw Error(found(file, where, v) + ", not a non-negative integer (INVALID_INDEX, TYPE_MISMATCH)");
}

// Sizes, offsets and enumerations: whole numbers (tinygltf truncates 1.5 and skips a string).
bool isCountKey(const std::string& key) { return oneOf(key, {"byteOffset", "byteLength", "byteStride", "count", "componentType", "mode", "target"}); }

bool isColorFactorKey(const std::string& key) {
  return oneOf(key, {"baseColorFactor", "emissiveFactor", "attenuationColor", "specularColorFactor", "sheenColorFactor"});
}

bool isScalarFactorKey(const std::string& key) {
  return oneOf(key, {"metallicFactor", "roughnessFactor", "alphaCutoff", "ior", "transmissionFactor", "thicknessFactor", "attenuationDistance",
                     "emissiveStrength", "specularFactor", "intensity", "innerConeAngle", "outerConeAngle", "strength"});
}

void requireNumbers(const nlohmann::json& v, const std::string& at, const std::string& file) {
  if (!v.is_array()) throw Error(found(file, at, v) + ", not an array of numbers (TYPE_MISMATCH)");
  for (size_t i = 0; i < v.size(); ++i)
    if (!v[i].is_number()) throw Error(found(file, at + "/" + std::to_string(i), v[i]) + ", not a number (ARRAY_TYPE_MISMATCH)");
}

std::string ignoredValue(const std::string& file, const std::string& at, const nlohmann::json& v, const char* wanted) {
  return found(file, at, v) + ", not " + wanted + "; ignored (TYPE_MISMATCH)";
}

// The rules on single values, over the whole document. `depth` bounds the recursion: glTF
// nests about ten levels; deeper is an extension's data.
void scanValues(const nlohmann::json& node, const std::string& where, const std::string& file, std::vector<std::string>& warnings, int depth = 0) {
  if (depth > 32) return;
  if (node.is_object()) {
    for (const auto& [key, value] : node.items()) {
      if (key == "extras") continue;  // the application's own data
      const std::string at = where + "/" + key;
      const bool inExtension = where.rfind("/extensions") != std::string::npos;
      if ((isIndexKey(key) || (isCountKey(key) && !inExtension)) && !value.is_object() && !value.is_array()) requireIndex(value, at, file);
      // A glTF object's name (not an extension's: its own data).
      if (key == "name" && !inExtension && !value.is_string()) warnings.push_back(ignoredValue(file, at, value, "a string"));
      // A node's transform and a material's colour factors: arrays of numbers (tinygltf drops
      // anything else, and the object would render untransformed or white).
      // (Materials and KHR_lights_punctual only: another extension's data may use the names.)
      const bool material = where.rfind("/materials/", 0) == 0, light = where.rfind("/extensions/KHR_lights_punctual/", 0) == 0;
      if (((key == "matrix" || key == "translation" || key == "rotation" || key == "scale") && where.rfind("/nodes/", 0) == 0) ||
          (material && isColorFactorKey(key)) || (light && key == "color"))
        requireNumbers(value, at, file);
      // A material's and a light's scalar factors: numbers (tinygltf keeps the default).
      if ((material || light) && isScalarFactorKey(key) && !value.is_number()) throw Error(found(file, at, value) + ", not a number (TYPE_MISMATCH)");
      if (key == "attributes" && value.is_object()) {
        for (const auto& [name, index] : value.items()) requireIndex(index, at + "/" + name, file);
      }
      // Lists of node indices: a scene's roots, a node's children, a skin's joints (the top-level
      // `nodes` holds objects).
      if ((key == "children" || key == "joints" || (key == "nodes" && !where.empty())) && value.is_array()) {
        for (size_t i = 0; i < value.size(); ++i) requireIndex(value[i], at + "/" + std::to_string(i), file);
      }
      scanValues(value, at, file, warnings, depth + 1);
    }
  } else if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i) scanValues(node[i], where + "/" + std::to_string(i), file, warnings, depth + 1);
  }
}

// An accessor's `min` and `max`: arrays of numbers, whole ones for an integer component type.
void checkAccessorBounds(const nlohmann::json& doc, const std::string& file, std::vector<std::string>& warnings) {
  const auto accessors = doc.find("accessors");
  if (accessors == doc.end() || !accessors->is_array()) return;
  for (size_t i = 0; i < accessors->size(); ++i) {
    const nlohmann::json& a = (*accessors)[i];
    if (!a.is_object()) continue;
    const auto type = a.find("componentType");
    const bool integer = type != a.end() && type->is_number_integer() && type->get<int64_t>() != 5126;  // all but FLOAT
    for (const char* key : {"min", "max"}) {
      const auto bound = a.find(key);
      if (bound == a.end()) continue;
      const std::string at = "/accessors/" + std::to_string(i) + "/" + key;
      if (!bound->is_array()) {
        warnings.push_back(ignoredValue(file, at, *bound, "an array"));
        continue;
      }
      for (size_t k = 0; k < bound->size(); ++k) {
        const nlohmann::json& v = (*bound)[k];
        const double d = v.is_number() ? v.get<double>() : 0.0;
        const bool whole = v.is_number_integer() || (std::isfinite(d) && std::floor(d) == d);
        if (!v.is_number() || (integer && !whole)) {
          warnings.push_back(ignoredValue(file, at + "/" + std::to_string(k), v, integer ? "an integer for an integer component type" : "a number"));
          break;
        }
      }
    }
  }
}

// extensionsUsed and extensionsRequired: arrays of strings.
void checkExtensionLists(const nlohmann::json& doc, const std::string& file, std::vector<std::string>& warnings) {
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    const auto list = doc.find(key);
    if (list == doc.end()) continue;
    const bool required = std::string(key) == "extensionsRequired";
    const std::vector<nlohmann::json> entries = list->is_array() ? list->get<std::vector<nlohmann::json>>() : std::vector<nlohmann::json>{*list};
    for (size_t i = 0; i < entries.size(); ++i) {
      if (entries[i].is_string()) continue;
      const std::string at = "/" + std::string(key) + (list->is_array() ? "/" + std::to_string(i) : "");
      if (required) throw Error(found(file, at, entries[i]) + ", not an extension's name (TYPE_MISMATCH)");
      warnings.push_back(ignoredValue(file, at, entries[i], "an extension's name"));
    }
  }
}

}  // namespace

void checkJson(std::string_view json, const std::string& file, std::vector<std::string>& warnings) {
  const nlohmann::json doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return;  // tinygltf reports the syntax error
  scanValues(doc, "", file, warnings);
  checkExtensionLists(doc, file, warnings);
  checkAccessorBounds(doc, file, warnings);
}

void checkAssetVersion(const tinygltf::Model& model, const std::string& file) {
  auto major = [](const std::string& v) {
    const size_t dot = v.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == v.size()) return -1;
    if (!std::all_of(v.begin(), v.end(), [](char c) { return (c >= '0' && c <= '9') || c == '.'; })) return -1;
    return std::stoi(v.substr(0, std::min<size_t>(dot, 6)));
  };
  const std::string& version = model.asset.version;
  if (major(version) != 2)
    throw Error(file + ": asset.version is '" + version + "'; raybudget reads glTF 2.x (UNKNOWN_ASSET_MAJOR_VERSION)");
  const std::string& minVersion = model.asset.minVersion;
  if (!minVersion.empty() && (major(minVersion) != 2 || minVersion.substr(minVersion.find('.') + 1) != "0"))
    throw Error(file + ": asset.minVersion is '" + minVersion + "'; raybudget reads glTF 2.0 files");
}

void checkPrimitiveFormats(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& at) {
  std::map<std::string, std::set<int>> numbered;
  for (const auto& [semantic, index] : primitive.attributes) {
    if (!semantic.empty() && semantic[0] == '_') continue;  // application-specific: not read
    const auto [base, number] = splitSemantic(semantic);
    const bool known = indexedSemantic(base) ? number >= 0 : (number < 0 && !allowedFormats(base).empty());
    if (!known)
      throw Error(at + ": attribute '" + semantic +
                  "' is not a glTF semantic (POSITION, NORMAL, TANGENT, TEXCOORD_n, COLOR_n, JOINTS_n, WEIGHTS_n, or _NAME) "
                  "(MESH_PRIMITIVE_INVALID_ATTRIBUTE)");
    if (number >= 0) numbered[base].insert(number);
    checkVertexAttribute(model, index, semantic, at);
  }
  for (const auto& [base, numbers] : numbered)
    if (*numbers.rbegin() + 1 != int(numbers.size()))
      throw Error(at + ": the " + base + "_n attributes are not numbered 0.." + std::to_string(numbers.size() - 1) +
                  " without gaps (MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY)");
  if (primitive.indices < 0) return;
  const std::string where = at + " indices";
  accessorLayout(model, primitive.indices, where);
  const std::string name = where + ": accessor " + std::to_string(primitive.indices);
  const tinygltf::Accessor& acc =
      requireFormat(model, primitive.indices,
                    {{TINYGLTF_TYPE_SCALAR, kUByte, false}, {TINYGLTF_TYPE_SCALAR, kUShort, false}, {TINYGLTF_TYPE_SCALAR, kUInt, false}},
                    "indices", name, "MESH_PRIMITIVE_INDICES_ACCESSOR_INVALID_FORMAT");
  if (acc.bufferView >= 0 && model.bufferViews[size_t(acc.bufferView)].byteStride != 0)
    throw Error(name + ": its bufferView " + std::to_string(acc.bufferView) +
                " has a byteStride, which glTF forbids for indices (MESH_PRIMITIVE_INDICES_ACCESSOR_WITH_BYTESTRIDE)");
}

void checkInstanceAttributeFormat(const tinygltf::Model& model, int index, const std::string& semantic, const std::string& at) {
  accessorLayout(model, index, at);
  using F = Format;
  const std::vector<Format> allowed =
      semantic == "ROTATION"
          ? std::vector<Format>{F{TINYGLTF_TYPE_VEC4, kFloat, false}, F{TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_BYTE, true},
                                F{TINYGLTF_TYPE_VEC4, TINYGLTF_COMPONENT_TYPE_SHORT, true}}
          : std::vector<Format>{F{TINYGLTF_TYPE_VEC3, kFloat, false}};
  requireFormat(model, index, allowed, "EXT_mesh_gpu_instancing " + semantic, at + ": accessor " + std::to_string(index),
                "EXT_mesh_gpu_instancing");
}

void checkSharedVertexBufferViews(const tinygltf::Model& model, const std::string& file) {
  std::map<int, std::set<int>> attributeAccessors;  // bufferView -> the vertex attribute accessors in it
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& primitive : mesh.primitives)
      for (const auto& [semantic, index] : primitive.attributes)
        if (index >= 0 && size_t(index) < model.accessors.size() && model.accessors[size_t(index)].bufferView >= 0)
          attributeAccessors[model.accessors[size_t(index)].bufferView].insert(index);
  for (const auto& [view, accessors] : attributeAccessors)
    if (accessors.size() > 1 && size_t(view) < model.bufferViews.size() && model.bufferViews[size_t(view)].byteStride == 0)
      throw Error(file + ": bufferView " + std::to_string(view) + " holds " + std::to_string(accessors.size()) +
                  " vertex attribute accessors but no byteStride, which glTF then requires (MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE)");
}

void checkPositionBounds(const tinygltf::Model& model, int accessor, const std::vector<glm::vec4>& positions, const std::string& at,
                         std::vector<std::string>& warnings) {
  const tinygltf::Accessor& acc = model.accessors[size_t(accessor)];
  if (acc.minValues.size() != 3 || acc.maxValues.size() != 3) {
    warnings.push_back(at + " POSITION: accessor " + std::to_string(accessor) +
                       " has no min/max, which glTF requires; the bounds are taken from the data (MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS)");
    return;
  }
  if (positions.empty()) return;
  glm::vec3 lo(positions[0]), hi(positions[0]);
  for (const glm::vec4& p : positions) {
    lo = glm::min(lo, glm::vec3(p));
    hi = glm::max(hi, glm::vec3(p));
  }
  // As the validator compares them: the declared values rounded to float against the data's.
  for (int c = 0; c < 3; ++c)
    if (float(acc.minValues[size_t(c)]) != lo[c] || float(acc.maxValues[size_t(c)]) != hi[c]) {
      warnings.push_back(at + " POSITION: accessor " + std::to_string(accessor) +
                         "'s declared min/max differ from its data; the data's bounds are used (ACCESSOR_MIN_MISMATCH, ACCESSOR_MAX_MISMATCH)");
      return;
    }
}

}  // namespace raybudget::gltf
