// Builds small glTF files for tests: a valid one-triangle (or custom) scene as JSON plus a
// .bin, which a test mutates to make exactly the malformation it checks.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace raybudget::test {

struct GltfFixture {
  nlohmann::json json;
  std::vector<uint8_t> bin;

  // One mesh with `positions` (and indices when not empty) at node 0 of scene 0.
  static GltfFixture triangles(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices = {});
  static GltfFixture oneTriangle();

  // Appends a NORMAL attribute (one per position) to the first primitive.
  void addNormals(const std::vector<glm::vec3>& normals);

  // Writes NAME.gltf and NAME.bin into `dir`; returns the .gltf path.
  std::filesystem::path write(const std::filesystem::path& dir, const std::string& name) const;
};

// Loads `path` expecting an Error whose message names the file and contains `expected`
// (gtest failures otherwise).
void expectLoadError(const std::filesystem::path& path, const std::string& expected);

}  // namespace raybudget::test
