// Undo and redo of the editor's edits to the document: an object's K, Q and I (what save
// writes into the glTF). Each edit stores the values before and after, so undoing applies
// `before` and redoing `after`; a new edit drops what could be redone.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "raybudget/scene.h"

namespace raybudget::editor {

struct ParamEdit {
  uint32_t objectId = 0;
  RayBudgetParams before, after;
};

class EditHistory {
 public:
  void record(const ParamEdit& edit);
  // The edit to apply `before` of, and moves it to the redo side; nothing when there is none.
  std::optional<ParamEdit> undo();
  // The edit to apply `after` of again; nothing when there is none.
  std::optional<ParamEdit> redo();
  bool canUndo() const { return done_ > 0; }
  bool canRedo() const { return done_ < edits_.size(); }
  // Whether the document differs from the one last saved (or loaded).
  bool modified() const { return done_ != savedAt_; }
  void markSaved() { savedAt_ = done_; }

 private:
  std::vector<ParamEdit> edits_;
  size_t done_ = 0;     // edits_[0, done_) are applied
  // The value of done_ when the file was saved; SIZE_MAX when that state was dropped by a
  // new edit after undoing past it.
  size_t savedAt_ = 0;
};

bool sameParams(const RayBudgetParams& a, const RayBudgetParams& b);

}  // namespace raybudget::editor
