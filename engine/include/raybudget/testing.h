// Checks for tests: the renderer reads GPU state back every frame and compares it with its
// CPU references. They cost time every frame and are not meant for an engine's frames.
#pragma once
#include "raybudget/renderer.h"

namespace raybudget::testing {

struct Checks {
  // Each frame's candidates, selection and per-object costs read back and compared with the
  // CPU reference policy and cost model on the same candidates
  // (FrameTiming::selectionMatchesCpu, ::costsMatchCpu).
  bool selectionAgainstCpu = false;
  // Nonzero: the ray-tracing stage's deadline in device-clock ticks after the stage began, in
  // place of the one learned from T (RenderSettings::stageDeadline), whatever the policy; 1
  // leaves every pixel the trace passes would trace to its fallback.
  uint32_t stageDeadlineTicks = 0;
  // Nonzero: the fill's deadline (of reflections and refractions a reduced rate skipped) in
  // device-clock ticks, in place of the one at about T; 1 leaves every pixel it would fill to
  // its fallback.
  uint32_t fillDeadlineTicks = 0;
};

}  // namespace raybudget::testing
