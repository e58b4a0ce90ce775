#include "edit_history.h"

#include <cstdint>

namespace raybudget::editor {

bool sameParams(const RayBudgetParams& a, const RayBudgetParams& b) {
  return a.importanceK == b.importanceK && a.raysQ == b.raysQ && a.hysteresisI == b.hysteresisI;
}

void EditHistory::record(const ParamEdit& edit) {
  if (savedAt_ > done_) savedAt_ = SIZE_MAX;  // the saved state was undone and is now unreachable
  edits_.resize(done_);
  edits_.push_back(edit);
  ++done_;
}

std::optional<ParamEdit> EditHistory::undo() {
  if (!canUndo()) return std::nullopt;
  return edits_[--done_];
}

std::optional<ParamEdit> EditHistory::redo() {
  if (!canRedo()) return std::nullopt;
  return edits_[done_++];
}

}  // namespace raybudget::editor
