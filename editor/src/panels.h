// The editor's panels (Dear ImGui), beside the viewport: the budget (T, policy, tracer, the
// ray-tracing stage's time against T over the last frames, frames over T), the picked
// object's K, Q and I (sliders and typed values), the sortable, filterable object list with
// the paper's per-object quantities and the items, the overlay, the per-pass times, and the
// prompt before quitting with unsaved changes. Drawing only: what the user asks for comes
// back as requests the editor applies between frames.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <utility>

#include "object_rows.h"
#include "session.h"

namespace raybudget::editor {

struct UiRequests {
  std::optional<int> pick;  // an object ID
  std::optional<std::pair<Param, double>> set;
  std::optional<double> budget;
  std::optional<Policy> policy;
  std::optional<Tracer> tracer;
  std::optional<Overlay> overlay;
  bool undo = false, redo = false, save = false, resetCamera = false;
  std::string saveAs;  // with save: another file than the scene's own
  bool quit = false;  // confirmed (saved, discarded, or nothing to save)
};

// What the UI shows beside the session.
struct UiView {
  int picked = -1;
  Overlay overlay = Overlay::None;
  std::string message;
  bool quitPrompt = false;  // the window asked to close with unsaved changes
  double uiCpuMs = 0.0, uiGpuMs = 0.0, frameMs = 0.0;
  float panelX = 0.0f, panelWidth = 0.0f, height = 0.0f;
};

class Panels {
 public:
  UiRequests draw(const Session& session, UiView& view);

 private:
  void budgetPanel(const Session& session, UiRequests& r);
  void objectPanel(const Session& session, const UiView& view, UiRequests& r);
  void objectList(const Session& session, const UiView& view, UiRequests& r);
  void statsPanel(const Session& session, const UiView& view);
  void quitPrompt(const Session& session, UiView& view, UiRequests& r);

  char filter_[64] = "";
  Column sortColumn_ = Column::Name;
  bool sortAscending_ = true;
  float budget_ = -1.0f;
  int editedObject_ = -1;
  std::array<float, 3> typed_{};
};

}  // namespace raybudget::editor
