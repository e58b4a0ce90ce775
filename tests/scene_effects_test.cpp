// sceneEffects: which ray-traced effects a scene can show at all (the renderer builds no
// pipeline and runs no pass for the others).
#include <gtest/gtest.h>

#include "raybudget/scene.h"

namespace raybudget {
namespace {

// One object per material, one triangle each, and one light.
Scene sceneWith(const std::vector<Material>& materials) {
  Scene s;
  s.materials = materials;
  for (size_t i = 0; i < materials.size(); ++i) {
    Mesh m;
    m.vertices.resize(3);
    m.indices = {0, 1, 2};
    m.primitives.push_back({0, 3, int32_t(i)});
    s.meshes.push_back(m);
    Object o;
    o.mesh = uint32_t(i);
    s.objects.push_back(o);
  }
  s.lights.push_back(defaultSun());
  return s;
}

Material rough() {
  Material m;
  m.roughness = 0.8f;
  return m;
}

TEST(SceneEffects, RoughOpaqueMaterialsNeedOnlyShadows) {
  const SceneEffects e = sceneEffects(sceneWith({rough(), rough()}), 0.35f);
  EXPECT_TRUE(e.shadows);
  EXPECT_FALSE(e.reflections);
  EXPECT_FALSE(e.refractions);
}

TEST(SceneEffects, ASmoothMaterialReflectsAndTheCutOffDecides) {
  Material smooth = rough();
  smooth.roughness = 0.3f;
  EXPECT_TRUE(sceneEffects(sceneWith({rough(), smooth}), 0.35f).reflections);
  EXPECT_FALSE(sceneEffects(sceneWith({rough(), smooth}), 0.25f).reflections);
}

TEST(SceneEffects, ARoughnessTextureCountsWithItsLeastValue) {
  Scene s = sceneWith({rough()});
  s.images.push_back({"mr", 2, 1, {0, 255, 0, 255, 0, 100, 0, 255}});  // G: 255 and 100
  s.textures.push_back({0, -1});
  s.materials[0].metallicRoughnessTexture = 0;
  // 0.8 * 100/255 = 0.31: reflects under the 0.35 cut-off, not under 0.3.
  EXPECT_TRUE(sceneEffects(s, 0.35f).reflections);
  EXPECT_FALSE(sceneEffects(s, 0.3f).reflections);
}

TEST(SceneEffects, TransmissionRefractsUnlitShowsNothingAndNoLightNoShadows) {
  Material glass = rough();
  glass.transmission = 1.0f;
  EXPECT_TRUE(sceneEffects(sceneWith({glass}), 0.35f).refractions);
  Material unlit = glass;
  unlit.unlit = true;
  unlit.roughness = 0.0f;
  Scene s = sceneWith({unlit});
  s.lights.clear();
  const SceneEffects e = sceneEffects(s, 0.35f);
  EXPECT_FALSE(e.shadows);
  EXPECT_FALSE(e.reflections);
  EXPECT_FALSE(e.refractions);
}

TEST(SceneEffects, OnlyMaterialsOfObjectsCount) {
  Material glass = rough();
  glass.transmission = 1.0f;
  Scene s = sceneWith({rough()});
  s.materials.push_back(glass);  // no object uses it
  EXPECT_FALSE(sceneEffects(s, 0.35f).refractions);
}

}  // namespace
}  // namespace raybudget
