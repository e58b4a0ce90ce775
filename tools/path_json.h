// A sweep's camera path as JSON (OUT/paths/NAME.json): written by every sweep, read back by
// `sweep --replay-paths` to run the cameras of an earlier sweep (like for like after the
// paths change).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "raybudget/camera.h"

namespace raybudget::cli {

// {"path": NAME, "frames": [{"position": [x, y, z], "target": [..], "up": [..], "yfov": F}, ..]}
void writePathJson(const std::filesystem::path& file, const std::string& name, const std::vector<Camera>& path);

// The cameras of a file writePathJson wrote, each over `base` (its near and far planes).
// Throws raybudget::Error naming the file and what is wrong: unreadable, not JSON, a frame
// without a finite position, target, up or field of view, or a camera no image comes from.
std::vector<Camera> readPathJson(const std::filesystem::path& file, const Camera& base);

}  // namespace raybudget::cli
