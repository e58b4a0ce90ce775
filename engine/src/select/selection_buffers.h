// The selection's GPU state (shaders/shared/selection.h): per object its coverage, K/Q/I/S,
// A..R record, selection flag and learned cost; per 8x8 tile the objects it shows and the
// list of tiles the trace passes dispatch over. Bound into the frame's descriptor set
// (shaders/include/bindings.glsl) and into the GPU selector's own.
#pragma once
#include <vector>

#include "raybudget/scene.h"
#include "shared/selection.h"
#include "vk/resources.h"

namespace raybudget::select {

struct SelectionBuffers {
  uint32_t objects = 0;  // the scene's objects (each buffer holds at least one record)
  uint32_t tiles = 0;    // 8x8 tiles of the frame
  vk::Buffer coverage;       // GpuCoverage per object
  vk::Buffer objectParams;   // GpuObjectParams per object: K, Q, I and S, the items' priors
  vk::Buffer objectRecords;  // GpuObjectRecord per object: A, P, D, V, C, R
  vk::Buffer selection;      // uint per object: 1 = traced this frame
  vk::Buffer objectCosts;    // GpuObjectCost per object: learned work per pixel, this frame's work
  vk::Buffer itemCosts;      // GpuItemCost per item (RB_ITEMS_PER_OBJECT per object), then the frame's totals: what `benefit` learns
  vk::Buffer tileObjects;    // RB_TILE_OBJECT_WORDS per tile (shaders/select/coverage.comp)
  // The header (shaders/include/bindings.glsl's TileListBlock: each trace pass's and the fill's
  // dispatch, the rays traced, the rays the items' prior counts, the chunks and tiles listed,
  // the stage's clock), then the trace passes' and the fill's chunks of tiles.
  vk::Buffer tileList;
};
constexpr uint32_t kTileListHeaderBytes = 112;
// The header's words the select pass resets (the lists); the stage's clock and what its
// deadline cut, after them, are reset before coverage (shaders/include/stage_clock.glsl).
constexpr uint32_t kTileListListBytes = 80;
// Per screen tile: each trace pass's and the fill's chunks (RB_TRACE_CHUNK pixels).
constexpr uint64_t kTileListWordsPerTile = 3 * (RB_TILE_SIZE * RB_TILE_SIZE / RB_TRACE_CHUNK);

// Each object's K, Q, I (its glTF extras or the defaults) and S = 0, as the selection starts;
// `maxRoughness`: the reflections' roughness cut-off, which the derived Q counts.
std::vector<gpu::GpuObjectParams> initialObjectParams(const Scene& scene, float maxRoughness);

// Buffers for `objects` objects whose K/Q/I/S start as `params` (initialObjectParams).
SelectionBuffers createSelectionBuffers(const vk::Context& ctx, uint32_t objects, const std::vector<gpu::GpuObjectParams>& params,
                                        uint32_t width, uint32_t height);

// Records the reset of what the selection learned: K/Q/I/S to `params`, no learned costs.
void recordSelectionReset(VkCommandBuffer cmd, const SelectionBuffers& buffers, const std::vector<gpu::GpuObjectParams>& params);

}  // namespace raybudget::select
