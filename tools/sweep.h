// `raybudget sweep`: run time against error for one scene. On an orbit and a fly-through it
// renders the full-RT reference (`all`), the raster-only frame (`none`) and every budgeted
// policy at budgets that include 10, 25, 50 and 100% of the full-RT stage cost (the shares
// bench/run.py's headline reads), in repeats whose configurations run in a shuffled order, `all` and `none`
// among them. Every configuration starts from the same learned cost model (calibrated once
// per path at the full budget) and warms up on its own, so its results do not depend on what
// ran before. Writes one CSV row per frame with GPU times per pass, the selection's stats
// and the image error against the reference (RMSE and PSNR on linear HDR), every recorded
// frame's display image (which bench/run.py scores with FLIP), and per path the calibration.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "cli_options.h"
#include "raybudget/renderer.h"

namespace raybudget::cli {

// A budgeted policy as the sweep runs it: `benefit` may leave one of its parts out (ablations)
// or choose a ray rate per item (benefit-rates).
struct SweepPolicy {
  Policy policy = Policy::Density;
  BenefitAblation ablation = BenefitAblation::None;
  ItemRate rate = ItemRate::Full;
  std::string name() const {
    return std::string(policyName(policy)) + (ablation == BenefitAblation::None ? "" : std::string("-") + ablationName(ablation)) +
           (rate == ItemRate::Auto ? "-rates" : "");
  }
};

struct SweepCommand {
  std::string scene;
  std::string out = "sweep";
  RenderTarget target;  // 640x360 unless told
  uint32_t frames = 4;   // recorded per camera path and configuration, after the warm-up
  uint32_t warmup = 8;   // frames on the path's first camera at the configuration's budget, not recorded
  uint32_t leadIn = 0;   // frames of the camera moving along the path before the last recorded frame, not recorded
  uint32_t budgets = 6;  // the headline shares of full RT, then more (unless budgetList is given)
  uint32_t repeats = 3;  // each repeat runs every configuration once; every repeat is imaged
  uint32_t orderSeed = 1;  // shuffles each repeat's configurations; 0: all, none, then budgets ascending
  std::vector<float> budgetList;  // explicit budgets in ms instead of the calibrated sweep
  bool priorTimeScale = false;    // never learn the time scale: selections independent of timing (tests)
  std::vector<SweepPolicy> policies{{Policy::Paper}, {Policy::Density}, {Policy::Nearest}, {Policy::Random}, {Policy::Benefit}};
  bool classified = true;  // run `classified` beside all and none
  RenderSettings image;  // the options shared with render (cli::parseImageOption); the rest default
  std::vector<std::string> paths{"orbit", "flythrough"};
  std::string replayPaths;  // a folder of an earlier sweep's path files, whose cameras run instead
};

// Parses a budgeted policy's name: paper, density, nearest, random, benefit, benefit with a
// part left out (benefit-no-centrality, -no-hysteresis, -prior-only, -no-classifier,
// -no-probe), or benefit-rates (a ray rate per item).
SweepPolicy parseSweepPolicy(const std::string& name);

// Parses `sweep` arguments (after the word "sweep"). Throws raybudget::Error.
SweepCommand parseSweep(const std::vector<std::string>& args);

// Runs the sweep; progress lines ("progress DONE TOTAL") on stdout. Returns the exit code.
int runSweep(const SweepCommand& command);

extern const char* kSweepUsage;

}  // namespace raybudget::cli
