#include "session.h"

#include <cmath>
#include <cstdio>

#include "raybudget/error.h"

namespace raybudget::editor {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

}  // namespace

Param parseParam(const std::string& letter) {
  if (letter == "K") return Param::K;
  if (letter == "Q") return Param::Q;
  if (letter == "I") return Param::I;
  throw Error("the parameter must be K, Q or I, got '" + letter + "'");
}

const char* paramName(Param param) { return param == Param::K ? "K" : param == Param::Q ? "Q" : "I"; }

Session::Session(const core::HostDevice& host, Scene scene, const RenderSettings& settings)
    : scene_(std::move(scene)), settings_(settings), host_(host) {
  settings_.objectMetrics = true;  // the object list shows A, P, D, V, C, R each frame
  core_ = std::make_unique<core::Context>(host_, scene_, settings_);
  for (const Object& o : scene_.objects) savedParams_.push_back(o.params);
}

bool Session::setParam(uint32_t objectId, Param param, double value, std::string& message) {
  if (objectId >= scene_.objects.size()) {
    message = "no object is picked";
    return false;
  }
  const Object& object = scene_.objects[objectId];
  RayBudgetParams next = object.params;
  // Values beyond float's range become infinity and are refused below like any absurd one.
  const float v = std::isfinite(value) && std::fabs(value) < 3.0e38 ? float(value) : float(INFINITY);
  (param == Param::K ? next.importanceK : param == Param::Q ? next.raysQ : next.hysteresisI) = v;
  try {
    validateRayBudgetParams(next, "object '" + object.name + "'");
  } catch (const Error& e) {
    message = std::string(e.what()) + "; nothing changed";
    return false;
  }
  const ParamEdit edit{objectId, object.params, next};
  applyParams(objectId, next);
  history_.record(edit);
  message = object.name + ": " + paramName(param) + " = " + number(v);
  return true;
}

void Session::applyParams(uint32_t objectId, const RayBudgetParams& params) {
  core_->setObjectParams(objectId, params);
  scene_.objects[objectId].params = params;
  edited_.insert(objectId);
}

bool Session::undo(std::string& message) { return step(history_.undo(), true, message); }

bool Session::redo(std::string& message) { return step(history_.redo(), false, message); }

bool Session::step(const std::optional<Edit>& edit, bool undoing, std::string& message) {
  const char* verb = undoing ? "undid" : "redid";
  if (!edit) {
    message = undoing ? "nothing to undo" : "nothing to redo";
    return false;
  }
  if (const auto* p = std::get_if<ParamEdit>(&*edit)) {
    applyParams(p->objectId, undoing ? p->before : p->after);
    message = std::string(verb) + " the edit of " + scene_.objects[p->objectId].name;
    return true;
  }
  const SettingsEdit& e = std::get<SettingsEdit>(*edit);
  if (!applySettings(undoing ? e.before : e.after, message)) return false;
  message = std::string(verb) + " the change of " + message;
  return true;
}

bool Session::modified() const {
  for (size_t i = 0; i < scene_.objects.size(); ++i)
    if (!sameParams(scene_.objects[i].params, savedParams_[i])) return true;
  return false;
}

void Session::save(const std::filesystem::path& path) {
  std::vector<std::pair<int, RayBudgetParams>> nodes;
  for (uint32_t id : edited_)
    if (scene_.objects[id].gltfNode >= 0) nodes.emplace_back(scene_.objects[id].gltfNode, scene_.objects[id].params);
  saveRayBudgetParams(scene_.path, path, nodes);
  for (size_t i = 0; i < scene_.objects.size(); ++i) savedParams_[i] = scene_.objects[i].params;
}

SessionSettings Session::sessionSettings() const { return {settings_.policy, settings_.budgetMs, settings_.rayTracing.tracer}; }

bool Session::restart(Policy policy, double budgetMs, std::string& message) {
  try {
    core_->completedFrames(true);
    core_->restartSelection(policy, float(budgetMs), settings_.benefitAblation, settings_.rayTracing.rate);
  } catch (const Error& e) {
    message = e.what();
    return false;
  }
  settings_.policy = policy;
  settings_.budgetMs = float(budgetMs);
  return true;
}

bool Session::change(const SessionSettings& next, std::string& message) {
  const SessionSettings before = sessionSettings();
  if (next == before) return true;
  if (!applySettings(next, message)) return false;
  history_.record(SettingsEdit{before, next});
  return true;
}

bool Session::applySettings(const SessionSettings& next, std::string& message) {
  const SessionSettings now = sessionSettings();
  if (next.tracer != now.tracer) {
    RenderSettings rebuilt = settings_;
    rebuilt.policy = next.policy;
    rebuilt.budgetMs = next.budgetMs;
    rebuilt.rayTracing.tracer = next.tracer;
    try {
      validateSettings(rebuilt);
      core_->completedFrames(true);
      if (beforeCoreRebuild) beforeCoreRebuild();
      core_.reset();  // one context on the device at a time; the new tracer learns its own cost model
      ++coreGeneration_;
      core_ = std::make_unique<core::Context>(host_, scene_, rebuilt);
    } catch (const Error& e) {
      message = e.what();
      if (!core_) core_ = std::make_unique<core::Context>(host_, scene_, settings_);
      return false;
    }
    settings_ = rebuilt;
  } else if (!restart(next.policy, next.budgetMs, message)) {
    return false;
  }
  message = std::string("policy ") + policyName(next.policy) + ", budget " + number(next.budgetMs) + " ms, tracer " + tracerName(next.tracer);
  return true;
}

bool Session::setBudget(double ms, std::string& message) {
  SessionSettings next = sessionSettings();
  next.budgetMs = float(ms);
  if (!std::isfinite(ms) || ms <= 0.0 || ms > 1e6) {
    message = "the budget must be a positive number of milliseconds, got " + number(ms);
    return false;
  }
  return change(next, message);
}

bool Session::setPolicy(Policy policy, std::string& message) {
  SessionSettings next = sessionSettings();
  next.policy = policy;
  return change(next, message);
}

bool Session::setTracer(Tracer tracer, std::string& message) {
  SessionSettings next = sessionSettings();
  next.tracer = tracer;
  return change(next, message);
}

void Session::collectFrame() {
  for (const FrameTiming& t : core_->completedFrames(true)) {
    last_ = t;
    timings_.push_back(t);
    if (isBudgeted(settings_.policy)) {
      ++budgeted_;
      if (t.rtStageMs() > t.budgetMs) ++overBudget_;
    }
    stageMs_.push_back(float(t.rtStageMs()));
    if (stageMs_.size() > kHistoryFrames) stageMs_.pop_front();
  }
  previousMetrics_ = std::move(metrics_);
  metrics_ = core_->objectMetrics();
  std::vector<RayBudgetParams> params(scene_.objects.size());
  for (uint32_t i = 0; i < params.size(); ++i) params[i] = core_->objectParams(i);
  rows_ = buildRows(scene_, params, metrics_, previousMetrics_, core_->costModel(), last_, settings_.width, settings_.height);
}

int Session::findObject(const std::string& name) const {
  for (const Object& o : scene_.objects)
    if (o.name == name) return int(o.id);
  return -1;
}

}  // namespace raybudget::editor
