// A trace pass (shadows, or reflections and refractions) over the tile list, in two pipelines
// from one shader: without and with the fill of reduced ray rates inside the pass
// (shaders/include/tile_fill.glsl, specialized by its constant rbFill). Each is built on
// first use, so a scene or policy that never traces the pass's effects builds neither;
// full-rate frames keep the plain one, whose shader has no barrier and no shared memory
// (with them, tracing at full rate measured ~7% slower on lavapipe).
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
  TracePass(const vk::Context& ctx, PassLayouts& layouts, vk::Spirv shader, TileList tiles);
  // Dispatches over the pass's tile list; `fill`: reduced ray rates are in the frame.
  void recordOverTiles(const FrameContext& fc, bool fill);
  bool builtPlain() const { return bool(plain_); }
  bool builtFilling() const { return bool(filling_); }

 private:
  const vk::Context& ctx_;
  const PassLayout& layout_;
  vk::Spirv shader_;
  TileList tiles_;
  vk::Owned<VkPipeline> plain_, filling_;
};

}  // namespace raybudget::passes
