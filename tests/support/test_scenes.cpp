#include "support/test_scenes.h"

#include <fstream>
#include <string>

#include <unistd.h>

#include <nlohmann/json.hpp>

namespace raybudget::test {

std::filesystem::path sharedScenesDir() { return std::filesystem::path(RAYBUDGET_SHARED_DIR) / "scenes"; }

std::vector<std::filesystem::path> manifestScenes(const std::string& set) {
  std::vector<std::filesystem::path> out;
  std::ifstream in(sharedScenesDir() / "MANIFEST.json");
  if (!in) return out;
  const nlohmann::json manifest = nlohmann::json::parse(in);
  for (const auto& e : manifest)
    if (e.value("set", "") == set) out.push_back(sharedScenesDir() / e.value("path", ""));
  return out;
}

std::filesystem::path defaultScenePath() { return std::filesystem::path(RAYBUDGET_SOURCE_DIR) / "data" / "default" / "court.gltf"; }

uint32_t objectNamed(const Scene& scene, const std::string& name) {
  for (const Object& o : scene.objects)
    if (o.name == name) return o.id;
  return kNoObjectNamed;
}

std::filesystem::path freshTempDir(const std::string& name) {
  // Per process: CTest runs each test as its own process, in parallel, and tests of one
  // file share names (two FrameTiming tests removed each other's folder while writing it).
  const auto dir = std::filesystem::temp_directory_path() / ("raybudget-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace raybudget::test
