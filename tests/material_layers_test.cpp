// Materials both paths shade alike: KHR_texture_transform read as the extension defines it
// and applied by the raster and the tracer; clearcoat, sheen and specular shaded the same by
// the deferred lighting (from the G-buffer's layers) and by a traced hit (from the material).
#include <cmath>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "raybudget/image_io.h"
#include "support/gltf_fixture.h"
#include "support/procedural.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

using test::hdr;

// The extension's reference GLSL (translation * rotation * scale) expanded by hand.
glm::vec2 specTransform(glm::vec2 uv, glm::vec2 offset, float rotation, glm::vec2 scale) {
  const glm::vec2 s = uv * scale;
  return offset + glm::vec2(std::cos(rotation) * s.x - std::sin(rotation) * s.y, std::sin(rotation) * s.x + std::cos(rotation) * s.y);
}

TEST(MaterialLayers, LoaderReadsTextureTransformsAndLayers) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "raybudget_material_layers";
  std::filesystem::create_directories(dir);
  writePng(dir / "checker.png", 2, 2, std::vector<uint8_t>(16, 200));
  test::GltfFixture f = test::GltfFixture::triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  f.json["images"] = {{{"uri", "checker.png"}}};
  f.json["textures"] = {{{"source", 0}}};
  f.json["materials"] = nlohmann::json::parse(R"([{
    "pbrMetallicRoughness": {
      "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.25, 0.1], "rotation": 0.4, "scale": [2.0, 0.5]}}},
      "metallicRoughnessTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0, 0]}}}},
    "emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.25, 0.1], "rotation": 0.4, "scale": [2.0, 0.5]}}},
    "extensions": {
      "KHR_materials_clearcoat": {"clearcoatFactor": 0.8, "clearcoatRoughnessFactor": 0.3, "clearcoatTexture": {"index": 0}},
      "KHR_materials_sheen": {"sheenColorFactor": [1.0, 0.5, 0.25], "sheenRoughnessFactor": 0.6},
      "KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [2.0, 1.0, 0.5]}}}])");
  f.json["meshes"][0]["primitives"][0]["material"] = 0;
  const Scene scene = loadScene(f.write(dir, "layers"));
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.metallicRoughnessTexture, 0) << "an identity transform keeps the file's texture";
  ASSERT_EQ(scene.textures.size(), 2u) << "one texture for the transformed references, shared by both";
  EXPECT_EQ(m.baseColorTexture, 1);
  EXPECT_EQ(m.emissiveTexture, 1);
  EXPECT_EQ(scene.textures[1].image, 0);
  for (const glm::vec2 uv : {glm::vec2(0.0f), glm::vec2(1.0f, 0.0f), glm::vec2(0.3f, 0.9f)}) {
    const glm::vec3 got = scene.textures[1].uvTransform * glm::vec3(uv, 1.0f);
    const glm::vec2 want = specTransform(uv, {0.25f, 0.1f}, 0.4f, {2.0f, 0.5f});
    EXPECT_NEAR(got.x, want.x, 1e-6f);
    EXPECT_NEAR(got.y, want.y, 1e-6f);
  }
  EXPECT_FLOAT_EQ(m.clearcoat, 0.8f);
  EXPECT_FLOAT_EQ(m.clearcoatRoughness, 0.3f);
  EXPECT_EQ(m.clearcoatTexture, 0);
  EXPECT_EQ(m.sheenColor, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(m.sheenRoughness, 0.6f);
  EXPECT_FLOAT_EQ(m.specular, 0.5f);
  EXPECT_EQ(m.specularColor, glm::vec3(2.0f, 1.0f, 0.5f)) << "the specular colour may exceed 1 (it scales F0)";
  for (const std::string& w : scene.warnings) EXPECT_EQ(w.find("ignored"), std::string::npos) << w;
}

// An 8x8 texture of distinct colours, sampled nearest and repeated.
void addChecker(Scene& scene) {
  Image img{"checker", 8, 8, {}};
  for (uint32_t i = 0; i < 64; ++i) {
    const uint8_t c[4] = {uint8_t(37 * i % 256), uint8_t(91 * i % 256), uint8_t(173 * i % 256), 255};
    img.rgba.insert(img.rgba.end(), c, c + 4);
  }
  scene.images.push_back(img);
  Sampler nearest;
  nearest.magLinear = nearest.minLinear = nearest.mipLinear = false;
  scene.samplers.push_back(nearest);
}

// Seen from above: on the right a textured floor quad (unlit: the texture's colour on screen,
// drawn by the raster), on the left a mirror showing a textured quad that hangs above the
// camera facing down (shaded at the tracer's hits). `viaTexture`: the texture carries the
// transform; else the quads' UVs do.
Scene transformScene(bool viaTexture, bool transform = true) {
  const glm::vec2 offset(0.25f, 0.1f), scale(2.0f, 0.5f);
  const float rotation = 0.4f;
  Scene scene;
  addChecker(scene);
  Texture t{0, 0};
  if (viaTexture && transform) {
    const glm::mat3 translate(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
    const glm::mat3 rotate(std::cos(rotation), std::sin(rotation), 0, -std::sin(rotation), std::cos(rotation), 0, 0, 0, 1);
    const glm::mat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
    t.uvTransform = translate * rotate * scaling;
  }
  scene.textures.push_back(t);
  Material unlit;
  unlit.unlit = true;
  unlit.baseColorTexture = 0;
  auto textured = [&](float half) {
    Mesh m = test::texturedQuad(half);
    if (!viaTexture && transform)
      for (Vertex& v : m.vertices) v.uv = specTransform(v.uv, offset, rotation, scale);
    return m;
  };
  test::addObject(scene, textured(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)), unlit);
  const glm::mat4 overhead = glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f, 10.0f, 0.0f)) * glm::rotate(glm::mat4(1.0f), glm::pi<float>(), glm::vec3(1, 0, 0));
  test::addObject(scene, textured(6.0f), overhead, unlit);
  test::addObject(scene, test::quad(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0.0f, 0.0f)), test::mirror());
  return scene;
}

FrameImages renderTransformScene(bool viaTexture, bool transform = true) {
  RenderSettings s = test::settingsFor(Policy::All, 64, 32);
  s.reflectionProbes = false;
  s.screenSpaceReflections = false;
  Renderer renderer(transformScene(viaTexture, transform), s);
  Camera cam;
  cam.position = {0.0f, 5.0f, 0.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  cam.up = {0.0f, 0.0f, -1.0f};
  cam.yfov = 0.45f;
  test::renderStill(renderer, cam, 1);
  FrameImages img = renderer.readback();
  test::expectValidationClean(renderer.validationMessages());
  return img;
}

// The same texture seen through its KHR_texture_transform and through UVs transformed on the
// CPU: the raster's and the tracer's pixels agree (the transform is affine, so transforming
// before or after interpolation is the same).
TEST(MaterialLayers, TextureTransformAppliesInTheRasterAndTheTracer) {
  const FrameImages viaTexture = renderTransformScene(true), viaUvs = renderTransformScene(false);
  const FrameImages untransformed = renderTransformScene(true, false);
  size_t floorPixels = 0, mirrorPixels = 0, differ = 0, changed = 0;
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 64; ++x) {
      const uint32_t id = viaTexture.objectIds[y * 64 + x];
      if (id == 0xFFFFFFFFu) continue;
      (id == 0 ? floorPixels : mirrorPixels) += 1;
      const glm::vec3 a = hdr(viaTexture, x, y), b = hdr(viaUvs, x, y), c = hdr(untransformed, x, y);
      differ += glm::length(a - b) > 0.02f;
      changed += glm::length(a - c) > 0.02f;
    }
  ASSERT_GT(floorPixels, 100u);
  ASSERT_GT(mirrorPixels, 100u) << "the mirror shows the quad above";
  // Nearest sampling at a texel edge may round either way for a handful of pixels.
  EXPECT_LE(differ, (floorPixels + mirrorPixels) / 50) << "pixels where the texture's transform and the transformed UVs disagree";
  EXPECT_GT(changed, (floorPixels + mirrorPixels) / 4) << "the transform changes what is shown";
}

// The radiance at the centre of a 17x17 frame of `scene` lit by one directional light
// travelling along `sunTravel` (no sky, probes or screen-space reflections), from a narrow
// camera at `position` looking at `target` with -z up on screen; the centre pixel must show
// object `centreObject`. An odd size: the centre pixel looks along the axis, so its view
// direction is the same seen directly and in a mirror (which flips the screen's x).
glm::vec3 centreRadiance(Scene scene, glm::vec3 sunTravel, Policy policy, glm::vec3 position, glm::vec3 target, uint32_t centreObject) {
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(sunTravel);
  sun.intensity = 3.0f;
  scene.lights.push_back(sun);
  RenderSettings s = test::settingsFor(policy, 17, 17);
  s.skyIntensity = 0.0f;
  s.reflectionProbes = false;
  s.screenSpaceReflections = false;
  Renderer renderer(scene, s);
  Camera cam;
  cam.position = position;
  cam.target = target;
  cam.up = {0.0f, 0.0f, -1.0f};
  cam.yfov = 0.1f;
  test::renderStill(renderer, cam, 1);
  const FrameImages img = renderer.readback();
  test::expectValidationClean(renderer.validationMessages());
  EXPECT_EQ(img.objectIds[8 * 17 + 8], centreObject);
  return hdr(img, 8, 8);
}

// A quad carrying `layered` faces down at y = 10 (turned by `tilt` about z), lit from below by
// a directional light;
// `mirrored`: seen in a small mirror at the origin from 5 above it (the tracer shades the
// quad at the reflected ray's hit), else seen directly from the origin (the deferred
// lighting shades it). The centre pixel sees the same point along the same direction in both.
glm::vec3 layeredQuadRadiance(const Material& layered, float tilt, bool mirrored, glm::vec3 normalMap = {0, 0, 1}) {
  Scene scene;
  const glm::mat4 above = glm::translate(glm::mat4(1.0f), glm::vec3(0, 10, 0)) * glm::rotate(glm::mat4(1.0f), tilt, glm::vec3(0, 0, 1)) *
                          glm::rotate(glm::mat4(1.0f), glm::pi<float>(), glm::vec3(1, 0, 0));
  Material m = layered;
  if (normalMap != glm::vec3(0, 0, 1)) m.normalTexture = test::addFlatNormalMap(scene, normalMap);
  test::addObject(scene, test::texturedQuad(4.0f), above, m);
  if (mirrored) test::addObject(scene, test::quad(0.5f), glm::mat4(1.0f), test::mirror());
  // Travelling up: the mirror's shadow falls 3 units aside.
  return centreRadiance(scene, glm::vec3(0.3f, 1.0f, 0.0f), Policy::All, mirrored ? glm::vec3(0, 5, 0) : glm::vec3(0.0f),
                        mirrored ? glm::vec3(0.0f) : glm::vec3(0, 10, 0), mirrored ? 1u : 0u);
}

struct LayerCase {
  const char* name;
  Material material;
  float tilt;  // the sheen shows towards grazing angles
};

std::vector<LayerCase> layerCases() {
  Material base;
  base.metallic = 0.0f;
  base.roughness = 0.4f;
  base.baseColorFactor = glm::vec4(0.6f, 0.1f, 0.1f, 1.0f);
  Material sheen = base;
  sheen.baseColorFactor = glm::vec4(0.05f, 0.05f, 0.05f, 1.0f);
  sheen.sheenColor = glm::vec3(1.0f, 0.4f, 0.1f);
  sheen.sheenRoughness = 0.5f;
  Material coat = base;
  coat.clearcoat = 1.0f;
  coat.clearcoatRoughness = 0.3f;
  Material specular = base;
  specular.specularColor = glm::vec3(0.5f, 5.0f, 5.0f);  // F0 0.02 red, 0.2 green and blue
  return {{"sheen", sheen, -1.05f}, {"clearcoat", coat, 0.0f}, {"specular", specular, 0.0f}, {"none", base, 0.0f}, {"none", base, -1.05f}};
}

// Each layer shaded by the deferred lighting (from the G-buffer) equals the same layer shaded
// at a traced hit (from the material), and changes the pixel against the bare base.
TEST(MaterialLayers, RasterAndTracedHitsShadeEachLayerAlike) {
  const std::vector<LayerCase> cases = layerCases();
  for (const LayerCase& c : cases) {
    const glm::vec3 raster = layeredQuadRadiance(c.material, c.tilt, false), traced = layeredQuadRadiance(c.material, c.tilt, true);
    ASSERT_GT(raster.r, 0.05f) << c.name << ": the light reaches the quad";
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(traced[k], raster[k], 0.02f * std::max(raster[k], 0.02f))
          << c.name << " channel " << k << ": deferred " << raster[k] << ", traced hit " << traced[k];
    const glm::vec3 bare = layeredQuadRadiance(cases[3].material, c.tilt, false);
    if (std::string(c.name) != "none") {
      EXPECT_GT(glm::length(raster - bare), 0.1f * glm::length(bare)) << c.name << " changes the pixel";
    }
  }
  // The sheen's colour shows at a grazing view over the dark base.
  const glm::vec3 sheen = layeredQuadRadiance(cases[0].material, cases[0].tilt, false);
  EXPECT_GT(sheen.r, 2.0f * sheen.b) << "sheen colour (1, 0.4, 0.1): " << sheen.r << " " << sheen.g << " " << sheen.b;
}


// The raster's radiance at the centre of a diffuse quad facing up (u along +x, v along +z),
// seen from above and lit by a directional light from `towardsLight`, with a normal map
// holding `t` (none when t is +z).
float normalMappedQuadRadiance(glm::vec3 t, glm::vec3 towardsLight) {
  Scene scene;
  Material diffuse;
  diffuse.roughness = 1.0f;
  diffuse.metallic = 0.0f;
  if (t != glm::vec3(0, 0, 1)) diffuse.normalTexture = test::addFlatNormalMap(scene, t);
  test::addObject(scene, test::texturedQuad(4.0f), glm::mat4(1.0f), diffuse);
  return centreRadiance(scene, -towardsLight, Policy::None, glm::vec3(0, 5, 0), glm::vec3(0.0f), 0u).g;
}

// glTF's tangent frame: the map's +X leans the normal towards increasing u, its +Y towards
// decreasing v (the texture's up; glTF's v runs down the image). A light from that side then
// lights the quad more than the flat normal, one from the other side less.
TEST(NormalMap, TheMapsAxesFollowGltfsTangentFrame) {
  const glm::vec3 leanX = glm::normalize(glm::vec3(0.6f, 0.0f, 0.8f)), leanY = glm::normalize(glm::vec3(0.0f, 0.6f, 0.8f));
  struct Case {
    const char* name;
    glm::vec3 t, towards;  // the light's side: world +x is increasing u, world -z decreasing v
  };
  for (const Case& c : {Case{"+X towards +u", leanX, {1, 1, 0}}, Case{"+Y towards -v", leanY, {0, 1, -1}}}) {
    const float flat = normalMappedQuadRadiance({0, 0, 1}, c.towards);
    const float towards = normalMappedQuadRadiance(c.t, c.towards);
    const float away = normalMappedQuadRadiance(c.t, glm::vec3(-c.towards.x, c.towards.y, -c.towards.z));
    ASSERT_GT(flat, 0.05f) << c.name;
    // N.L: 0.99 leaning towards the light, 0.71 flat, 0.14 leaning away.
    EXPECT_NEAR(towards / flat, 0.99f / 0.707f, 0.08f) << c.name;
    EXPECT_NEAR(away / flat, 0.141f / 0.707f, 0.08f) << c.name;
  }
}

// A normal-mapped quad shades alike seen directly (the deferred lighting of the G-buffer's
// perturbed normal) and in a mirror (the tracer's hit, its frame from the triangle's edges),
// and the map changes it.
TEST(NormalMap, RasterAndTracedHitsPerturbTheNormalAlike) {
  Material base = layerCases()[3].material;
  Material mapped = base;
  for (const glm::vec3 t : {glm::vec3(0.6f, 0.0f, 0.8f), glm::vec3(0.0f, -0.6f, 0.8f), glm::vec3(-0.48f, 0.36f, 0.8f)}) {
    const glm::vec3 raster = layeredQuadRadiance(mapped, 0.0f, false, t), traced = layeredQuadRadiance(mapped, 0.0f, true, t);
    const glm::vec3 bare = layeredQuadRadiance(base, 0.0f, false);
    ASSERT_GT(raster.r, 0.02f);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(traced[k], raster[k], 0.02f * std::max(raster[k], 0.02f))
          << "t " << t.x << " " << t.y << " channel " << k << ": deferred " << raster[k] << ", traced hit " << traced[k];
    EXPECT_GT(glm::length(raster - bare), 0.1f * glm::length(bare)) << "the map changes the pixel";
  }
}

}  // namespace
}  // namespace raybudget
