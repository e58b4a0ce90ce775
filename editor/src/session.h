// The document the editor edits and the renderer it drives: the scene (with each object's
// K, Q, I as edited), the core context rendering it with the chosen policy, budget and
// tracer, the undo history, saving into the glTF, and what the last frames measured. No
// window here: the UI and the script both edit through these calls, so they validate and
// undo alike.
#pragma once
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "edit_history.h"
#include "object_rows.h"
#include "raybudget/core.h"

namespace raybudget::editor {

// One parameter of the paper's per object: importance K, rays Q, hysteresis I.
enum class Param { K, Q, I };
Param parseParam(const std::string& letter);  // "K", "Q" or "I"; throws Error otherwise
const char* paramName(Param param);

class Session {
 public:
  static constexpr size_t kHistoryFrames = 300;

  Session(const core::HostDevice& host, Scene scene, const RenderSettings& settings);

  core::Context& core() { return *core_; }
  const Scene& scene() const { return scene_; }
  const RenderSettings& settings() const { return settings_; }

  // Sets one parameter of an object from the next frame on and records it for undo. A
  // negative, non-finite or absurd value is refused: nothing changes and the message says why.
  bool setParam(uint32_t objectId, Param param, double value, std::string& message);
  // Undo and redo step through every edit: K/Q/I and the policy, budget and tracer.
  bool undo(std::string& message);
  bool redo(std::string& message);
  bool canUndo() const { return history_.canUndo(); }
  bool canRedo() const { return history_.canRedo(); }
  // Whether some object's K/Q/I differ from the file's as loaded or last saved.
  bool modified() const;
  // Writes every edited object's K/Q/I into `path` (a copy of the loaded file with the nodes'
  // extras.raybudget replaced). Throws Error naming the file.
  void save(const std::filesystem::path& path);

  // Policy, budget and tracer from the next frame on (every recorded frame has completed),
  // recorded for undo; false with a message on a bad value. A new tracer rebuilds the core
  // context: beforeCoreRebuild is called first (to drop views of the old one's images) and
  // coreGeneration() counts the rebuilds.
  bool setBudget(double ms, std::string& message);
  bool setPolicy(Policy policy, std::string& message);
  bool setTracer(Tracer tracer, std::string& message);
  SessionSettings sessionSettings() const;
  uint32_t coreGeneration() const { return coreGeneration_; }
  std::function<void()> beforeCoreRebuild;

  // After a frame completed: its timing, the objects' metrics and the rows.
  void collectFrame();
  const std::vector<ObjectRow>& rows() const { return rows_; }
  const FrameTiming& lastTiming() const { return last_; }
  const std::deque<float>& stageMsHistory() const { return stageMs_; }
  uint64_t framesOverBudget() const { return overBudget_; }
  uint64_t budgetedFrames() const { return budgeted_; }
  const std::vector<FrameTiming>& allTimings() const { return timings_; }

  int findObject(const std::string& name) const;  // -1 when none has the name

 private:
  void applyParams(uint32_t objectId, const RayBudgetParams& params);
  // Restarts the selection with this policy and budget; false with the message on a bad value.
  bool restart(Policy policy, double budgetMs, std::string& message);
  bool change(const SessionSettings& next, std::string& message);  // applied and recorded
  bool applySettings(const SessionSettings& next, std::string& message);
  bool step(const std::optional<Edit>& edit, bool undoing, std::string& message);

  Scene scene_;
  RenderSettings settings_;
  core::HostDevice host_;
  std::unique_ptr<core::Context> core_;
  uint32_t coreGeneration_ = 0;
  EditHistory history_;
  std::set<uint32_t> edited_;  // objects whose extras save rewrites
  std::vector<RayBudgetParams> savedParams_;  // per object, as loaded or last saved
  std::vector<ObjectMetrics> metrics_, previousMetrics_;
  std::vector<ObjectRow> rows_;
  FrameTiming last_;
  std::deque<float> stageMs_;
  std::vector<FrameTiming> timings_;
  uint64_t overBudget_ = 0, budgeted_ = 0;
};

}  // namespace raybudget::editor
