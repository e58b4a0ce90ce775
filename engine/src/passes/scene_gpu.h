// The scene on the GPU: vertices, indices, objects, materials, lights (with their shadow
// matrices), textures and samplers, plus the draw list the raster passes walk.
#pragma once
#include <vector>

#include "passes/scene_tracer.h"
#include "raybudget/renderer.h"
#include "raybudget/scene.h"
#include "shared/types.h"
#include "vk/resources.h"

namespace raybudget::passes {

struct Draw {
  uint32_t firstIndex;
  uint32_t indexCount;
  int32_t vertexOffset;
  uint32_t object;
  uint32_t material;
  bool alphaMask;
  bool transmissive;  // KHR_materials_transmission: drawn over the opaque frame it shows behind it
};

// A material texture slot: an image of SceneGpu::textureImages and its sampler.
struct GpuTexture {
  uint32_t image;
  VkSampler sampler;
};

// What sizing a light's map from its screen coverage needs (ShadowMapPass::fit): the light,
// the sphere its shadows fall in (w < 0: everywhere, a directional light) and its texel size
// at the full map size (GpuLight's shadowParams.x when the whole layer is used).
struct ShadowFit {
  uint32_t light;
  glm::vec4 reach;
  float fullSizeTexel;
};

struct ShadowViews {
  uint32_t mapLayers = 0;      // directional + spot lights with a shadow map
  uint32_t pointCubes = 0;     // point lights with a cube map
  std::vector<glm::mat4> mapViewProj;     // per layer
  std::vector<glm::mat4> cubeFaceViewProj;  // per cube face (6 per point light)
  std::vector<ShadowFit> fit;  // per layer, then per cube
};

struct SceneGpu {
  // CPU copies for updates when objects move: the scene without vertex data, and where
  // each mesh starts in the shared index and vertex buffers.
  Scene shell;
  std::vector<uint32_t> meshFirstIndex, meshVertexOffset;
  std::vector<bool> meshClosedThinGlass;  // per mesh: RB_OBJECT_CLOSED_THIN_GLASS
  std::unique_ptr<SceneTracer> tracer;  // the trace passes' acceleration structure
  vk::Buffer vertices;
  vk::Buffer indices;
  vk::Buffer objects;
  vk::Buffer materials;
  vk::Buffer lights;
  std::vector<vk::Owned<VkSampler>> samplers;  // [0] default, then one per glTF sampler
  std::vector<vk::Image> textureImages;
  std::vector<GpuTexture> textures;            // at least one (white) so the array is never empty
  vk::Buffer textureTransforms;                // GpuTextureTransform per texture slot
  std::vector<Draw> draws;
  std::vector<glm::vec4> objectSpheres;  // world bounding spheres, for culling
  ShadowViews shadows;
  uint32_t lightCount = 0;
  bool hasTransmission = false;
  bool hasLayers = false;  // a material with clearcoat, sheen or specular (RB_MATERIAL_LAYERS)
};

SceneGpu uploadScene(const vk::Context& ctx, const Scene& scene, const RenderSettings& settings);

// The GPU record of an object (transforms, bounds, IDs, where its mesh lives).
gpu::GpuObject gpuObject(const SceneGpu& scene, const Object& o);

}  // namespace raybudget::passes
