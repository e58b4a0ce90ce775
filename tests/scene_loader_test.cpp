// Every shared scene loads, and what we load matches the manifest's independent counts.
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "raybudget/scene.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

struct ManifestEntry {
  std::filesystem::path path;
  size_t triangles;
  size_t lights;
};

std::vector<ManifestEntry> manifest() {
  std::vector<ManifestEntry> out;
  std::ifstream in(test::sharedScenesDir() / "MANIFEST.json");
  if (!in) return out;
  for (const auto& e : nlohmann::json::parse(in))
    out.push_back({test::sharedScenesDir() / e.value("path", ""), e.value("triangles", size_t(0)), e.value("punctual_lights", size_t(0))});
  return out;
}

TEST(SceneLoader, EverySharedSceneLoadsWithTheManifestTriangleCount) {
  RB_REQUIRE_SHARED_SCENES();
  const auto entries = manifest();
  ASSERT_GE(entries.size(), 29u);
  for (const ManifestEntry& e : entries) {
    SCOPED_TRACE(e.path.string());
    const Scene s = loadScene(e.path);
    // The manifest counts drawn triangles with an independent tool; we drop zero-area ones.
    EXPECT_EQ(s.stats.triangles + s.stats.droppedDegenerateTriangles, e.triangles);
    EXPECT_EQ(s.lights.size(), std::max<size_t>(e.lights, 1));
    EXPECT_EQ(s.usesDefaultSun, e.lights == 0);
    for (const Object& o : s.objects) {
      EXPECT_LT(o.mesh, s.meshes.size());
      EXPECT_TRUE(glm::all(glm::lessThanEqual(o.boundsMin, o.boundsMax)));
    }
    for (size_t i = 0; i < s.objects.size(); ++i) EXPECT_EQ(s.objects[i].id, i) << "object IDs are stable indices";
  }
}

TEST(SceneLoader, GpuInstancingMakesOneObjectPerInstance) {
  RB_REQUIRE_SHARED_SCENES();
  const Scene s = loadScene(test::sharedScenesDir() / "ci/SimpleInstancing/SimpleInstancing.gltf");
  EXPECT_EQ(s.objects.size(), 125u);
  EXPECT_EQ(s.meshes.size(), 1u) << "instances share one mesh";
}

TEST(SceneLoader, StripsAndFansBecomeTrianglesAndPointsLinesAreSkipped) {
  RB_REQUIRE_SHARED_SCENES();
  const Scene s = loadScene(test::sharedScenesDir() / "ci/MeshPrimitiveModes/MeshPrimitiveModes.gltf");
  EXPECT_EQ(s.stats.skippedPointLinePrimitives, 4u);
  for (const Mesh& m : s.meshes) EXPECT_EQ(m.indices.size() % 3, 0u);
}

TEST(SceneLoader, MaterialExtensionsAreRead) {
  RB_REQUIRE_SHARED_SCENES();
  const Scene s = loadScene(test::sharedScenesDir() / "ci/BlenderIorTest/17_ior.gltf");
  std::vector<float> iors;
  for (const Material& m : s.materials)
    if (m.transmission > 0.0f) iors.push_back(m.ior);
  std::sort(iors.begin(), iors.end());
  ASSERT_EQ(iors.size(), 3u);
  EXPECT_FLOAT_EQ(iors[0], 1.45f);
  EXPECT_FLOAT_EQ(iors[1], 1.5f);
  EXPECT_FLOAT_EQ(iors[2], 2.0f);
  const Scene v = loadScene(test::sharedScenesDir() / "ci/AttenuationTest/AttenuationTest.gltf");
  EXPECT_TRUE(std::any_of(v.materials.begin(), v.materials.end(), [](const Material& m) { return m.thickness > 0.0f && m.attenuationDistance > 0.0f; }));
  const Scene e = loadScene(test::sharedScenesDir() / "ci/EmissiveStrengthTest/EmissiveStrengthTest.gltf");
  EXPECT_TRUE(std::any_of(e.materials.begin(), e.materials.end(), [](const Material& m) { return m.emissive.r > 1.0f; }))
      << "KHR_materials_emissive_strength scales emissive beyond 1";
}

TEST(SceneLoader, CamerasAndLightsComeFromTheFile) {
  RB_REQUIRE_SHARED_SCENES();
  const Scene duck = loadScene(test::sharedScenesDir() / "ci/Duck/Duck.glb");
  ASSERT_TRUE(duck.camera.has_value());
  EXPECT_GT(duck.camera->zfar, duck.camera->znear);
  const Scene suzanne = loadScene(test::sharedScenesDir() / "ci/IridescenceSuzanne/IridescenceSuzanne.gltf");
  ASSERT_EQ(suzanne.lights.size(), 1u);
  EXPECT_FALSE(suzanne.usesDefaultSun);
}

TEST(SceneLoader, SceneWithoutLightsGetsTheDocumentedSun) {
  RB_REQUIRE_SHARED_SCENES();
  const Scene s = loadScene(test::sharedScenesDir() / "ci/Box/Box.gltf");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_TRUE(s.usesDefaultSun);
  EXPECT_EQ(s.lights[0].name, defaultSun().name);
  EXPECT_EQ(s.lights[0].type, LightType::Directional);
}

TEST(SceneLoader, DefaultCameraFramesTheBounds) {
  RB_REQUIRE_SHARED_SCENES();
  const Scene s = loadScene(test::sharedScenesDir() / "ci/Box/Box.gltf");
  ASSERT_FALSE(s.camera.has_value());
  const Camera c = defaultCamera(s, 16.0f / 9.0f);
  const glm::vec3 center = 0.5f * (s.boundsMin + s.boundsMax);
  EXPECT_LT(glm::length(c.target - center), 1e-5f);
  // Every bounds corner is in front of the camera and inside its view frustum.
  const glm::mat4 vp = c.projection(16.0f / 9.0f) * c.view();
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 p((k & 1) ? s.boundsMax.x : s.boundsMin.x, (k & 2) ? s.boundsMax.y : s.boundsMin.y, (k & 4) ? s.boundsMax.z : s.boundsMin.z);
    const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
    EXPECT_GT(clip.w, 0.0f);
    EXPECT_LE(std::abs(clip.x / clip.w), 1.0f);
    EXPECT_LE(std::abs(clip.y / clip.w), 1.0f);
    EXPECT_GE(clip.z / clip.w, 0.0f);
    EXPECT_LE(clip.z / clip.w, 1.0f);
  }
}

}  // namespace
}  // namespace raybudget
