#include "passes/scene_gpu.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "raybudget/error.h"
#include "scene/triangles.h"
#include "shared/config.h"

namespace raybudget::passes {
namespace {

static_assert(sizeof(gpu::GpuVertex) == 48);
static_assert(sizeof(gpu::GpuObject) == 160);
static_assert(sizeof(gpu::GpuMaterial) == 176);
static_assert(sizeof(gpu::GpuTextureTransform) == 32);
static_assert(sizeof(gpu::GpuLight) == 144);
static_assert(sizeof(gpu::FrameUniforms) == 352 + 3 * 16 * RB_MAX_PROBES + 112);
static_assert(sizeof(gpu::DrawPush) == 80);

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

VkSamplerAddressMode addressMode(int gltfWrap) {
  switch (gltfWrap) {
    case 33071: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case 33648: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    default: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
  }
}

vk::Owned<VkSampler> makeSampler(const vk::Context& ctx, const Sampler& s) {
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = s.magLinear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  ci.minFilter = s.minLinear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  ci.mipmapMode = s.mipLinear ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  ci.addressModeU = addressMode(s.wrapS);
  ci.addressModeV = addressMode(s.wrapT);
  ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  ci.maxLod = VK_LOD_CLAMP_NONE;
  return vk::createSampler(ctx, ci);
}

vk::Image makeTextureImage(const vk::Context& ctx, const Image& img, bool srgb) {
  vk::ImageDesc d;
  d.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  d.width = img.width;
  d.height = img.height;
  d.mips = uint32_t(std::floor(std::log2(float(std::max(img.width, img.height))))) + 1;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  vk::Image image = vk::createImage(ctx, d);
  vk::uploadTexture(ctx, image, img.rgba);
  return image;
}

glm::vec3 anyPerpendicular(const glm::vec3& d) { return std::fabs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0); }

float farthestCorner(const Scene& scene, const glm::vec3& p) {
  float far = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? scene.boundsMax.x : scene.boundsMin.x, (c & 2) ? scene.boundsMax.y : scene.boundsMin.y,
                           (c & 4) ? scene.boundsMax.z : scene.boundsMin.z);
    far = std::max(far, glm::length(corner - p));
  }
  return far;
}

// Fills each light's shadow parameters and the views the shadow pass renders.
void placeShadows(const Scene& scene, const RenderSettings& settings, std::vector<gpu::GpuLight>& lights, ShadowViews& views) {
  const glm::vec3 center = 0.5f * (scene.boundsMin + scene.boundsMax);
  const float radius = std::max(0.5f * glm::length(scene.boundsMax - scene.boundsMin), 1e-3f);
  const float mapSize = float(settings.shadowMapSize);
  const float cubeSize = float(std::max(settings.shadowMapSize / 2, 16u));
  const float offset = settings.shadowNormalOffset;
  std::vector<ShadowFit> cubeFits;  // listed after every layer's
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    gpu::GpuLight& g = lights[i];
    if (l.type == LightType::Directional) {
      // Orthographic box around the scene's bounding sphere.
      const glm::mat4 view = glm::lookAt(center - l.direction * radius * 2.0f, center, anyPerpendicular(l.direction));
      const glm::mat4 proj = glm::orthoRH_ZO(-radius, radius, -radius, radius, radius * 0.5f, radius * 3.5f);
      g.shadowViewProj = proj * view;
      g.shadowParams = glm::vec4(2.0f * radius / mapSize, radius * 0.5f, radius * 3.5f, offset);
      g.spotShadow.z = float(views.mapLayers++);
      views.mapViewProj.push_back(g.shadowViewProj);
      views.fit.push_back({uint32_t(i), glm::vec4(center, -1.0f), g.shadowParams.x});
    } else {
      const float far = l.range > 0.0f ? l.range : farthestCorner(scene, l.position) * 1.01f;
      const float near = std::max(far * 1e-4f, 1e-3f);
      if (l.type == LightType::Spot) {
        const float fov = std::min(2.0f * l.outerConeAngle + 0.05f, 3.0f);
        const glm::mat4 view = glm::lookAt(l.position, l.position + l.direction, anyPerpendicular(l.direction));
        g.shadowViewProj = glm::perspectiveRH_ZO(fov, 1.0f, near, far) * view;
        g.shadowParams = glm::vec4(2.0f * std::tan(0.5f * fov) / mapSize, near, far, offset);
        g.spotShadow.z = float(views.mapLayers++);
        views.mapViewProj.push_back(g.shadowViewProj);
        views.fit.push_back({uint32_t(i), glm::vec4(l.position, far), g.shadowParams.x});
      } else {
        // Cube faces in Vulkan order +X -X +Y -Y +Z -Z, with the up vectors that make the
        // rendered faces match cube-map addressing (no y flip).
        static const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
        const glm::mat4 proj = glm::perspectiveRH_ZO(glm::half_pi<float>(), 1.0f, near, far);
        for (int f = 0; f < 6; ++f) views.cubeFaceViewProj.push_back(proj * glm::lookAt(l.position, l.position + dirs[f], ups[f]));
        g.shadowParams = glm::vec4(2.0f / cubeSize, near, far, offset);
        g.spotShadow.z = float(views.pointCubes++);
        cubeFits.push_back({uint32_t(i), glm::vec4(l.position, far), g.shadowParams.x});
      }
    }
  }
  views.fit.insert(views.fit.end(), cubeFits.begin(), cubeFits.end());
}

// Whether the mesh's thin-walled transmissive triangles close a shell: a view ray through one
// of them leaves through another, as the tracer's does (env_fallback.glsl's far wall). An
// alpha-masked shell has holes where its far wall may be cut away: not closed.
bool closedThinGlass(const Scene& scene, const Mesh& m) {
  std::vector<uint32_t> glass;
  for (const Primitive& p : m.primitives) {
    const Material& mat = scene.materials[size_t(p.material)];
    if (mat.alphaMode == AlphaMode::Mask) return false;
    if (mat.transmission > 0.0f && mat.thickness <= 0.0f)
      glass.insert(glass.end(), m.indices.begin() + p.firstIndex, m.indices.begin() + p.firstIndex + p.indexCount);
  }
  if (glass.empty()) return false;
  std::vector<glm::vec3> positions;
  positions.reserve(m.vertices.size());
  for (const Vertex& v : m.vertices) positions.push_back(v.position);
  return closedSurface(positions, glass);
}

}  // namespace

gpu::GpuObject gpuObject(const SceneGpu& scene, const Object& o) {
  gpu::GpuObject g{};
  g.model = o.transform;
  g.normalMatrix = glm::mat4(glm::inverseTranspose(glm::mat3(o.transform)));
  const glm::vec3 c = 0.5f * (o.boundsMin + o.boundsMax);
  g.boundsCenterRadius = glm::vec4(c, 0.5f * glm::length(o.boundsMax - o.boundsMin));
  g.ids = glm::uvec4(o.id, scene.meshFirstIndex[o.mesh], scene.meshVertexOffset[o.mesh],
                     scene.meshClosedThinGlass[o.mesh] ? RB_OBJECT_CLOSED_THIN_GLASS : 0u);
  return g;
}

SceneGpu uploadScene(const vk::Context& ctx, const Scene& scene, const RenderSettings& settings) {
  SceneGpu gpu;
  std::vector<uint32_t>& meshFirstIndex = gpu.meshFirstIndex;
  std::vector<uint32_t>& meshVertexOffset = gpu.meshVertexOffset;

  // Geometry: all meshes in one vertex and one index buffer; draws address them by offset.
  std::vector<gpu::GpuVertex> vertices;
  std::vector<uint32_t> indices;
  for (const Mesh& m : scene.meshes) {
    meshFirstIndex.push_back(uint32_t(indices.size()));
    meshVertexOffset.push_back(uint32_t(vertices.size()));
    for (const Vertex& v : m.vertices)
      vertices.push_back({glm::vec4(v.position, v.uv.x), glm::vec4(v.normal, v.uv.y), v.color});
    indices.insert(indices.end(), m.indices.begin(), m.indices.end());
    gpu.meshClosedThinGlass.push_back(closedThinGlass(scene, m));
  }
  gpu.vertices = vk::createDeviceBuffer(ctx, vertices, kStorage);
  gpu.indices = vk::createDeviceBuffer(ctx, indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT | kStorage);

  // Textures: one GPU image per (image, colour space) actually used, and one slot per
  // (texture, colour space) with its sampler and UV transform.
  gpu.samplers.push_back(makeSampler(ctx, Sampler{}));
  for (const Sampler& s : scene.samplers) gpu.samplers.push_back(makeSampler(ctx, s));
  std::map<std::pair<int, bool>, uint32_t> imageOf;
  std::map<std::pair<int, bool>, int> textureSlot;
  std::vector<gpu::GpuTextureTransform> transforms;
  auto slot = [&](int texture, bool srgb) -> int {
    if (texture < 0) return -1;
    auto it = textureSlot.find({texture, srgb});
    if (it != textureSlot.end()) return it->second;
    const Texture& t = scene.textures[size_t(texture)];
    auto image = imageOf.find({t.image, srgb});
    if (image == imageOf.end()) {
      gpu.textureImages.push_back(makeTextureImage(ctx, scene.images[size_t(t.image)], srgb));
      image = imageOf.emplace(std::pair{t.image, srgb}, uint32_t(gpu.textureImages.size() - 1)).first;
    }
    gpu.textures.push_back({image->second, gpu.samplers[size_t(t.sampler + 1)]});
    const glm::mat3& m = t.uvTransform;
    transforms.push_back({glm::vec4(m[0][0], m[1][0], m[2][0], 0.0f), glm::vec4(m[0][1], m[1][1], m[2][1], 0.0f)});
    return textureSlot[{texture, srgb}] = int(gpu.textures.size() - 1);
  };
  std::vector<gpu::GpuMaterial> materials;
  for (const Material& m : scene.materials) {
    gpu::GpuMaterial g{};
    g.baseColorFactor = m.baseColorFactor;
    g.emissiveAlphaCutoff = glm::vec4(m.emissive, m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : 0.0f);
    g.metallicRoughnessTransmissionIor = glm::vec4(m.metallic, m.roughness, m.transmission, m.ior);
    g.textures = glm::ivec4(slot(m.baseColorTexture, true), slot(m.metallicRoughnessTexture, false), slot(m.normalTexture, false),
                            slot(m.emissiveTexture, true));
    g.attenuationColorDistance = glm::vec4(m.attenuationColor, m.attenuationDistance);
    uint32_t flags = 0;
    if (m.doubleSided) flags |= RB_MATERIAL_DOUBLE_SIDED;
    if (m.alphaMode == AlphaMode::Mask) flags |= RB_MATERIAL_ALPHA_MASK;
    if (m.unlit) flags |= RB_MATERIAL_UNLIT;
    const bool customF0 = m.specularColor != glm::vec3(1.0f) || m.specularColorTexture >= 0;
    if (m.clearcoat > 0.0f || m.sheenColor != glm::vec3(0.0f) || m.specular != 1.0f || m.specularTexture >= 0 || customF0) {
      flags |= RB_MATERIAL_LAYERS;
      gpu.hasLayers = true;
    }
    for (int t : {m.baseColorTexture, m.metallicRoughnessTexture, m.normalTexture, m.emissiveTexture, m.clearcoatTexture, m.clearcoatRoughnessTexture,
                  m.clearcoatNormalTexture, m.sheenColorTexture, m.sheenRoughnessTexture, m.specularTexture, m.specularColorTexture})
      if (t >= 0 && scene.textures[size_t(t)].uvTransform != glm::mat3(1.0f)) flags |= RB_MATERIAL_UV_TRANSFORM;
    g.normalScaleThicknessFlags = glm::vec4(m.normalScale, m.thickness, std::bit_cast<float>(flags), 0.0f);
    g.clearcoat = glm::vec4(m.clearcoat, m.clearcoatRoughness, m.clearcoatNormalScale, m.specular);
    g.sheen = glm::vec4(m.sheenColor, m.sheenRoughness);
    g.specularColor = glm::vec4(m.specularColor, customF0 ? 1.0f : 0.0f);
    g.layerTextures = glm::ivec4(slot(m.clearcoatTexture, false), slot(m.clearcoatRoughnessTexture, false), slot(m.clearcoatNormalTexture, false),
                                 slot(m.specularTexture, false));
    g.layerTextures2 = glm::ivec4(slot(m.sheenColorTexture, true), slot(m.sheenRoughnessTexture, false), slot(m.specularColorTexture, true), -1);
    materials.push_back(g);
    gpu.hasTransmission = gpu.hasTransmission || m.transmission > 0.0f;
  }
  if (gpu.textures.empty()) {
    Image white{"white", 1, 1, {255, 255, 255, 255}};
    gpu.textureImages.push_back(makeTextureImage(ctx, white, false));
    gpu.textures.push_back({0, gpu.samplers[0]});
    transforms.push_back({glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0)});
  }
  gpu.textureTransforms = vk::createDeviceBuffer(ctx, transforms, kStorage);
  gpu.materials = vk::createDeviceBuffer(ctx, materials, kStorage);

  // Objects and their draws (one per primitive).
  std::vector<gpu::GpuObject> objects;
  for (const Object& o : scene.objects) {
    const gpu::GpuObject g = gpuObject(gpu, o);
    objects.push_back(g);
    gpu.objectSpheres.push_back(g.boundsCenterRadius);
    const Mesh& m = scene.meshes[o.mesh];
    for (const Primitive& p : m.primitives) {
      const Material& mat = scene.materials[size_t(p.material)];
      gpu.draws.push_back({meshFirstIndex[o.mesh] + p.firstIndex, p.indexCount, int32_t(meshVertexOffset[o.mesh]), o.id, uint32_t(p.material),
                           mat.alphaMode == AlphaMode::Mask, mat.transmission > 0.0f});
    }
  }
  gpu.objects = vk::createDeviceBuffer(ctx, objects, kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT);

  // The acceleration structure for the ray-traced effects (static scenes: built once, here).
  gpu.tracer = createSceneTracer(ctx, scene, settings);
  gpu.shell = scene;
  for (Mesh& m : gpu.shell.meshes) {
    m.vertices = {};
    m.indices = {};
  }
  gpu.shell.images = {};

  // Lights and their shadow views.
  if (scene.lights.size() > RB_MAX_LIGHTS)
    throw Error(scene.path.string() + ": " + std::to_string(scene.lights.size()) + " lights; raybudget renders at most " +
                std::to_string(RB_MAX_LIGHTS));
  std::vector<gpu::GpuLight> lights(scene.lights.size());
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    gpu::GpuLight& g = lights[i];
    const uint32_t type = l.type == LightType::Directional ? RB_LIGHT_DIRECTIONAL : l.type == LightType::Point ? RB_LIGHT_POINT : RB_LIGHT_SPOT;
    g.positionRange = glm::vec4(l.position, l.range);
    g.directionType = glm::vec4(l.direction, float(type));
    g.colorIntensity = glm::vec4(l.color * l.intensity, 0.0f);
    g.spotShadow = glm::vec4(std::cos(l.innerConeAngle), std::cos(l.outerConeAngle), -1.0f, 1.0f);
  }
  placeShadows(scene, settings, lights, gpu.shadows);
  gpu.lightCount = uint32_t(lights.size());
  // A uniform buffer of the fixed RB_MAX_LIGHTS size the shaders declare: lavapipe reads a
  // uniform-indexed UBO once per SIMD batch, where an SSBO costs a gather per lane.
  lights.resize(RB_MAX_LIGHTS);
  gpu.lights = vk::createDeviceBuffer(ctx, lights, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  return gpu;
}

}  // namespace raybudget::passes
