// Converts glTF mesh primitives into raybudget triangle-list meshes: topology modes,
// attribute reads, NaN checks, zero-area triangle removal and missing-normal generation.
#pragma once
#include <string>

#include "raybudget/scene.h"

namespace tinygltf {
class Model;
}

namespace raybudget::gltf {

// Builds mesh `meshIndex`; `where` prefixes error messages (the file path). Appends the
// default material to `scene.materials` when a primitive has none, and counts dropped and
// skipped geometry in `scene.stats` / `scene.warnings`.
Mesh buildMesh(const tinygltf::Model& model, int meshIndex, const std::string& where, Scene& scene);

}  // namespace raybudget::gltf
