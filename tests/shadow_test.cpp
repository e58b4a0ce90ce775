// Raster shadow fallbacks: for each light type, a box between the light and a ground plane
// darkens exactly the ground point the geometry says is occluded, and leaves lit ground
// smooth (no acne); alpha-masked casters mask as the G-buffer and the rays do. The sky is
// off, so a shadowed point receives no light at all.
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

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

// The ground seen from above one corner, lit by `light` alone (no sky), with `policy`.
struct GroundView {
  FrameImages img;
  glm::mat4 viewProj;
};

GroundView renderGround(Scene scene, const Light& light, Policy policy = Policy::None, const RenderSettings& base = {}) {
  scene.lights = {light};
  scene.usesDefaultSun = false;
  RenderSettings settings = base;
  settings.width = kW;
  settings.height = kH;
  settings.validation = true;
  settings.skyIntensity = 0.0f;
  settings.policy = policy;
  Renderer renderer(scene, settings);
  Camera cam;
  cam.position = {7.0f, 5.0f, 7.0f};
  cam.target = {0.0f, 0.0f, 0.0f};
  cam.znear = 0.1f;
  cam.zfar = 50.0f;
  renderer.render(cam);
  renderer.finish();
  GroundView v{renderer.readback(), cam.projection(renderer.aspect()) * cam.view()};
  test::expectValidationClean(renderer.validationMessages());
  return v;
}

// HDR luminance at the pixel (dx, dy) away from where `world` projects.
float luminanceAt(const GroundView& v, const glm::vec3& world, int dx, int dy) {
  const glm::vec4 c = v.viewProj * glm::vec4(world, 1.0f);
  const int x = int((c.x / c.w * 0.5f + 0.5f) * kW) + dx, y = int((c.y / c.w * 0.5f + 0.5f) * kH) + dy;
  EXPECT_TRUE(x >= 0 && y >= 0 && x < int(kW) && y < int(kH));
  const size_t i = (size_t(y) * kW + size_t(x)) * 4;
  const std::vector<uint16_t>& hdr = v.img.hdrRgba16;
  return 0.2126f * halfToFloat(hdr[i]) + 0.7152f * halfToFloat(hdr[i + 1]) + 0.0722f * halfToFloat(hdr[i + 2]);
}

// Averaged over the (2r+1)^2 pixels around where `world` projects.
float meanLuminance(const GroundView& v, const glm::vec3& world, int r) {
  double sum = 0.0;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) sum += luminanceAt(v, world, dx, dy);
  return float(sum / double((2 * r + 1) * (2 * r + 1)));
}

ShadowProbe probe(Scene scene, const Light& light, const glm::vec3& occluded, const glm::vec3& open, const RenderSettings& base = {}) {
  const GroundView v = renderGround(std::move(scene), light, Policy::None, base);
  ShadowProbe r{luminanceAt(v, occluded, 0, 0), luminanceAt(v, open, 0, 0), 0.0f};
  // Acne is high-frequency: a second difference, which ignores the smooth falloff of light.
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      const float l = luminanceAt(v, open, dx, dy);
      const float neighbours = 0.5f * (luminanceAt(v, open, dx - 1, dy) + luminanceAt(v, open, dx + 1, dy));
      r.litRoughness = std::max(r.litRoughness, std::fabs(l - neighbours) / l);
    }
  return r;
}

void expectShadow(const ShadowProbe& p) {
  EXPECT_GT(p.lit, 0.01f);
  EXPECT_LT(p.shadowed, 0.02f * p.lit) << "the occluded point is lit";
  EXPECT_LT(p.litRoughness, 0.02f) << "lit ground is not smooth: acne";
}

Light overheadSun() {
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.0f;
  sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  return sun;
}

TEST(ShadowMaps, DirectionalLightShadowsTheGroundUnderTheBox) {
  const Light sun = overheadSun();
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

// The biases against acne are settings that reach the shadow pass and the lookups: under a
// low sun the ground stays smooth with the defaults, and acne covers it with both at zero.
TEST(ShadowMaps, WithoutItsBiasesALowSunAcnesTheGround) {
  Light low = overheadSun();
  low.direction = glm::normalize(glm::vec3(-0.8f, -0.6f, 0.0f));
  const glm::vec3 occluded(-2.0f, 0.0f, 0.0f), open(3.0f, 0.0f, -3.0f);  // the box's shadow lies along -x
  expectShadow(probe(groundAndBox("low"), low, occluded, open));
  RenderSettings unbiased;
  unbiased.shadowNormalOffset = 0.0f;
  unbiased.shadowSlopeBias = 0.0f;
  EXPECT_GT(probe(groundAndBox("low0"), low, occluded, open, unbiased).litRoughness, 0.1f) << "no acne without the biases";
}

// The shadow classifier (`classified`, shadows only) at a reach of 4 texels, on a smooth
// sphere resting on the ground under a low and a high sun, a spot and a point light: it traces
// only about the sphere's shadow edges and terminator, and the image is full RT's. Its depth
// tests out at the reach compare against the point's triangle plane there; against the point's
// own depth, as the lighting pass's taps are, they sank below the slanted ground and the
// curved sphere and called 33-97% of the pixels uncertain.
TEST(ShadowMaps, TheClassifierFindsLitSlantsAndCurvesCertain) {
  auto sun = [](float elevationDegrees) {
    const float e = glm::radians(elevationDegrees), a = glm::radians(30.0f);
    Light l = overheadSun();
    l.direction = -glm::vec3(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
    return l;
  };
  Light spot;
  spot.type = LightType::Spot;
  spot.intensity = 80.0f;
  spot.position = {-5.0f, 3.0f, 1.5f};
  spot.direction = glm::normalize(glm::vec3(5.0f, -2.5f, -1.5f));
  spot.outerConeAngle = 0.9f;
  spot.innerConeAngle = 0.7f;
  Light point;
  point.type = LightType::Point;
  point.intensity = 60.0f;
  point.position = {-3.0f, 2.5f, 1.0f};
  const std::pair<Light, const char*> lights[] = {{sun(20.0f), "low sun"}, {sun(60.0f), "high sun"}, {spot, "spot"}, {point, "point"}};
  for (const auto& [light, name] : lights) {
    Scene scene = test::sceneWithMesh(test::quad(10.0f));
    scene.materials[0].metallic = 0.0f;
    Material diffuse;
    diffuse.metallic = 0.0f;
    test::addObject(scene, test::icosphere(3), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f)), diffuse);
    scene.lights = {light};
    scene.usesDefaultSun = false;
    RenderSettings s = test::settingsFor(Policy::Classified, kW, kH);
    s.skyIntensity = 0.0f;
    s.rayTracing.reflections = false;
    s.rayTracing.refractions = false;
    s.rayTracing.shadowUncertaintyTexels = 4.0f;
    Camera cam;
    cam.position = {4.0f, 3.0f, 4.0f};
    cam.target = {0.0f, 0.5f, 0.0f};
    cam.znear = 0.1f;
    cam.zfar = 50.0f;
    const test::ClassifierFrame c = test::classifierAgainstFullRt(scene, s, cam);
    EXPECT_GT(c.rays, 0u) << name << ": no shadow edge found uncertain";
    EXPECT_LT(c.rays, c.fullRays / 10) << name << ": lit ground or sphere found uncertain";
    EXPECT_GT(c.fallback, 0.0) << name;
    EXPECT_LE(c.kept, 0.01 * c.fallback) << name << ": classified " << c.kept << " against the maps' " << c.fallback;
  }
}

TEST(ShadowMaps, AbsurdBiasesAreRefusedNamingTheSetting) {
  const Scene scene = groundAndBox("bad-bias");
  for (float v : {-1.0f, 17.0f, NAN, INFINITY}) {
    RenderSettings offset, slope;
    offset.shadowNormalOffset = v;
    slope.shadowSlopeBias = v;
    for (const auto& [settings, name] : {std::pair{offset, "shadowNormalOffset"}, std::pair{slope, "shadowSlopeBias"}}) {
      try {
        Renderer renderer(scene, settings);
        ADD_FAILURE() << name << " = " << v << " accepted";
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      }
    }
  }
}

// A diffuse ground 20x20 at y = 0 and a 2x2 caster 1.5 above its centre.
Scene groundAndCaster(const Material& material, float vertexAlpha) {
  Scene scene = test::sceneWithMesh(test::quad(10.0f));
  scene.materials[0].metallic = 0.0f;
  Mesh caster = test::quad(1.0f);
  for (Vertex& v : caster.vertices) v.color.a = vertexAlpha;
  test::addObject(scene, caster, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.5f, 0.0f)), material);
  return scene;
}

// A diffuse, double-sided, alpha-masked material (cut-off 0.5).
Material maskedMaterial() {
  Material m;
  m.metallic = 0.0f;
  m.alphaMode = AlphaMode::Mask;
  m.alphaCutoff = 0.5f;
  m.doubleSided = true;
  return m;
}

// An alpha-masked caster cut out by its vertex colours' alpha (COLOR_0, which the G-buffer and
// the tracer multiply into the base colour's alpha as glTF says) casts no shadow map shadow
// either: the raster fallback and the traced shadows agree.
TEST(ShadowMaps, AVertexAlphaCutOutCasterCastsNoShadow) {
  const ShadowProbe p = probe(groundAndCaster(maskedMaterial(), 0.0f), overheadSun(), {0.0f, 0.0f, 0.0f}, {3.0f, 0.0f, -3.0f});
  EXPECT_GT(p.lit, 0.01f);
  EXPECT_GT(p.shadowed, 0.98f * p.lit) << "the cut-out caster shadows the ground in the shadow map";
  // With opaque vertex colours the same caster shadows it.
  expectShadow(probe(groundAndCaster(maskedMaterial(), 1.0f), overheadSun(), {0.0f, 0.0f, 0.0f}, {3.0f, 0.0f, -3.0f}));
}

// A caster masked by a fine alpha texture (one opaque column in four, finer than a shadow-map
// texel): the shadow map's alpha test samples its finest level as the rays' does, so the
// fallback's shadow under it is about as dark as the traced one. At the level the light's view
// picks the columns average to alpha 0.25, under the cut-off: no shadow at all.
TEST(ShadowMaps, AFinelyMaskedCasterShadowsAsTheRaysSeeIt) {
  Material masked = maskedMaterial();
  masked.baseColorTexture = 0;
  Scene scene = groundAndCaster(masked, 1.0f);
  Image stripes{"stripes", 256, 4, std::vector<uint8_t>(256 * 4 * 4, 255)};
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 256; ++x) stripes.rgba[(y * 256 + x) * 4 + 3] = x % 4 == 0 ? 255 : 0;
  scene.images.push_back(stripes);
  scene.textures.push_back(Texture{0, -1});
  Mesh& caster = scene.meshes.back();
  for (Vertex& v : caster.vertices) v.uv = glm::vec2(v.position.x > 0.0f ? 1.0f : 0.0f, v.position.z > 0.0f ? 1.0f : 0.0f);
  float shade[2];  // raster, traced: 1 - luminance under the caster / on open ground
  for (int traced = 0; traced < 2; ++traced) {
    const GroundView v = renderGround(scene, overheadSun(), traced ? Policy::All : Policy::None);
    shade[traced] = 1.0f - meanLuminance(v, {0.3f, 0.0f, -0.3f}, 4) / meanLuminance(v, {3.0f, 0.0f, -3.0f}, 4);
  }
  const float mapShade = shade[0], tracedShade = shade[1];
  EXPECT_GT(tracedShade, 0.1f) << "the rays see no shadow under the masked caster";
  EXPECT_NEAR(mapShade, tracedShade, 0.5f * tracedShade) << "shadow map shade " << mapShade << ", traced " << tracedShade;
}

}  // namespace
}  // namespace raybudget
