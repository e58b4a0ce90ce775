// `raybudget sweep`: run time against error for one scene. Renders the full-RT reference
// (`all`), the raster-only frame (`none`) and every budgeted policy at a log-spaced sweep of
// budgets from the cheapest object's predicted cost to the full-RT trace time, on an orbit
// and a fly-through, repeated; writes one CSV row per frame with GPU times, the selection's
// stats and the image error against the reference (RMSE and PSNR on linear HDR), and the
// display images that bench/run.py scores with FLIP.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "raybudget/renderer.h"

namespace raybudget::cli {

struct SweepCommand {
  std::string scene;
  std::string out = "sweep";
  uint32_t width = 320, height = 180;
  uint32_t frames = 8;   // per camera path, after the warm-up
  uint32_t warmup = 4;   // frames on the path's first camera, not recorded: the cost model settles
  uint32_t budgets = 8;  // log-spaced points
  uint32_t repeats = 3;  // images and errors from the first repeat; timings from all
  std::vector<Policy> policies{Policy::Paper, Policy::Density, Policy::Nearest, Policy::Random};
  std::vector<std::string> paths{"orbit", "flythrough"};
  std::string device;
  bool validation = false;
};

// Parses `sweep` arguments (after the word "sweep"). Throws raybudget::Error.
SweepCommand parseSweep(const std::vector<std::string>& args);

// Runs the sweep; progress lines ("progress DONE TOTAL") on stdout. Returns the exit code.
int runSweep(const SweepCommand& command);

extern const char* kSweepUsage;

}  // namespace raybudget::cli
