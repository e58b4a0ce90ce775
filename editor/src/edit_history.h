// Undo and redo of every edit the editor makes: an object's K, Q and I (the document, what
// save writes into the glTF), and the budget, policy and tracer (the session's settings,
// not saved). Each edit stores the values before and after, so undoing applies `before`
// and redoing `after`; a new edit drops what could be redone.
#pragma once
#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

#include "raybudget/scene.h"
#include "raybudget/settings.h"

namespace raybudget::editor {

struct ParamEdit {
  uint32_t objectId = 0;
  RayBudgetParams before, after;
};

struct SessionSettings {
  Policy policy = Policy::None;
  float budgetMs = 0.0f;
  Tracer tracer = Tracer::Compute;
  bool operator==(const SessionSettings&) const = default;
};

struct SettingsEdit {
  SessionSettings before, after;
};

using Edit = std::variant<ParamEdit, SettingsEdit>;

class EditHistory {
 public:
  void record(const Edit& edit);
  // The edit to apply `before` of, and moves it to the redo side; nothing when there is none.
  std::optional<Edit> undo();
  // The edit to apply `after` of again; nothing when there is none.
  std::optional<Edit> redo();
  bool canUndo() const { return done_ > 0; }
  bool canRedo() const { return done_ < edits_.size(); }

 private:
  std::vector<Edit> edits_;
  size_t done_ = 0;  // edits_[0, done_) are applied
};

bool sameParams(const RayBudgetParams& a, const RayBudgetParams& b);

}  // namespace raybudget::editor
