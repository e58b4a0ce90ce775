// GPU structs, defined once and included from both C++ and GLSL (std430 / std140-safe:
// every member is a vec4-sized slot). engine/src/passes/scene_gpu.cpp static_asserts sizes.
#ifndef RAYBUDGET_SHARED_TYPES_H
#define RAYBUDGET_SHARED_TYPES_H

#include "shared/config.h"

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace raybudget::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
using uint = std::uint32_t;
#endif

// 48 bytes: vertex pulled by index from a storage buffer.
struct GpuVertex {
  vec4 positionU;  // xyz position (mesh space), w texture u
  vec4 normalV;    // xyz normal (mesh space), w texture v
  vec4 color;      // COLOR_0, white when absent
};

// 160 bytes: one object = one node instance of one mesh.
struct GpuObject {
  mat4 model;
  mat4 normalMatrix;        // inverse-transpose of model (upper 3x3 used)
  vec4 boundsCenterRadius;  // world-space bounding sphere
  uvec4 ids;                // x object ID, y first index of its mesh, z its vertex offset, w RB_OBJECT_* flags
};

// 176 bytes: glTF metallic-roughness material with the transmission/volume extensions and
// the clearcoat, sheen and specular layers. Texture slots index `textures` and
// `textureTransforms` (-1: none).
struct GpuMaterial {
  vec4 baseColorFactor;
  vec4 emissiveAlphaCutoff;   // rgb emissive * emissive_strength, w alpha cutoff
  vec4 metallicRoughnessTransmissionIor;
  ivec4 textures;             // base colour, metallic-roughness, normal, emissive (-1 = none)
  vec4 attenuationColorDistance;  // KHR_materials_volume: rgb colour, w distance
  vec4 normalScaleThicknessFlags; // x normal scale, y thickness, z flags (as float bits), w unused
  vec4 clearcoat;             // x factor, y roughness, z normal scale, w KHR_materials_specular factor
  vec4 sheen;                 // rgb colour, w roughness
  vec4 specularColor;         // rgb: scales the dielectric F0 (KHR_materials_specular), w 1 when set
  ivec4 layerTextures;        // clearcoat (R), clearcoat roughness (G), clearcoat normal, specular (A)
  ivec4 layerTextures2;       // sheen colour (RGB), sheen roughness (A), specular colour (RGB), unused
};

// 32 bytes: a texture slot's KHR_texture_transform, uv' = (dot(u.xyz, (uv, 1)), dot(v.xyz, (uv, 1))).
struct GpuTextureTransform {
  vec4 u;
  vec4 v;
};

// 144 bytes: a punctual light and its shadow map.
struct GpuLight {
  vec4 positionRange;   // xyz world position, w range (0 = infinite)
  vec4 directionType;   // xyz direction the light travels, w type (RB_LIGHT_*)
  vec4 colorIntensity;  // rgb colour * intensity, w unused
  vec4 spotShadow;      // x cos(inner), y cos(outer), z shadow layer or cube (-1 none),
                        //   w share of the layer's side the map uses (sized from screen coverage)
  vec4 shadowParams;    // x texel size at the used size (world units; per unit distance for
                        //   spot/point), y near, z far, w normal offset in texels
  mat4 shadowViewProj;  // directional / spot: world -> shadow clip space
};

// Per-frame constants (uniform buffer), 336 bytes.
struct FrameUniforms {
  mat4 view;
  mat4 proj;
  mat4 viewProj;
  mat4 invViewProj;
  vec4 cameraPositionNear;  // xyz camera position, w near plane
  uvec4 sizeLightsFrame;    // x width, y height, z light count, w frame index
  vec4 sunDirection;        // xyz direction towards the sun (procedural sky), w sky intensity
  vec4 exposure;            // x exposure (linear scale before tonemapping), y shadow-map uncertainty reach (texels), z 1 when the behind-glass image holds this frame's opaque frame, w 1 when the G-buffer holds material layers (gLayers)
  uvec4 rayTracing;         // x effects traced (RB_RT_* bits, 0: all raster), y bounce depth, z roughness cut-off (float bits), w RB_RT_CLASSIFY_SHADOWS | RB_RT_MEASURE_ITEMS | RB_RT_SHORTEN_SHADOW_RAYS | RB_RT_RATES | RB_RT_TEMPORAL_FILL
  uvec4 probes;             // x reflection probes in use (0: the sky alone)
  vec4 probeCenter[RB_MAX_PROBES];  // xyz where each probe was captured from
  vec4 probeBoxMin[RB_MAX_PROBES];  // xyz its box: the surfaces it shows, and the points it serves
  vec4 probeBoxMax[RB_MAX_PROBES];
  mat4 previousViewProj;    // the previous frame's, for reprojecting its image
  vec4 ssr;                 // x 1 when ssrImage holds this frame's screen-space reflections, y roughness cut-off, z the diagonal of the scene's bounds (their rays' length)
  vec4 previousCamera;      // xyz the previous frame's camera position, w 1 when there was one
  uvec4 stageDeadline;      // the ray-tracing stage's deadlines in device-clock ticks after it began, x the effects pass's, y the shadow pass's, z the fill's (0: none; include/stage_clock.glsl)
};

// Push constants for the raster passes and the compute passes, 80 bytes (the guaranteed
// minimum is 128).
struct DrawPush {
  mat4 viewProj;         // shadow passes: the light's view-projection; otherwise unused
  uvec4 objectMaterial;  // x object index, y material index; compute passes: x = mip or pass argument (y, z more)
};

#ifdef __cplusplus
}  // namespace raybudget::gpu
#endif
#endif
