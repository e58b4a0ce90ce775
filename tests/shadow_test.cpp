// Raster shadow fallbacks: for each light type, a box between the light and a ground plane
// darkens exactly the ground point the geometry says is occluded, and leaves lit ground
// smooth (no acne); alpha-masked casters mask as the G-buffer and the rays do. The sky is
// off, so a shadowed point receives no light at all.
#include <cstring>

#include <gtest/gtest.h>

#include "support/gltf_fixture.h"
#include "support/procedural.h"
#include "support/render_helpers.h"
#include "support/test_scenes.h"

namespace raybudget {
namespace {

constexpr uint32_t kW = 256, kH = 192;

float halfToFloat(uint16_t h) {
  const uint32_t exponent = (h >> 10) & 0x1F, mantissa = h & 0x3FF;
  if (exponent == 0) return std::ldexp(float(mantissa), -24);
  const uint32_t bits = (uint32_t(h >> 15) << 31) | ((exponent + 112) << 23) | (mantissa << 13);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// Ground plane 20x20 at y=0 and a unit box floating at y in [1, 2] above the origin.
Scene groundAndBox(const std::string& name) {
  std::vector<glm::vec3> p = {{-10, 0, -10}, {10, 0, -10}, {10, 0, 10}, {-10, 0, 10}};
  std::vector<uint32_t> idx = {0, 2, 1, 0, 3, 2};
  const glm::vec3 lo(-0.5f, 1.0f, -0.5f), hi(0.5f, 2.0f, 0.5f);
  for (int c = 0; c < 8; ++c) p.push_back({(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z});
  const uint32_t faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (const auto& f : faces) idx.insert(idx.end(), {4 + f[0], 4 + f[1], 4 + f[2], 4 + f[0], 4 + f[2], 4 + f[3]});
  const auto dir = test::freshTempDir("shadow-" + name);
  return loadScene(test::GltfFixture::triangles(p, idx).write(dir, "scene"));
}

struct ShadowProbe {
  float shadowed;  // HDR luminance at the occluded ground point
  float lit;       // at a ground point the box cannot occlude
  float litRoughness;  // max |L - mean of its horizontal neighbours| / L over a 5x5 patch
};

ShadowProbe probe(Scene scene, const Light& light, const glm::vec3& occluded, const glm::vec3& open) {
  scene.lights = {light};
  scene.usesDefaultSun = false;
  RenderSettings settings;
  settings.width = kW;
  settings.height = kH;
  settings.validation = true;
  settings.skyIntensity = 0.0f;
  Renderer renderer(scene, settings);
  Camera cam;
  cam.position = {7.0f, 5.0f, 7.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  cam.znear = 0.1f;
  cam.zfar = 50.0f;
  renderer.render(cam);
  renderer.finish();
  const FrameImages img = renderer.readback();
  test::expectValidationClean(renderer.validationMessages());
  const glm::mat4 vp = cam.projection(renderer.aspect()) * cam.view();
  auto luminanceAt = [&](const glm::vec3& world, int dx, int dy) {
    const glm::vec4 c = vp * glm::vec4(world, 1.0f);
    const int x = int((c.x / c.w * 0.5f + 0.5f) * kW) + dx, y = int((c.y / c.w * 0.5f + 0.5f) * kH) + dy;
    EXPECT_TRUE(x >= 0 && y >= 0 && x < int(kW) && y < int(kH));
    const size_t i = (size_t(y) * kW + size_t(x)) * 4;
    return 0.2126f * halfToFloat(img.hdrRgba16[i]) + 0.7152f * halfToFloat(img.hdrRgba16[i + 1]) + 0.0722f * halfToFloat(img.hdrRgba16[i + 2]);
  };
  ShadowProbe r{luminanceAt(occluded, 0, 0), luminanceAt(open, 0, 0), 0.0f};
  // Acne is high-frequency: a second difference, which ignores the smooth falloff of light.
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      const float l = luminanceAt(open, dx, dy);
      const float neighbours = 0.5f * (luminanceAt(open, dx - 1, dy) + luminanceAt(open, dx + 1, dy));
      r.litRoughness = std::max(r.litRoughness, std::fabs(l - neighbours) / l);
    }
  return r;
}

void expectShadow(const ShadowProbe& p) {
  EXPECT_GT(p.lit, 0.01f);
  EXPECT_LT(p.shadowed, 0.02f * p.lit) << "the occluded point is lit";
  EXPECT_LT(p.litRoughness, 0.02f) << "lit ground is not smooth: acne";
}

TEST(ShadowMaps, DirectionalLightShadowsTheGroundUnderTheBox) {
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.0f;
  sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  expectShadow(probe(groundAndBox("dir"), sun, {0.0f, 0.0f, 0.0f}, {3.0f, 0.0f, -3.0f}));
}

TEST(ShadowMaps, SpotLightShadowsTheGroundUnderTheBox) {
  Light spot;
  spot.type = LightType::Spot;
  spot.intensity = 60.0f;
  spot.position = {0.0f, 6.0f, 0.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.innerConeAngle = 0.6f;
  spot.outerConeAngle = 0.8f;
  expectShadow(probe(groundAndBox("spot"), spot, {0.0f, 0.0f, 0.0f}, {2.5f, 0.0f, -2.5f}));
}

TEST(ShadowMaps, PointLightShadowsTheGroundUnderTheBox) {
  Light point;
  point.type = LightType::Point;
  point.intensity = 60.0f;
  point.position = {0.0f, 5.0f, 0.0f};
  expectShadow(probe(groundAndBox("point"), point, {0.0f, 0.0f, 0.0f}, {3.0f, 0.0f, -3.0f}));
  // Off-axis: the light beside the box throws its shadow along +x, through the +x cube face.
  point.position = {-2.0f, 2.5f, 0.0f};
  expectShadow(probe(groundAndBox("point2"), point, {2.0f, 0.0f, 0.0f}, {-2.0f, 0.0f, 3.0f}));
}

// An alpha-masked caster cut out by its vertex colours' alpha (COLOR_0, which the G-buffer and
// the tracer multiply into the base colour's alpha as glTF says) casts no shadow map shadow
// either: the raster fallback and the traced shadows agree.
// A diffuse ground 20x20 at y = 0 and a 2x2 caster 1.5 above its centre.
Scene groundAndCaster(const Material& material, float vertexAlpha) {
  Scene scene = test::sceneWithMesh(test::quad(10.0f));
  scene.materials[0].metallic = 0.0f;
  Mesh caster = test::quad(1.0f);
  for (Vertex& v : caster.vertices) v.color.a = vertexAlpha;
  test::addObject(scene, caster, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.5f, 0.0f)), material);
  return scene;
}

TEST(ShadowMaps, AVertexAlphaCutOutCasterCastsNoShadow) {
  Material cutOut;
  cutOut.metallic = 0.0f;
  cutOut.alphaMode = AlphaMode::Mask;
  cutOut.alphaCutoff = 0.5f;
  cutOut.doubleSided = true;
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.0f;
  sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  const ShadowProbe p = probe(groundAndCaster(cutOut, 0.0f), sun, {0.0f, 0.0f, 0.0f}, {3.0f, 0.0f, -3.0f});
  EXPECT_GT(p.lit, 0.01f);
  EXPECT_GT(p.shadowed, 0.98f * p.lit) << "the cut-out caster shadows the ground in the shadow map";
  // With opaque vertex colours the same caster shadows it.
  expectShadow(probe(groundAndCaster(cutOut, 1.0f), sun, {0.0f, 0.0f, 0.0f}, {3.0f, 0.0f, -3.0f}));
}

// Luminance of `img` (HDR) averaged over the (2r+1)^2 pixels around the projection of `world`.
float meanLuminance(const FrameImages& img, const glm::mat4& viewProj, const glm::vec3& world, int r) {
  const glm::vec4 c = viewProj * glm::vec4(world, 1.0f);
  const int cx = int((c.x / c.w * 0.5f + 0.5f) * float(img.width)), cy = int((c.y / c.w * 0.5f + 0.5f) * float(img.height));
  double sum = 0.0;
  for (int y = cy - r; y <= cy + r; ++y)
    for (int x = cx - r; x <= cx + r; ++x) {
      const size_t i = (size_t(y) * img.width + size_t(x)) * 4;
      sum += 0.2126f * halfToFloat(img.hdrRgba16[i]) + 0.7152f * halfToFloat(img.hdrRgba16[i + 1]) + 0.0722f * halfToFloat(img.hdrRgba16[i + 2]);
    }
  return float(sum / double((2 * r + 1) * (2 * r + 1)));
}

// A caster masked by a fine alpha texture (one opaque column in four, finer than a shadow-map
// texel): the shadow map's alpha test samples its finest level as the rays' does, so the
// fallback's shadow under it is about as dark as the traced one. At the level the light's view
// picks the columns average to alpha 0.25, under the cut-off: no shadow at all.
TEST(ShadowMaps, AFinelyMaskedCasterShadowsAsTheRaysSeeIt) {
  Material masked;
  masked.metallic = 0.0f;
  masked.alphaMode = AlphaMode::Mask;
  masked.alphaCutoff = 0.5f;
  masked.doubleSided = true;
  masked.baseColorTexture = 0;
  Scene scene = groundAndCaster(masked, 1.0f);
  Image stripes{"stripes", 256, 4, std::vector<uint8_t>(256 * 4 * 4, 255)};
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 256; ++x) stripes.rgba[(y * 256 + x) * 4 + 3] = x % 4 == 0 ? 255 : 0;
  scene.images.push_back(stripes);
  scene.textures.push_back(Texture{0, -1});
  Mesh& caster = scene.meshes.back();
  for (Vertex& v : caster.vertices) v.uv = glm::vec2(v.position.x > 0.0f ? 1.0f : 0.0f, v.position.z > 0.0f ? 1.0f : 0.0f);
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.0f;
  sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  scene.lights = {sun};
  scene.usesDefaultSun = false;
  Camera cam;
  cam.position = {7.0f, 5.0f, 7.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  float under[2], open[2];
  for (int traced = 0; traced < 2; ++traced) {
    RenderSettings settings;
    settings.width = kW;
    settings.height = kH;
    settings.validation = true;
    settings.skyIntensity = 0.0f;
    settings.policy = traced ? Policy::All : Policy::None;
    Renderer renderer(scene, settings);
    renderer.render(cam);
    renderer.finish();
    const FrameImages img = renderer.readback();
    test::expectValidationClean(renderer.validationMessages());
    const glm::mat4 vp = cam.projection(renderer.aspect()) * cam.view();
    under[traced] = meanLuminance(img, vp, {0.3f, 0.0f, -0.3f}, 4);
    open[traced] = meanLuminance(img, vp, {3.0f, 0.0f, -3.0f}, 4);
  }
  const float tracedShade = 1.0f - under[1] / open[1], mapShade = 1.0f - under[0] / open[0];
  EXPECT_GT(tracedShade, 0.1f) << "the rays see no shadow under the masked caster";
  EXPECT_NEAR(mapShade, tracedShade, 0.5f * tracedShade) << "shadow map shade " << mapShade << ", traced " << tracedShade;
}

}  // namespace
}  // namespace raybudget
