#include "stage_plot.h"

#include <algorithm>

namespace raybudget::editor {

std::vector<float> runPeaks(const std::deque<float>& history, size_t points) {
  if (history.size() <= points || points == 0) return {history.begin(), history.end()};
  std::vector<float> peaks(points);
  for (size_t p = 0; p < points; ++p) {
    const size_t first = p * history.size() / points, end = (p + 1) * history.size() / points;
    peaks[p] = *std::max_element(history.begin() + std::ptrdiff_t(first), history.begin() + std::ptrdiff_t(end));
  }
  return peaks;
}

}  // namespace raybudget::editor
