// Per-frame statistics written as CSV: one row per frame, one column per pass (GPU ms).
#pragma once
#include <filesystem>
#include <fstream>
#include <vector>

#include "raybudget/renderer.h"

namespace raybudget {

class StatsCsv {
 public:
  explicit StatsCsv(const std::filesystem::path& path);
  void add(const FrameTiming& timing);

 private:
  std::ofstream out_;
  std::filesystem::path path_;
};

// Median GPU time of each pass over `timings` (frames where the pass ran), and of the total.
struct PassSummary {
  std::array<double, kPassCount> medianMs{};
  std::array<size_t, kPassCount> frames{};
  double medianTotalMs = 0.0;
};
PassSummary summarize(const std::vector<FrameTiming>& timings);

}  // namespace raybudget
