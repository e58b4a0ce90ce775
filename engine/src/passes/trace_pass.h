// A trace pass (shadows, or reflections and refractions) over the tile list, in two pipelines
// from one shader: without and with the fill of reduced ray rates inside the pass
// (shaders/include/tile_fill.glsl, specialized by its constant rbFill). Each is built on
// first use, so a scene or policy that never traces the pass's effects builds neither;
// full-rate frames keep the plain one, whose shader has no barrier and no shared memory
// (with them, tracing at full rate measured ~7% slower on lavapipe). The effects pass's
// pipelines hold only the paths the scene and settings need (RB_PATHS_CONSTANT_ID).
#pragma once
#include "passes/frame_context.h"
#include "passes/pass_layouts.h"
#include "vk/context.h"
#include "vk/owned.h"
#include "vk/pipelines.h"

namespace raybudget::passes {

// The tile list a trace pass runs over (shaders/include/bindings.glsl's TileListBlock): the
// tiles of its own items only.
enum class TileList : uint32_t { Shadows = 0, Effects = 1 };

class TracePass {
 public:
  // `paths`: for the effects pass, the RB_RT_REFLECTIONS / RB_RT_REFRACTIONS its pipelines
  // hold (0 for the shadow pass).
  TracePass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader, TileList tiles, uint32_t paths = 0);
  // Dispatches over the pass's tile list; `fill`: reduced ray rates are in the frame.
  void recordOverTiles(const FrameContext& fc, bool fill);
  bool builtPlain() const { return bool(plain_); }
  bool builtFilling() const { return bool(filling_); }
  uint32_t paths() const { return paths_; }

 private:
  const vk::Context& ctx_;
  const PassLayout& layout_;
  vk::Spirv shader_;
  TileList tiles_;
  uint32_t paths_;
  vk::Owned<VkPipeline> plain_, filling_;
};

}  // namespace raybudget::passes
