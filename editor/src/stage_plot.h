#pragma once
// The budget panel's plot of the stage time over the last frames, thinned for drawing.

#include <cstddef>
#include <deque>
#include <vector>

namespace raybudget::editor {

// `history` in at most `points` values, in order: each the largest of a run of consecutive
// frames (the runs as even as the counts allow), so a frame over T stays in the plot. A line
// segment per frame was most of the UI pass on lavapipe (300 frames: ~600 triangles against
// ~200 for the plot's 400 pixels); `history` itself where it has no more than `points`.
std::vector<float> runPeaks(const std::deque<float>& history, size_t points);

}  // namespace raybudget::editor
