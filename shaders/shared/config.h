// One configuration header for C++ and GLSL: every constant both sides must agree on.
#ifndef RAYBUDGET_SHARED_CONFIG_H
#define RAYBUDGET_SHARED_CONFIG_H

// Compute passes over the screen run 8x8 tiles. The trace passes run over chunks of
// RB_TRACE_CHUNK pixels of a tile, as many of a tile's chunks as its items' ray rates need
// (include/tile_pixel.glsl), RB_TRACE_GROUP_SIZE invocations a workgroup.
#define RB_TILE_SIZE 8
#define RB_TRACE_CHUNK 4u
#define RB_TRACE_GROUP_SIZE 64
// Lanes of the one-dimensional passes (one invocation per object, tile, candidate or ray),
// and of the selection's key pass; the host dispatches groupsFor(n, ...) (vk/pipelines.h).
#define RB_GROUP_SIZE 64
#define RB_KEYS_GROUP_SIZE 256

// Object-ID value of pixels that show no object (the G-buffer clear value).
#define RB_NO_OBJECT 0xFFFFFFFFu
// Per 8x8 tile, the coverage pass notes up to RB_TILE_OBJECT_WORDS - 1 distinct objects
// (ID + 1, 0 = none) and, in the last word, 1 when the tile shows more: the tile list then
// checks those objects instead of fetching the tile's pixels.
#define RB_TILE_OBJECT_WORDS 4u

// Light types (GpuLight.directionType.w).
#define RB_LIGHT_DIRECTIONAL 0
#define RB_LIGHT_POINT 1
#define RB_LIGHT_SPOT 2

// Material flags (GpuMaterial.flags).
#define RB_MATERIAL_DOUBLE_SIDED 1u
#define RB_MATERIAL_ALPHA_MASK 2u
#define RB_MATERIAL_UNLIT 4u
#define RB_MATERIAL_LAYERS 8u        // clearcoat, sheen or specular other than glTF's defaults
#define RB_MATERIAL_UV_TRANSFORM 16u  // a texture slot with a KHR_texture_transform

// Object flags (GpuObject.ids.w).
#define RB_OBJECT_CLOSED_THIN_GLASS 1u  // its thin-walled transmissive triangles close a shell

// Ray-traced effects (FrameUniforms.rayTracing.x bits).
#define RB_RT_SHADOWS 1u
#define RB_RT_REFLECTIONS 2u
#define RB_RT_REFRACTIONS 4u
// FrameUniforms.rayTracing.w bits: the shadow pass traces only where the shadow map is
// uncertain; the trace and lighting passes count per item its work and the display error
// its tracing removed (GpuItemCost); the shadow pass's rays end past the map's nearest
// blocker.
#define RB_RT_CLASSIFY_SHADOWS 1u
#define RB_RT_MEASURE_ITEMS 2u
#define RB_RT_SHORTEN_SHADOW_RAYS 4u
#define RB_RT_RATES 8u  // some items may be traced at a reduced rate (include/tile_pixel.glsl)
// The fill of reflections and refractions takes a pixel's value from the last frames where it
// was traced, if it is still valid there (include/fill_history.glsl), before its traced neighbours.
#define RB_RT_TEMPORAL_FILL 16u
#define RB_FILL_HISTORY_LAYERS 4u  // colour and geometry for each frame parity
// The shadow fill's history (include/shadow_history.glsl): per frame parity a layer of where,
// and one of when and the first RB_SHADOW_HISTORY_LIGHTS lights' visibility (8 bits each).
#define RB_SHADOW_HISTORY_LAYERS 4u
#define RB_SHADOW_HISTORY_LIGHTS 12u
// The effects pass's specialization constant: the paths (RB_RT_REFLECTIONS, RB_RT_REFRACTIONS) its
// pipeline holds, those the scene can show and the settings switch on; the others' code is
// compiled out (rt_effects.comp).
#define RB_PATHS_CONSTANT_ID 0
// Most reflection/refraction bounces a ray may take (the frame's depth is clamped to it).
#define RB_RT_MAX_DEPTH 4

// The lighting pass's argument (DrawPush.objectMaterial.x) when it lights the opaque frame
// that transmissive surfaces show behind them: shadow maps only, nothing measured.
#define RB_PASS_BEHIND_GLASS 1u
#define RB_PASS_COMPOSE 2u  // lighting: also compose the frame (no trace pass of reflections or refractions follows)
// The behind-glass image's alpha where no surface was drawn (view distance, half float).
#define RB_BEHIND_GLASS_SKY 65000.0

// Upper bound of punctual lights a scene may carry: the lighting loop is per pixel, and
// beyond this count a deferred renderer would cluster lights (not needed by our scenes).
#define RB_MAX_LIGHTS 64

// Environment cube map: base resolution and mip count of the prefiltered chain.
#define RB_ENV_SIZE 128
#define RB_ENV_MIPS 6
// GGX importance samples per texel when prefiltering the environment.
#define RB_ENV_PREFILTER_SAMPLES 64

// Reflection probes: at most this many (authored ones; else one over the scene's bounds),
// each a cube of RB_ENV_SIZE texels per side and RB_ENV_MIPS prefiltered levels.
#define RB_MAX_PROBES 8
#define RB_NO_PROBE 0xFFFFFFFFu
// The captured radiance keeps a full mip chain (to 1x1 per face: the probe's mean alpha).
#define RB_PROBE_RADIANCE_MIPS 8
// A probe is used where at least this share of its directions see the outside of surfaces
// (less: its centre is inside a closed object, and the sky stands in for it) ...
#define RB_PROBE_MIN_OUTSIDE 0.99
// ... and see no surface nearer than this share of the scene's diagonal.
#define RB_PROBE_MIN_CLEARANCE 0.025
// Screen-space reflections: surfaces up to this roughness march their mirror ray (fading out
// from 0.6 of it), through a min-depth pyramid of at most RB_HIZ_LEVELS levels (16384 pixels).
#define RB_SSR_MAX_ROUGHNESS 0.4
#define RB_HIZ_LEVELS 15

#endif
