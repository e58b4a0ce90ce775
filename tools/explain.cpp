#include "explain.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <map>
#include <string>

#include "cli_options.h"

namespace raybudget::cli {
namespace {

const char* const kEffects[] = {"shadows", "reflections", "refractions"};

double rateShare(ItemRate rate) {
  return rate == ItemRate::Half ? 0.5 : rate == ItemRate::Quarter ? 0.25 : rate == ItemRate::Sixteenth ? 0.0625 : 1.0;
}

std::string formatted(const char* format, auto... values) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), format, values...);
  return buffer;
}

}  // namespace

void printPassPlan(std::ostream& out, const Renderer& renderer, const std::vector<FrameTiming>& frames,
                   const std::vector<ObjectMetrics>& lastFrame) {
  out << "pass plan over " << frames.size() << " frames:\n";
  for (size_t p = 0; p < kPassCount; ++p) {
    std::vector<double> ms;
    std::map<PassSkip, size_t> skipped;
    for (const FrameTiming& t : frames) {
      if (t.passMs[p]) ms.push_back(*t.passMs[p]);
      else ++skipped[t.skipped[p]];
    }
    std::vector<std::string> parts;
    if (!ms.empty()) parts.push_back(formatted("ran in %zu, median %.3f ms", ms.size(), median(ms)));
    for (const auto& [why, n] : skipped) parts.push_back(formatted("left out of %zu: %s", n, passSkipText(why)));
    out << formatted("  %-14s ", passName(Pass(p)));
    for (size_t i = 0; i < parts.size(); ++i) out << (i ? "; " : "") << parts[i];
    out << '\n';
  }
  const SceneEffects e = renderer.sceneEffects();
  out << "the scene can show: shadows " << (e.shadows ? "yes" : "no (no light)") << ", reflections "
      << (e.reflections ? "yes" : "no (no material smooth enough)") << ", refractions " << (e.refractions ? "yes" : "no (no transmissive material)")
      << '\n';
  out << "pipelines built:";
  for (const std::string& name : renderer.builtPipelines()) out << ' ' << name;
  out << '\n';
  if (lastFrame.empty()) return;
  // Pixels that need rays (the classifier's counts) and those of selected items, scaled by
  // their ray rate; shadows count the items' pixels (the shadow pass traces only where the
  // map is uncertain, with `benefit` and `classified`).
  double need[3] = {}, traced[3] = {};
  for (const ObjectMetrics& m : lastFrame) {
    const uint32_t pixels[3] = {m.pixels, m.reflectionPixels, m.refractionPixels};
    for (int i = 0; i < 3; ++i) {
      need[i] += pixels[i];
      if (m.selectedItems >> i & 1u) traced[i] += pixels[i] * rateShare(m.itemRate[size_t(i)]) * m.itemTileShare[size_t(i)];
    }
  }
  out << "last frame, pixels per effect (those that could take rays / those traced, by ray rate):\n";
  for (int i = 0; i < 3; ++i) out << formatted("  %-12s %9.0f / %9.0f\n", kEffects[i], need[i], traced[i]);
  const FrameTiming last = frames.empty() ? FrameTiming{} : frames.back();
  out << formatted("  rays traced: %u in %u tiles (%u for shadows, %u for reflections and refractions)\n", last.raysTraced, last.tracedTiles,
                   last.shadowTiles, last.effectTiles);
  // What `benefit` with rates chosen per item valued the reduced rates at (docs/SELECTION.md).
  if (last.stillFrames > 0)
    out << formatted("  the view: still for the %u frame%s before it (reduced rates valued for the temporal fill)\n", last.stillFrames,
                     last.stillFrames == 1 ? "" : "s");
  else
    out << "  the view: moved since the frame before (reduced rates valued at the moving-view priors)\n";
}

void printFrameSelection(std::ostream& out, uint64_t frame, const std::vector<ObjectMetrics>& metrics) {
  size_t selected = 0;
  for (const ObjectMetrics& m : metrics) selected += std::popcount(m.selectedItems);
  out << "frame " << frame << ": " << selected << " items selected\n";
  for (size_t id = 0; id < metrics.size(); ++id) {
    const ObjectMetrics& m = metrics[id];
    for (uint32_t i = 0; i < 3; ++i)
      if (m.selectedItems >> i & 1u)
        out << formatted("  object %4zu %-11s rate %-7s V %.4f C %.4f R %.4f  benefit %.4g/pixel  cost %.4g/pixel%s\n", id, kEffects[i],
                         itemRateName(m.itemRate[i]), double(m.V), double(m.C), double(m.R), double(m.itemBenefit[i]),
                         double(m.itemCostPerPixel[i]),
                         m.itemTileShare[i] < 1.0f ? formatted("  on %.2f of its tiles", double(m.itemTileShare[i])).c_str() : "");
  }
}

}  // namespace raybudget::cli
