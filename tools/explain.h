// `raybudget render --explain`: what the frame did and why. The pass plan (per pass: the
// frames it ran in and their median GPU time, the frames it was left out of and why), the
// effects the scene can show, the pipelines built, and per effect the pixels that need rays
// and the pixels of traced items; with --explain=frames, each frame's selected items.
#pragma once
#include <cstdint>
#include <ostream>
#include <vector>

#include "raybudget/renderer.h"

namespace raybudget::cli {

void printPassPlan(std::ostream& out, const Renderer& renderer, const std::vector<FrameTiming>& frames,
                   const std::vector<ObjectMetrics>& lastFrame);

void printFrameSelection(std::ostream& out, uint64_t frame, const std::vector<ObjectMetrics>& metrics);

}  // namespace raybudget::cli
