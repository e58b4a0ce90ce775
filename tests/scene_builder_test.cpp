// raybudget::SceneBuilder: a host's arrays (any stride) become the same scene the glTF
// loader makes, and bad input is refused with the mesh, material or instance named.
#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "raybudget/error.h"
#include "support/builder_scene.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

std::string errorOf(auto&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneBuilder, RebuildsTheDefaultSceneFromInterleavedArrays) {
  const Scene loaded = loadScene(test::defaultScenePath());
  const Scene built = test::rebuiltThroughBuilder(loaded);
  ASSERT_EQ(built.objects.size(), loaded.objects.size());
  EXPECT_EQ(built.lights.size(), loaded.lights.size());
  EXPECT_EQ(built.stats.triangles, loaded.stats.triangles);
  EXPECT_EQ(built.boundsMin, loaded.boundsMin);
  EXPECT_EQ(built.boundsMax, loaded.boundsMax);
  for (size_t i = 0; i < loaded.objects.size(); ++i) {
    const Object &a = loaded.objects[i], &b = built.objects[i];
    EXPECT_EQ(b.id, i);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.transform, a.transform);
    EXPECT_EQ(b.boundsMin, a.boundsMin);
    EXPECT_EQ(b.params.importanceK, a.params.importanceK);
    const Mesh &ma = loaded.meshes[a.mesh], &mb = built.meshes[b.mesh];
    EXPECT_EQ(mb.indices, ma.indices);
    ASSERT_EQ(mb.vertices.size(), ma.vertices.size());
    for (size_t v = 0; v < ma.vertices.size(); ++v) {
      EXPECT_EQ(mb.vertices[v].position, ma.vertices[v].position);
      EXPECT_EQ(mb.vertices[v].normal, ma.vertices[v].normal);
    }
    EXPECT_EQ(mb.primitives[0].material, ma.primitives[0].material);
  }
  ASSERT_EQ(built.materials.size(), loaded.materials.size());
  for (size_t i = 0; i < loaded.materials.size(); ++i) {
    const Material &a = loaded.materials[i], &b = built.materials[i];
    EXPECT_EQ(b.baseColorFactor, a.baseColorFactor);
    EXPECT_EQ(b.roughness, a.roughness);
    EXPECT_EQ(b.transmission, a.transmission);
    EXPECT_EQ(b.thickness, a.thickness);
    EXPECT_EQ(b.attenuationDistance, a.attenuationDistance);
    EXPECT_EQ(b.attenuationColor, a.attenuationColor);
  }
}

TEST(SceneBuilder, GeneratesNormalsDropsZeroAreaTrianglesAndCopiesMaterialsPerInstance) {
  SceneBuilder b;
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0};  // packed (stride 0)
  const uint32_t indices[] = {0, 1, 2, 0, 1, 3};                   // the second has no area
  MeshInput in{"tri", 4, {positions, 0}, {}, indices};
  const uint32_t mesh = b.addMesh(in);
  const uint32_t red = b.addMaterial({.name = "red", .baseColor = {1, 0, 0, 1}});
  const uint32_t glass = b.addMaterial({.name = "glass", .transmission = 1.0f});
  EXPECT_EQ(b.addInstance(mesh, red, glm::mat4(1.0f)), 0u);
  EXPECT_EQ(b.addInstance(mesh, glass, glm::translate(glm::mat4(1.0f), glm::vec3(3, 0, 0)), {2.0f, {}, {}}, "pane"), 1u);
  EXPECT_EQ(b.addInstance(mesh, glass, glm::translate(glm::mat4(1.0f), glm::vec3(6, 0, 0))), 2u);
  const Scene s = b.build();
  EXPECT_EQ(s.meshes.size(), 2u);  // one copy for the second material, shared by its instances
  EXPECT_EQ(s.objects[2].mesh, s.objects[1].mesh);
  EXPECT_EQ(s.stats.droppedDegenerateTriangles, 1u);
  EXPECT_EQ(s.meshes[s.objects[0].mesh].indices.size(), 3u);
  EXPECT_EQ(s.meshes[s.objects[0].mesh].vertices[0].normal, glm::vec3(0, 0, 1));
  EXPECT_EQ(s.meshes[s.objects[0].mesh].primitives[0].material, int(red));
  EXPECT_EQ(s.meshes[s.objects[1].mesh].primitives[0].material, int(glass));
  EXPECT_EQ(s.objects[1].name, "pane");
  EXPECT_EQ(*s.objects[1].params.importanceK, 2.0f);
  EXPECT_EQ(s.objects[1].boundsMin, glm::vec3(3, 0, 0));
  EXPECT_TRUE(s.usesDefaultSun);
  EXPECT_EQ(sceneEffects(s, 0.35f).refractions, true);
}

TEST(SceneBuilder, BadInputIsNamed) {
  SceneBuilder b;
  const float nan = std::nanf("");
  const float bad[] = {0, 0, 0, 1, nan, 0, 0, 1, 0};
  const uint32_t tri[] = {0, 1, 2}, outOfRange[] = {0, 1, 7}, two[] = {0, 1};
  EXPECT_EQ(errorOf([&] { b.addMesh({"bad", 3, {bad, 0}, {}, tri}); }), "mesh 0 ('bad'): the position of vertex 1 is not finite (NaN or Inf)");
  const float ok[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_NE(errorOf([&] { b.addMesh({"far", 3, {ok, 0}, {}, outOfRange}); }).find("index 2 is 7, out of range for 3 vertices"), std::string::npos);
  EXPECT_NE(errorOf([&] { b.addMesh({"two", 3, {ok, 0}, {}, two}); }).find("not a triangle list"), std::string::npos);
  const float line[] = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  EXPECT_NE(errorOf([&] { b.addMesh({"flat", 3, {line, 0}, {}, tri}); }).find("no triangle with any area"), std::string::npos);
  EXPECT_NE(errorOf([&] { b.addMaterial({.name = "shiny", .roughness = 2.0f}); }).find("material 0 ('shiny'): roughness"), std::string::npos);
  EXPECT_NE(errorOf([&] { b.addMaterial({.name = "n", .metallic = nan}); }).find("metallic"), std::string::npos);
  const uint32_t mesh = b.addMesh({"ok", 3, {ok, 0}, {}, tri});
  const uint32_t material = b.addMaterial({});
  EXPECT_NE(errorOf([&] { b.addInstance(9, material, glm::mat4(1.0f)); }).find("mesh 9 does not exist"), std::string::npos);
  EXPECT_NE(errorOf([&] { b.addInstance(mesh, 9, glm::mat4(1.0f)); }).find("material 9 does not exist"), std::string::npos);
  EXPECT_NE(errorOf([&] { b.addInstance(mesh, material, glm::mat4(0.0f), {}, "flat"); }).find("instance 0 ('flat'): singular transform"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { b.addInstance(mesh, material, glm::mat4(1.0f), {-1.0f, {}, {}}); }).find("negative"), std::string::npos);
  Light light;
  light.intensity = -3.0f;
  EXPECT_NE(errorOf([&] { b.addLight(light); }).find("negative or not finite"), std::string::npos);
  EXPECT_NE(errorOf([&] { (void)b.build(); }).find("no instance"), std::string::npos);
}

}  // namespace
}  // namespace raybudget
