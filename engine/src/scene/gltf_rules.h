// The glTF 2.0 validity rules the loader enforces beyond bounds-checked reading
// (accessor_reader.h): the asset version, the accessor formats and alignment each use
// allows, and what a primitive's attributes must look like. Each broken rule is an Error
// naming the file, the object and the rule, in the words of the specification (and the
// Khronos glTF-Validator's issue code, so a user can look it up); docs/ROBUSTNESS.md lists
// them with what is repaired instead.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace raybudget::gltf {

// The rules tinygltf's reading hides, checked on the file's JSON text (`json`: a GLB's JSON
// chunk). Every index (mesh, material, accessor, bufferView, node... references,
// `children`, the primitives' attributes) is a non-negative integer where present: tinygltf
// reads a negative one as "absent", which would silently drop a mesh or turn an accessor into
// zeros (INVALID_INDEX). Values of the wrong type in fields raybudget does not render are
// ignored with a warning (TYPE_MISMATCH): a `name` or an `extensionsUsed` entry that is not a
// string, an accessor's `min` or `max` that is not an array of numbers (integers for an
// integer component type). An `extensionsRequired` entry that is not a string is an error:
// what the file requires cannot be known.
void checkJson(std::string_view json, const std::string& file, std::vector<std::string>& warnings);

// asset.version (and minVersion) must name glTF 2.x.
void checkAssetVersion(const tinygltf::Model& model, const std::string& file);

// Every attribute of the primitive: a known semantic (or an application one, "_NAME"),
// indexed semantics numbered from 0 without gaps, the types and component types its
// semantic allows, 4-byte aligned; its indices an unsigned scalar, not normalized, in a
// bufferView without byteStride. Accessor indices are range-checked first.
void checkPrimitiveFormats(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& at);

// An EXT_mesh_gpu_instancing attribute (`semantic`: TRANSLATION, ROTATION, SCALE) in the
// format the extension allows: VEC3 float for TRANSLATION and SCALE; VEC4 float, or normalized
// byte or short, for ROTATION.
void checkInstanceAttributeFormat(const tinygltf::Model& model, int accessor, const std::string& semantic, const std::string& at);

// Two or more accessors that hold vertex attributes in one bufferView need its byteStride.
void checkSharedVertexBufferViews(const tinygltf::Model& model, const std::string& file);

// The declared min/max of a POSITION accessor, which glTF requires, against its data: a
// missing or wrong one is repaired (the data's bounds are what the renderer uses) with a
// warning appended to `warnings`.
void checkPositionBounds(const tinygltf::Model& model, int accessor, const std::vector<glm::vec4>& positions, const std::string& at,
                         std::vector<std::string>& warnings);

}  // namespace raybudget::gltf
