// The one descriptor set every raybudget pipeline shares (engine/src/passes/bindings.h
// lists the same binding numbers for C++). Unused bindings cost nothing in a shader.
#ifndef RB_BINDINGS_GLSL
#define RB_BINDINGS_GLSL
#extension GL_EXT_nonuniform_qualifier : require
#include "shared/config.h"
#include "shared/types.h"
#include "shared/selection.h"

layout(set = 0, binding = 0) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1, std430) readonly buffer ObjectBlock { GpuObject objects[]; };
layout(set = 0, binding = 2, std430) readonly buffer MaterialBlock { GpuMaterial materials[]; };
layout(set = 0, binding = 3, std140) uniform LightBlock { GpuLight lights[RB_MAX_LIGHTS]; };
layout(set = 0, binding = 4, std430) readonly buffer VertexBlock { GpuVertex vertices[]; };
layout(set = 0, binding = 5) uniform sampler2D textures[];
layout(set = 0, binding = 51, std430) readonly buffer TextureTransformBlock { GpuTextureTransform textureTransforms[]; };

// G-buffer, read with texelFetch.
layout(set = 0, binding = 6) uniform sampler2D gDepth;
layout(set = 0, binding = 7) uniform sampler2D gNormal;
layout(set = 0, binding = 8) uniform sampler2D gBaseMetal;
layout(set = 0, binding = 9) uniform sampler2D gRoughTransIor;
layout(set = 0, binding = 10) uniform sampler2D gEmissive;
layout(set = 0, binding = 11) uniform usampler2D gObjectId;
layout(set = 0, binding = 12) uniform usampler2D gMaterialId;
layout(set = 0, binding = 52) uniform usampler2D gLayers;  // material layers (gbuffer.glsl's packLayers)

// Raster fallbacks.
layout(set = 0, binding = 13) uniform sampler2DArrayShadow shadowMaps;      // directional + spot
layout(set = 0, binding = 14) uniform sampler2DArrayShadow pointShadows;    // 6 layers (cube faces) per point light
layout(set = 0, binding = 15) uniform samplerCube envMap;                   // prefiltered, RB_ENV_MIPS mips
layout(set = 0, binding = 16) uniform samplerCube skyMap;                   // sky radiance with mips

// Storage images written by the compute passes.
layout(set = 0, binding = 17, rgba16f) uniform image2D directImage;
// The reflected and the refracted light, apart so that a host can compose them apart.
layout(set = 0, binding = 18, rgba16f) uniform image2D reflectionImage;
layout(set = 0, binding = 53, rgba16f) uniform image2D refractionImage;
// The effects pass's temporal fill (include/fill_history.glsl): per pixel what tracing changed
// against the fallback where its reflection and refraction were last traced, two layers per
// frame parity.
layout(set = 0, binding = 54, rgba32ui) uniform uimage2DArray fillHistory;
// The lighting pass's temporal shadow fill (include/shadow_history.glsl): per pixel the shadow
// maps' error where its shadows were last traced, two layers per frame parity.
layout(set = 0, binding = 55, rgba32ui) uniform uimage2DArray shadowHistory;
layout(set = 0, binding = 19, rgba16f) uniform writeonly image2D hdrImage;
layout(set = 0, binding = 20, rgba8) uniform writeonly image2D ldrImage;
layout(set = 0, binding = 21, rgba16f) uniform writeonly imageCube skyStorage;
layout(set = 0, binding = 22, rgba16f) uniform writeonly imageCube envStorage[RB_ENV_MIPS];

// An HDR environment image (equirectangular) that replaces the procedural sky when given.
layout(set = 0, binding = 23) uniform sampler2D envSource;

// Ray tracing: the BVH (bindings 24-26, see rayquery.glsl), the mesh indices for hit
// attributes, and the ray-traced shadow mask: a layer per light of its visibility, then as
// many again holding the shadow map's visibility where a reduced ray rate traced the pixel
// (the lighting pass's fill reads it: include/shadow_fill.glsl).
#define RB_BVH_SET 0
#define RB_BVH_BINDING 24
layout(set = 0, binding = 27, std430) readonly buffer IndexBlock { uint meshIndices[]; };
layout(set = 0, binding = 28, r32f) uniform image2DArray shadowMask;
int mappedLayer(uint light) { return imageSize(shadowMask).z / 2 + int(light); }
layout(set = 0, binding = 29) uniform sampler2D gPosition;  // xyz world position, w packed geometric normal

// The heuristic (shared/selection.h): per-object coverage, parameters and records.
layout(set = 0, binding = 30, std430) buffer CoverageBlock { GpuCoverage coverage[]; };
layout(set = 0, binding = 31, std430) readonly buffer ObjectParamsBlock { GpuObjectParams objectParams[]; };
layout(set = 0, binding = 32, std430) buffer ObjectRecordBlock { GpuObjectRecord objectRecords[]; };
// The selection (1: the object's pixels get ray-traced effects) and, per trace pass and for
// the fill of reflections and refractions, the chunks of the 8x8 tiles holding pixels it runs
// (tile_list.comp, include/tile_pixel.glsl), with the pass's indirect dispatch (x, y, z). Apart,
// so that a pass never runs over the tiles of the other's items (the shadow pass over a mirror's
// tiles cost a quarter of the mirror's 1/16 rate).
layout(set = 0, binding = 33, std430) buffer SelectionBlock { uint selected[]; };
layout(set = 0, binding = 34, std430) buffer TileListBlock {
  uvec4 tileDispatch;    // the shadow pass's: x groups, y 1, z 1, w rays the trace passes traced
  uvec4 effectDispatch;  // the reflection and refraction pass's: x groups, y 1, z 1, w tiles in either list
  uvec4 traceCounts;     // x the rays the items' prior counts at the pixels traced (rt_common.glsl); y, z, w
                         // the chunks listed for the shadow pass, the effect pass and the fill
  uvec4 fillDispatch;    // the fill's (fill_effects.comp): x groups, y 1, z 1, w 0
  uvec4 tileCounts;      // the tiles listed for the shadow pass (x) and the effect pass (y); zw 0
  uvec4 stageClock;      // the stage's time on the device clock, for its deadline (include/stage_clock.glsl)
  uvec4 deadlineCut;     // what the deadline left to the fallbacks: x pixels, y their predicted work, z the shadow pass's pixels; w the pixels the fill left
  uint tiles[];          // from RB_SHADOW_CHUNKS, RB_EFFECT_CHUNKS and RB_FILL_CHUNKS each list's chunks
                         // (tile_pixel.glsl's chunkWord)
};
// Where the lists start in tiles[]: a pass needs at most 64 / RB_TRACE_CHUNK chunks a tile.
#define RB_CHUNKS_PER_TILE (RB_TILE_SIZE * RB_TILE_SIZE / RB_TRACE_CHUNK)
#define RB_SHADOW_CHUNKS 0u
#define RB_EFFECT_CHUNKS (screenTileCount() * RB_CHUNKS_PER_TILE)
#define RB_FILL_CHUNKS (screenTileCount() * 2u * RB_CHUNKS_PER_TILE)

layout(set = 0, binding = 35, std430) buffer ObjectCostBlock { GpuObjectCost objectCosts[]; };
// Per tile, RB_TILE_OBJECT_WORDS words: the objects it shows (shared/config.h).
layout(set = 0, binding = 36, std430) buffer TileObjectBlock { uint tileObjects[]; };
// Per item (object * RB_ITEMS_PER_OBJECT + effect): what `benefit` learns (shared/selection.h).
layout(set = 0, binding = 37, std430) buffer ItemCostBlock { GpuItemCost itemCosts[]; };
// The record after the items: the frame's totals.
uint itemTotalsIndex() { return uint(itemCosts.length()) - 1u; }
// The shadow maps of bindings 13 and 14 read as depths (no compare, nearest).
layout(set = 0, binding = 38) uniform sampler2DArray shadowMapDepths;
layout(set = 0, binding = 39) uniform sampler2DArray pointShadowDepths;
// Per pixel, the effects whose rays were traced and shown there this frame (RB_RT_SHADOWS,
// RB_RT_REFLECTIONS, RB_RT_REFRACTIONS bits; 0 where the fallbacks stand, and where a
// reduced rate filled the pixel from traced neighbours); core::FrameOutputs::tracedMask.
layout(set = 0, binding = 40, r32ui) uniform uimage2D tracedMask;
void markTraced(ivec2 pixel, uint effects) {
  if (effects != 0u) imageStore(tracedMask, pixel, uvec4(imageLoad(tracedMask, pixel).r | effects));
}

// The opaque frame, lit before transmissive surfaces are drawn over it (rgb radiance, a its
// view distance at mip 0), with a mip chain: what glass shows behind it (env_fallback.glsl).
layout(set = 0, binding = 41) uniform sampler2D behindGlass;
layout(set = 0, binding = 42, rgba16f) uniform writeonly image2D behindGlassImage;  // mip 0
bool behindGlassReady() { return frame.exposure.z > 0.5; }

// Reflection probes (include/environment.glsl): a cube per probe, the radiance captured
// from the probe's centre with a blitted mip chain, and its GGX-prefiltered copy
// (RB_ENV_MIPS roughness levels, like envMap).
layout(set = 0, binding = 43) uniform samplerCubeArray reflectionProbes;
layout(set = 0, binding = 44) uniform samplerCubeArray probeRadiance;
layout(set = 0, binding = 45, rgba16f) uniform writeonly imageCubeArray probeRadianceImage;  // mip 0
layout(set = 0, binding = 46, rgba16f) uniform writeonly imageCubeArray reflectionProbeMips[RB_ENV_MIPS];

// Screen-space reflections (ssr.comp): the min-depth pyramid of the G-buffer's depth (level 0
// the depth itself), the previous frame's HDR image they reproject, and their result per
// pixel (rgb radiance, a confidence).
layout(set = 0, binding = 47) uniform sampler2D depthPyramid;
layout(set = 0, binding = 48, r32f) uniform writeonly image2D depthPyramidLevels[RB_HIZ_LEVELS];
layout(set = 0, binding = 49) uniform sampler2D previousFrame;
layout(set = 0, binding = 50, rgba16f) uniform image2D ssrImage;
bool ssrReady() { return frame.ssr.x > 0.5; }

// The 8x8 tiles covering the screen.
uint screenTileCount() {
  uvec2 size = frame.sizeLightsFrame.xy;
  return ((size.x + RB_TILE_SIZE - 1u) / RB_TILE_SIZE) * ((size.y + RB_TILE_SIZE - 1u) / RB_TILE_SIZE);
}

// The 8x8 tile of a pass with one invocation per tile (coverage, tile list): its pixels
// [first, last); false past the last tile.
bool screenTile(uint t, out uvec2 first, out uvec2 last) {
  uvec2 size = frame.sizeLightsFrame.xy;
  uint tilesX = (size.x + RB_TILE_SIZE - 1u) / RB_TILE_SIZE, tilesY = (size.y + RB_TILE_SIZE - 1u) / RB_TILE_SIZE;
  first = uvec2(t % tilesX, t / tilesX) * RB_TILE_SIZE;
  last = min(first + RB_TILE_SIZE, size);
  return t < tilesX * tilesY;
}

// What the selection holds for a pixel's object: its items, their rates and probes (0 for no
// object). A pass reads it once per pixel: on lavapipe each read of a buffer at an index that
// differs per lane is a loop over the lanes, and the buffer is written elsewhere, so repeated
// reads are not merged.
struct Selection {
  uint word;
};
Selection selectionOf(uint objectId) { return Selection(objectId == RB_NO_OBJECT ? 0u : selected[objectId]); }
// Whether the object's item `effect` (RB_ITEM_*) is selected.
bool itemSelected(Selection sel, uint effect) { return (sel.word & (1u << effect)) != 0u; }
bool measuringItems() { return (frame.rayTracing.w & RB_RT_MEASURE_ITEMS) != 0u; }
// Reflections are traced on surfaces up to this roughness (RayTracingSettings::maxRoughness).
float maxTracedRoughness() { return uintBitsToFloat(frame.rayTracing.z); }
// The reflected plus the refracted light at a pixel.
vec3 indirectLight(ivec2 pixel) { return imageLoad(reflectionImage, pixel).rgb + imageLoad(refractionImage, pixel).rgb; }

#endif
