#include "panels.h"

#include <algorithm>
#include <vector>

#include <imgui.h>

#include "stage_plot.h"

namespace raybudget::editor {
namespace {

const Policy kPolicies[] = {Policy::None, Policy::All, Policy::Paper, Policy::Density, Policy::Nearest, Policy::Random, Policy::Benefit,
                            Policy::Classified};
// The stage-time plot's values at most (stage_plot.h): about one per two of its pixels.
constexpr size_t kPlotPoints = 150;
const Overlay kOverlays[] = {Overlay::None, Overlay::Items, Overlay::Cost, Overlay::Benefit, Overlay::Ids, Overlay::Traced};

}  // namespace

UiRequests Panels::draw(const Session& session, UiView& view) {
  UiRequests r;
  ImGui::SetNextWindowPos(ImVec2(view.panelX, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(view.panelWidth, view.height));
  const std::string title = session.scene().path.filename().string() + (session.modified() ? " *" : "") + "###panel";
  ImGui::Begin(title.c_str(), nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  if (ImGui::Button("Undo") || (ImGui::GetIO().KeyCtrl && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Z)))) r.undo = true;
  ImGui::SameLine();
  if (ImGui::Button("Redo") || (ImGui::GetIO().KeyCtrl && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Y)))) r.redo = true;
  ImGui::SameLine();
  if (ImGui::Button("Save")) r.save = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset camera")) r.resetCamera = true;
  ImGui::TextWrapped("%s", view.message.c_str());
  ImGui::Separator();
  budgetPanel(session, r);
  objectPanel(session, view, r);
  objectList(session, view, r);
  statsPanel(session, view);
  quitPrompt(session, view, r);
  ImGui::End();
  return r;
}

void Panels::budgetPanel(const Session& session, UiRequests& r) {
  if (!ImGui::CollapsingHeader("Budget", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const RenderSettings& s = session.settings();
  if (budget_ < 0.0f) budget_ = s.budgetMs;
  ImGui::SliderFloat("T (ms)", &budget_, 1.0f, 1000.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemDeactivatedAfterEdit()) r.budget = budget_;
  if (ImGui::BeginCombo("policy", policyName(s.policy))) {
    for (Policy p : kPolicies)
      if (ImGui::Selectable(policyName(p), p == s.policy)) r.policy = p;
    ImGui::EndCombo();
  }
  if (ImGui::BeginCombo("tracer", tracerName(s.rayTracing.tracer))) {
    for (Tracer t : {Tracer::Compute, Tracer::Native})
      if (ImGui::Selectable(tracerName(t), t == s.rayTracing.tracer)) r.tracer = t;
    ImGui::EndCombo();
  }
  const std::vector<float> values = runPeaks(session.stageMsHistory(), kPlotPoints);
  float top = s.budgetMs * 1.5f;
  for (float v : values) top = std::max(top, v);
  const std::string caption = "stage ms (T " + std::to_string(int(s.budgetMs + 0.5f)) + ")";
  ImGui::PlotLines("##stage", values.data(), int(values.size()), 0, caption.c_str(), 0.0f, top, ImVec2(ImGui::GetContentRegionAvail().x, 70.0f));
  // T as a line across the plot.
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  const float y = hi.y - (hi.y - lo.y) * (s.budgetMs / top);
  ImGui::GetWindowDrawList()->AddLine(ImVec2(lo.x, y), ImVec2(hi.x, y), IM_COL32(255, 80, 60, 255));
  if (isBudgeted(s.policy))
    ImGui::Text("frames over T: %llu of %llu", (unsigned long long)session.framesOverBudget(), (unsigned long long)session.budgetedFrames());
  const FrameTiming& t = session.lastTiming();
  ImGui::Text("stage %.2f ms, trace %.2f (predicted %.2f), %u objects", t.rtStageMs(), t.measuredTraceMs, t.predictedTraceMs, t.selectedObjects);
}

void Panels::objectPanel(const Session& session, const UiView& view, UiRequests& r) {
  if (!ImGui::CollapsingHeader("Picked object", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const std::vector<ObjectRow>& rows = session.rows();
  if (view.picked < 0 || size_t(view.picked) >= rows.size()) {
    ImGui::TextUnformatted("click an object in the viewport or the list");
    editedObject_ = -1;
    return;
  }
  const ObjectRow& row = rows[size_t(view.picked)];
  const std::array<float, 3> now{row.K, row.Q, row.I};
  if (editedObject_ != view.picked) typed_ = now;
  editedObject_ = view.picked;
  ImGui::Text("%s (id %u)", row.name.c_str(), row.id);
  const ObjectMetrics& m = row.metrics;
  ImGui::Text("A %.4f  P %.3f  D %.2f  V %.5f", m.A, m.P, m.D, m.V);
  ImGui::Text("C %.5f  R %.5f  S %d  candidate %d", m.C, m.R, int(row.selectedLastFrame), int(m.candidate));
  const Param params[] = {Param::K, Param::Q, Param::I};
  const float maxima[] = {100.0f, 64.0f, 10.0f};
  for (int i = 0; i < 3; ++i) {
    ImGui::PushID(i);
    float slider = now[size_t(i)];
    ImGui::SetNextItemWidth(view.panelWidth * 0.45f);
    ImGui::SliderFloat("##slider", &slider, 0.0f, maxima[i], "%.3f", ImGuiSliderFlags_Logarithmic);
    if (ImGui::IsItemDeactivatedAfterEdit()) r.set = {params[i], slider};
    ImGui::SameLine();
    ImGui::SetNextItemWidth(view.panelWidth * 0.3f);
    if (!ImGui::IsAnyItemActive()) typed_[size_t(i)] = now[size_t(i)];  // the typed field follows the value unless being edited
    if (ImGui::InputFloat(paramName(params[i]), &typed_[size_t(i)], 0.0f, 0.0f, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue))
      r.set = {params[i], typed_[size_t(i)]};
    ImGui::PopID();
  }
  if (ImGui::BeginTable("items", 5, ImGuiTableFlags_Borders)) {
    for (const char* h : {"item", "traced", "value", "pred ms", "meas ms"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (int e = 0; e < 3; ++e) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(kItemNames[e]);
      ImGui::TableNextColumn();
      // The partial item: traced on a share of its tiles (docs/SELECTION.md).
      if (((m.selectedItems >> e) & 1u) && m.itemTileShare[size_t(e)] < 1.0f) {
        ImGui::Text("%.0f%% tiles", 100.0 * double(m.itemTileShare[size_t(e)]));
      } else {
        ImGui::TextUnformatted((m.selectedItems >> e) & 1u ? "yes" : "no");
      }
      ImGui::TableNextColumn();
      ImGui::Text("%.4f", m.itemBenefit[e]);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", row.predictedMs[size_t(e)]);
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", row.measuredMs[size_t(e)]);
    }
    ImGui::EndTable();
  }
}

void Panels::objectList(const Session& session, const UiView& view, UiRequests& r) {
  if (!ImGui::CollapsingHeader("Objects", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::InputText("filter", filter_, sizeof(filter_));
  const int overlayIndex = int(view.overlay);
  if (ImGui::BeginCombo("overlay", overlayName(view.overlay))) {
    for (Overlay o : kOverlays)
      if (ImGui::Selectable(overlayName(o), int(o) == overlayIndex)) r.overlay = o;
    ImGui::EndCombo();
  }
  const int columns = int(Column::Count);
  // No alternating row colours: on lavapipe each row-wide rectangle costs as much as a
  // dozen glyphs (the list's rows are most of the UI pass's time).
  const ImGuiTableFlags flags =
      ImGuiTableFlags_Sortable | ImGuiTableFlags_ScrollX | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersOuter | ImGuiTableFlags_Resizable;
  if (!ImGui::BeginTable("objects", columns, flags, ImVec2(0.0f, 260.0f))) return;
  ImGui::TableSetupScrollFreeze(1, 1);
  for (int c = 0; c < columns; ++c)
    ImGui::TableSetupColumn(columnName(Column(c)), c == 0 ? ImGuiTableColumnFlags_DefaultSort : ImGuiTableColumnFlags_None);
  ImGui::TableHeadersRow();
  if (ImGuiTableSortSpecs* specs = ImGui::TableGetSortSpecs(); specs && specs->SpecsCount > 0) {
    sortColumn_ = Column(specs->Specs[0].ColumnIndex);
    sortAscending_ = specs->Specs[0].SortDirection == ImGuiSortDirection_Ascending;
  }
  for (const ObjectRow* row : visibleRows(session.rows(), filter_, sortColumn_, sortAscending_)) {
    const ObjectMetrics& m = row->metrics;
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    if (ImGui::Selectable(row->name.c_str(), int(row->id) == view.picked, ImGuiSelectableFlags_SpanAllColumns)) r.pick = int(row->id);
    const float values[] = {row->K, row->Q, row->I, m.A, m.P, m.D, m.V, m.C, m.R};
    for (float v : values) {
      ImGui::TableNextColumn();
      ImGui::Text("%.4g", v);
    }
    ImGui::TableNextColumn();
    ImGui::Text("%d", int(row->selectedLastFrame));
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(itemsText(m).c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%.4g", double(m.itemBenefit[0]) + m.itemBenefit[1] + m.itemBenefit[2]);
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", row->predictedTotal());
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", row->measuredTotal());
  }
  ImGui::EndTable();
}

void Panels::statsPanel(const Session& session, const UiView& view) {
  if (!ImGui::CollapsingHeader("Frame")) return;
  const FrameTiming& t = session.lastTiming();
  for (size_t p = 0; p < kPassCount; ++p)
    if (t.passMs[p]) ImGui::Text("%-14s %7.2f ms", passName(Pass(p)), *t.passMs[p]);
  ImGui::Text("%-14s %7.2f ms GPU, %.2f ms CPU", "ui", view.uiGpuMs, view.uiCpuMs);
  ImGui::Text("%-14s %7.2f ms", "frame (wall)", view.frameMs);
}

void Panels::quitPrompt(const Session& session, UiView& view, UiRequests& r) {
  if (view.quitPrompt && !ImGui::IsPopupOpen("Unsaved changes")) ImGui::OpenPopup("Unsaved changes");
  if (!ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::Text("%s has unsaved K/Q/I edits.", session.scene().path.filename().string().c_str());
  if (ImGui::Button("Save and quit")) {
    r.save = true;
    r.quit = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Quit without saving")) r.quit = true;
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) view.quitPrompt = false;
  if (r.quit || !view.quitPrompt) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

}  // namespace raybudget::editor
