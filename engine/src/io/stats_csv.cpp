#include <algorithm>
#include <iomanip>

#include "raybudget/error.h"
#include "raybudget/stats.h"

namespace raybudget {

StatsCsv::StatsCsv(const std::filesystem::path& path) : out_(path), path_(path) {
  if (!out_) throw Error(path.string() + ": cannot open for writing");
  out_ << "frame";
  for (size_t p = 0; p < kPassCount; ++p) out_ << ',' << passName(Pass(p)) << "_ms";
  out_ << ",total_ms,rt_stage_ms,tlas_rebuild_ms,traced_tiles,rays,budget_ms,trace_budget_ms,budget_below_fixed_cost,predicted_trace_ms,measured_trace_ms,selected_objects,selected_value,selection_changes,optimal_value_bound,selection_sorted,candidates_ms,item_option_changes,shadow_map_views,shadow_map_draws,shadow_map_texels,probes_captured,partial_share,still_frames,deadline_cut_pixels,fill_cut_pixels,coverage_reused\n";
}

void StatsCsv::add(const FrameTiming& t) {
  out_ << t.frame << std::fixed << std::setprecision(4);
  for (const auto& ms : t.passMs) {
    out_ << ',';
    if (ms) out_ << *ms;  // empty cell: the pass was skipped this frame
  }
  out_ << ',' << t.totalMs() << ',' << t.rtStageMs() << ',' << t.tlasRebuildMs << ',' << t.tracedTiles << ',' << t.raysTraced << ',' << t.budgetMs << ','
       << t.traceBudgetMs << ',' << (t.budgetBelowFixedCost ? 1 : 0) << ',' << t.predictedTraceMs << ','
       << t.measuredTraceMs << ',' << t.selectedObjects << ',' << std::setprecision(8) << t.selectedValue << ',' << t.selectionChanges << ',' << t.optimalValueBound << ','
       << (t.selectionSorted ? 1 : 0) << ',' << std::setprecision(4) << t.candidatesMs << ',' << t.itemOptionChanges << ',' << t.shadowMapViews << ','
       << t.shadowMapDraws << ',' << t.shadowMapTexels << ',' << t.probesCaptured << ',' << t.partialShare << ',' << t.stillFrames << ',' << t.deadlineCutPixels << ',' << t.fillCutPixels << ','
       << (t.coverageReused ? 1 : 0) << '\n';
  if (!out_) throw Error(path_.string() + ": write failed");
}

namespace {
double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}
}  // namespace

PassSummary summarize(const std::vector<FrameTiming>& timings) {
  PassSummary s;
  std::vector<double> totals;
  for (size_t p = 0; p < kPassCount; ++p) {
    std::vector<double> v;
    for (const FrameTiming& t : timings)
      if (t.passMs[p]) v.push_back(*t.passMs[p]);
    s.medianMs[p] = median(v);
    s.frames[p] = v.size();
  }
  for (const FrameTiming& t : timings) totals.push_back(t.totalMs());
  s.medianTotalMs = median(totals);
  return s;
}

}  // namespace raybudget
