// A compute pass over a tile list (chunks of tiles: shaders/include/tile_pixel.glsl), its
// pipeline built on
// first use, so a scene or policy that never needs the pass builds none: the trace passes
// (shadows, or reflections and refractions) and the fill of reflections and refractions at
// reduced ray rates. The effects pass's pipeline holds only the paths the scene and settings
// need (RB_PATHS_CONSTANT_ID). A trace pass fills nothing a reduced rate skipped (the lighting
// pass fills shadows, fill_effects.comp reflections and refractions), so a skipped pixel costs
// it its object's read alone.
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

// The list a pass runs over (shaders/include/bindings.glsl's TileListBlock), named by the
// place of its indirect dispatch in the list's header: the trace passes' chunks of the tiles
// of their own items, the fill's chunks of the tiles whose reflections or refractions a
// reduced rate skips.
enum class TileList : uint32_t { Shadows = 0, Effects = 1, EffectFill = 3 };

class TileListPass {
 public:
  // `paths`: for the effects pass, the RB_RT_REFLECTIONS / RB_RT_REFRACTIONS its pipeline
  // holds (0 for the others: no such constant).
  TileListPass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader, TileList tiles, uint32_t paths = 0);
  // Dispatches over the pass's tile list.
  void recordOverTiles(const FrameContext& fc);
  bool built() const { return bool(pipeline_); }
  uint32_t paths() const { return paths_; }

 private:
  const vk::Context& ctx_;
  const PassLayout& layout_;
  vk::Spirv shader_;
  TileList tiles_;
  uint32_t paths_;
  vk::Owned<VkPipeline> pipeline_;
};

}  // namespace raybudget::passes
