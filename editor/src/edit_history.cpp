#include "edit_history.h"

namespace raybudget::editor {

bool sameParams(const RayBudgetParams& a, const RayBudgetParams& b) {
  return a.importanceK == b.importanceK && a.raysQ == b.raysQ && a.hysteresisI == b.hysteresisI;
}

void EditHistory::record(const Edit& edit) {
  edits_.resize(done_);
  edits_.push_back(edit);
  ++done_;
}

std::optional<Edit> EditHistory::undo() {
  if (!canUndo()) return std::nullopt;
  return edits_[--done_];
}

std::optional<Edit> EditHistory::redo() {
  if (!canRedo()) return std::nullopt;
  return edits_[done_++];
}

}  // namespace raybudget::editor
