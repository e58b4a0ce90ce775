#include "support/gltf_fixture.h"

#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "raybudget/error.h"
#include "raybudget/scene.h"

namespace raybudget::test {

GltfFixture GltfFixture::triangles(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
  GltfFixture f;
  glm::vec3 lo = positions.empty() ? glm::vec3(0.0f) : positions[0], hi = lo;
  for (const glm::vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  f.bin.resize(positions.size() * 12 + indices.size() * 4);
  std::memcpy(f.bin.data(), positions.data(), positions.size() * 12);
  std::memcpy(f.bin.data() + positions.size() * 12, indices.data(), indices.size() * 4);
  nlohmann::json prim = {{"attributes", {{"POSITION", 0}}}};
  nlohmann::json accessors = nlohmann::json::array(
      {{{"bufferView", 0}, {"componentType", 5126}, {"count", positions.size()}, {"type", "VEC3"}, {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}}});
  nlohmann::json views = nlohmann::json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", positions.size() * 12}}});
  if (!indices.empty()) {
    prim["indices"] = 1;
    accessors.push_back({{"bufferView", 1}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}});
    views.push_back({{"buffer", 0}, {"byteOffset", positions.size() * 12}, {"byteLength", indices.size() * 4}});
  }
  f.json = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}, {"name", "tri"}}}},
            {"meshes", {{{"primitives", {prim}}}}},
            {"accessors", accessors},
            {"bufferViews", views},
            {"buffers", {{{"uri", "PLACEHOLDER.bin"}, {"byteLength", f.bin.size()}}}}};
  return f;
}

void GltfFixture::addNormals(const std::vector<glm::vec3>& normals) {
  const size_t offset = bin.size();  // a multiple of 4: positions and indices are
  bin.resize(offset + normals.size() * 12);
  std::memcpy(bin.data() + offset, normals.data(), normals.size() * 12);
  json["buffers"][0]["byteLength"] = bin.size();
  json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", normals.size() * 12}});
  json["accessors"].push_back({{"bufferView", json["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", normals.size()}, {"type", "VEC3"}});
  json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = json["accessors"].size() - 1;
}

GltfFixture GltfFixture::oneTriangle() { return triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}); }

std::filesystem::path GltfFixture::write(const std::filesystem::path& dir, const std::string& name) const {
  nlohmann::json j = json;
  if (j.contains("buffers") && !j["buffers"].empty() && j["buffers"][0].value("uri", "") == "PLACEHOLDER.bin") j["buffers"][0]["uri"] = name + ".bin";
  const auto gltf = dir / (name + ".gltf");
  std::ofstream(gltf) << j.dump(2);
  std::ofstream(dir / (name + ".bin"), std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
  return gltf;
}

void expectLoadError(const std::filesystem::path& path, const std::string& expected) {
  try {
    loadScene(path);
    ADD_FAILURE() << "loading " << path << " should have failed with '" << expected << "'";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << "message does not name the file: " << what;
    EXPECT_NE(what.find(expected), std::string::npos) << "message: " << what;
  }
}

}  // namespace raybudget::test
