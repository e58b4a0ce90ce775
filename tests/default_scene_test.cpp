// The default scene is what the README's main command renders, the plaza the benchmark's
// generated level: both must be reproducible from their generator and have what the
// mission asks of them.
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "raybudget/scene.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::filesystem::path plazaPath() { return std::filesystem::path(RAYBUDGET_SOURCE_DIR) / "data" / "plaza" / "plaza.gltf"; }

TEST(DefaultScene, GeneratorReproducesTheCommittedFiles) {
  const auto dir = test::freshTempDir("default-scene");
  const std::string cmd = "python3 \"" + std::string(RAYBUDGET_SOURCE_DIR) + "/tools/make_default_scene.py\" \"" + dir.string() + "\" > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  for (const std::filesystem::path& committed : {test::defaultScenePath(), plazaPath()}) {
    const std::filesystem::path made = dir / committed.parent_path().filename() / committed.filename();
    EXPECT_EQ(slurp(made), slurp(committed)) << committed << " is stale: run tools/make_default_scene.py";
    EXPECT_EQ(slurp(std::filesystem::path(made).replace_extension(".bin")), slurp(std::filesystem::path(committed).replace_extension(".bin")));
  }
}

// What the mission asks of a generated scene: mirrors, glass, lights of every punctual
// type, authored priorities, objects at mixed distances, and at least `objects` of them.
void expectMirrorsGlassLightsAndACrowd(const std::filesystem::path& file, size_t objects, size_t lights) {
  SCOPED_TRACE(file.string());
  const Scene s = loadScene(file);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_GE(s.objects.size(), objects) << "enough objects that the budget has to choose";
  bool directional = false, point = false, spot = false;
  for (const Light& l : s.lights) {
    directional |= l.type == LightType::Directional;
    point |= l.type == LightType::Point;
    spot |= l.type == LightType::Spot;
  }
  EXPECT_TRUE(directional && point && spot) << "one light of each punctual type";
  EXPECT_GE(s.lights.size(), lights);
  size_t mirrors = 0, glass = 0, authored = 0;
  for (const Object& o : s.objects) {
    for (const Primitive& p : s.meshes[o.mesh].primitives) {
      const Material& m = s.materials[size_t(p.material)];
      mirrors += m.metallic == 1.0f && m.roughness <= 0.05f;
      glass += m.transmission > 0.0f;
    }
    authored += o.params.importanceK || o.params.raysQ || o.params.hysteresisI;
  }
  EXPECT_GE(mirrors, 1u);
  EXPECT_GE(glass, 2u);
  EXPECT_GE(authored, 4u) << "some objects carry extras.raybudget";
  ASSERT_TRUE(s.camera.has_value());
  // Objects at mixed distances from the camera: the nearest and farthest differ by 3x.
  float nearest = 1e30f, farthest = 0.0f;
  for (const Object& o : s.objects) {
    const float d = glm::length(0.5f * (o.boundsMin + o.boundsMax) - s.camera->position);
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
  }
  EXPECT_GT(farthest, 3.0f * nearest);
}

TEST(DefaultScene, HasMirrorsGlassLightsAndACrowd) { expectMirrorsGlassLightsAndACrowd(test::defaultScenePath(), 36, 3); }

// The benchmark's level: the paper's setting, a game level with many objects.
TEST(DefaultScene, ThePlazaIsALevelOfOverAHundredObjects) { expectMirrorsGlassLightsAndACrowd(plazaPath(), 100, 4); }

}  // namespace
}  // namespace raybudget
