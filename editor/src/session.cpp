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

bool Session::undo(std::string& message) {
  const std::optional<ParamEdit> edit = history_.undo();
  if (!edit) {
    message = "nothing to undo";
    return false;
  }
  applyParams(edit->objectId, edit->before);
  message = "undid the edit of " + scene_.objects[edit->objectId].name;
  return true;
}

bool Session::redo(std::string& message) {
  const std::optional<ParamEdit> edit = history_.redo();
  if (!edit) {
    message = "nothing to redo";
    return false;
  }
  applyParams(edit->objectId, edit->after);
  message = "redid the edit of " + scene_.objects[edit->objectId].name;
  return true;
}

void Session::save(const std::filesystem::path& path) {
  std::vector<std::pair<int, RayBudgetParams>> nodes;
  for (uint32_t id : edited_)
    if (scene_.objects[id].gltfNode >= 0) nodes.emplace_back(scene_.objects[id].gltfNode, scene_.objects[id].params);
  saveRayBudgetParams(scene_.path, path, nodes);
  history_.markSaved();
}

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

bool Session::setBudget(double ms, std::string& message) {
  if (!restart(settings_.policy, ms, message)) return false;
  message = "budget " + number(ms) + " ms";
  return true;
}

bool Session::setPolicy(Policy policy, std::string& message) {
  if (!restart(policy, settings_.budgetMs, message)) return false;
  message = std::string("policy ") + policyName(policy);
  return true;
}

bool Session::setTracer(Tracer tracer, std::string& message) {
  RenderSettings next = settings_;
  next.rayTracing.tracer = tracer;
  try {
    core_->completedFrames(true);
    core_.reset();  // one context on the device at a time; the new tracer learns its own cost model
    core_ = std::make_unique<core::Context>(host_, scene_, next);
    settings_ = next;
  } catch (const Error& e) {
    message = e.what();
    if (!core_) core_ = std::make_unique<core::Context>(host_, scene_, settings_);
    ++coreGeneration_;
    return false;
  }
  ++coreGeneration_;
  message = std::string("tracer ") + tracerName(tracer);
  return true;
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
