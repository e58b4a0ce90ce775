// `raybudget soak`: a long run of one scene as an engine would run it, checking what a short
// test cannot: memory that creeps, values that turn to NaN after thousands of frames, and
// whether the budget holds while T changes and the CPU is busy. The camera alternates between
// an orbit and a fly-through; T is a square wave between two budgets; a competing CPU load
// runs part of the time. Every --scan-every frames the output image and the per-object
// selection records are read back and scanned for NaN and Inf, and host RSS and device memory
// (VK_EXT_memory_budget) are sampled. Fails (exit 1) when either memory ends 1% or more above
// its peak over the first half after the warm-up, a NaN or Inf was found, or (3) the
// validation layer reported anything.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "cli_options.h"
#include "raybudget/settings.h"

namespace raybudget::cli {

struct SoakCommand {
  std::string scene;
  uint32_t frames = 10000;
  RenderTarget target{320, 180};
  uint32_t period = 100;        // frames per half-wave of the budget
  uint32_t pathFrames = 1000;   // frames per camera path before switching to the other
  float loadShare = 0.25f;      // share of each load cycle (4 periods) with the CPU load running
  uint32_t scanEvery = 100;     // frames between scans (and memory samples)
  uint32_t warmup = 0;          // frames before the memory baseline (0: a tenth of the frames, at least one scan)
  std::vector<float> budgets;   // low, high in ms (empty: 0.25 and 0.75 of the measured full-RT stage cost)
  Policy policy = Policy::Benefit;
  ItemRate rate = ItemRate::Auto;
};

SoakCommand parseSoak(const std::vector<std::string>& args);  // after the word "soak"; throws Error

int runSoak(const SoakCommand& command);  // the exit code

extern const char* kSoakUsage;

}  // namespace raybudget::cli
