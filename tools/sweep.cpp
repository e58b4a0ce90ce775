#include "sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <sstream>

#include <glm/gtc/packing.hpp>

#include "cli_options.h"
#include "path_json.h"
#include "raybudget/raybudget.h"

namespace raybudget::cli {

const char* kSweepUsage = R"(usage: raybudget sweep SCENE.gltf|SCENE.glb [options]
  --out DIR             output folder (default ./sweep): frames.csv, calibration.csv, paths/*.json, images/
  --width W --height H  image size (default 640x360)
  --frames N            recorded frames per camera path and configuration (default 4)
  --warmup N            frames on the path's first camera before them, not recorded (default 8)
  --lead-in N           frames of the camera moving along the path (a hundredth of the recorded
                        frames' spacing a frame) before the last recorded frame, not recorded;
                        the others follow a jump (default 0, at most 99)
  --budgets N           budgets: 100, 25, 50, 10 and 20% of full RT's stage cost (as many as N
                        allows), then twice the stage's fixed cost, then the widest gaps in log
                        cost (default 6)
  --budget-list LIST    comma-separated budgets in ms instead
  --repeats N           runs of every configuration, each imaged (default 3)
  --order-seed S        shuffles each repeat's configurations (default 1; 0: all, none, budgets ascending)
  --prior-time-scale    never learn the cost model's time scale: selections independent of timing
  --policies LIST       comma-separated budgeted policies (default paper,density,nearest,random,benefit);
                        benefit-no-centrality, -no-hysteresis, -prior-only, -no-classifier, -no-probe: ablations;
                        benefit-rates: benefit choosing a ray rate per item
  --no-screen-space-transmission
                        glass falls back to the environment alone (the fallbacks' ablation)
  --no-reflection-probes
                        reflections fall back to the sky alone (the fallbacks' ablation)
  --no-screen-space-reflections
                        no screen-space reflections (the fallbacks' ablation)
  --no-temporal-fill    reduced rates fill from traced neighbours alone
                        (RayTracingSettings::temporalFill off)
  --shadow-normal-offset X
                        shadow-map lookups' normal offset in texels (RenderSettings::shadowNormalOffset)
  --shadow-slope-bias X the shadow pass's slope-scaled depth bias (RenderSettings::shadowSlopeBias)
  --budget-confidence C the budgeted policies' headroom quantile, 0.5..0.99
                        (RenderSettings::budgetConfidence, default 0.9)
  --no-stage-deadline   the trace passes trace all that was selected even past T
                        (RenderSettings::stageDeadline off)
  --no-classified       leave out `classified` (every item, shadows where the map is uncertain),
                        which otherwise runs in every repeat beside all and none
  --paths LIST          comma-separated camera paths: orbit, flythrough (default both)
  --replay-paths DIR    each path's cameras from DIR/NAME.json, as an earlier sweep wrote them
                        (its OUT/paths): like-for-like runs after the paths change; --frames
                        must equal the file's
  --device NAME, --validation
)";

namespace {

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<Camera> cameraPath(const std::string& name, const Camera& start, uint32_t frames, FlythroughShape shape) {
  std::vector<Camera> path;
  for (uint32_t f = 0; f < frames; ++f) path.push_back(cameraOnPath(name, start, f, frames, shape));
  return path;
}

// The cameras an earlier sweep recorded for `name` (--replay-paths), as many as --frames.
std::vector<Camera> replayedPath(const SweepCommand& c, const std::string& name, const Camera& start) {
  const std::filesystem::path file = std::filesystem::path(c.replayPaths) / (name + ".json");
  std::vector<Camera> path = readPathJson(file, start);
  if (path.size() != c.frames)
    throw Error(file.string() + " holds " + std::to_string(path.size()) + " cameras, --frames asks for " + std::to_string(c.frames));
  return path;
}

std::vector<float> linearRgb(const FrameImages& img) {
  std::vector<float> rgb;
  rgb.reserve(size_t(img.width) * img.height * 3);
  for (size_t p = 0; p < size_t(img.width) * img.height; ++p)
    for (int c = 0; c < 3; ++c) rgb.push_back(glm::unpackHalf1x16(img.hdrRgba16[p * 4 + c]));
  return rgb;
}

double meanSquaredError(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += double(a[i] - b[i]) * double(a[i] - b[i]);
  return a.empty() ? 0.0 : sum / double(a.size());
}

std::string frameFile(size_t frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "%04zu.png", frame);
  return name;
}

std::string passCell(const FrameTiming& t, Pass p) {
  return t.passMs[size_t(p)] ? std::to_string(*t.passMs[size_t(p)]) : std::string();  // empty: skipped
}

// One configuration of the sweep: a policy at a budget (all and none: index 0, no budget).
// The policy whose calibration learns `p`'s cost unit (CostModel): the paper's C, benefit's
// item work, the other policies' object work.
Policy costUnitPolicy(Policy p) { return p == Policy::Paper || p == Policy::Benefit ? p : Policy::Density; }

struct Config {
  Policy policy;
  uint32_t budgetIndex = 0;
  float budgetMs = 0.0f;
  BenefitAblation ablation = BenefitAblation::None;
  ItemRate rate = ItemRate::Full;
  std::string name() const { return SweepPolicy{policy, ablation, rate}.name(); }
  std::string label() const { return name() + (isBudgeted(policy) ? "-b" + std::to_string(budgetIndex) : std::string()); }
};

// Where a run's images go and what its rows say: a repeat (with its place in the repeat's
// order), or the path's pilot / calibration runs (not in frames.csv).
struct RunKind {
  bool recorded = false;
  uint32_t repeat = 0, order = 0;
  std::string imageDir;  // relative to --out; empty: no images
  bool reference = false;  // this run's images are the path's reference
};

class Sweep {
 public:
  Sweep(const SweepCommand& c, const Scene& scene, Renderer& renderer, std::ofstream& csv, uint64_t totalFrames)
      : c_(c), scene_(scene), renderer_(renderer), csv_(csv), total_(totalFrames) {}

  // Every configuration starts from this learned state (budgeted policies).
  void startFrom(const CostModel& model) { start_ = model; }

  // One configuration over one camera path: restart the selection from the saved cost
  // model, warm up on the first camera at the configuration's budget, then the recorded
  // frames, each read back when imaged. Returns the recorded frames' timings.
  std::vector<FrameTiming> run(const std::string& pathName, const std::vector<Camera>& path, const Config& cfg, const RunKind& kind) {
    renderer_.restartSelection(cfg.policy, isBudgeted(cfg.policy) ? cfg.budgetMs : 1.0f, cfg.ablation, cfg.rate);
    if (isBudgeted(cfg.policy)) renderer_.setCostModel(start_);
    const std::filesystem::path dir = std::filesystem::path(c_.out) / kind.imageDir;
    if (!kind.imageDir.empty()) std::filesystem::create_directories(dir);
    std::vector<FrameTiming> all;
    std::vector<double> rmse(path.size(), -1.0);
    auto collect = [&](const std::vector<FrameTiming>& done) { all.insert(all.end(), done.begin(), done.end()); };
    std::vector<uint64_t> recordedAt;  // the renderer's frame number of each recorded frame
    for (uint32_t w = 0; w < c_.warmup; ++w) render(path.front(), collect);
    for (size_t f = 0; f < path.size(); ++f) {
      // The last recorded frame follows the camera's approach along the path (--lead-in); the
      // others follow a jump from the frame before (or the still warm-up).
      if (f + 1 == path.size())
        for (const Camera& camera : leadIn_) render(camera, collect);
      recordedAt.push_back(rendered_);
      render(path[f], collect);
      if (kind.imageDir.empty()) continue;
      const FrameImages img = renderer_.readback();
      writePng(dir / frameFile(f), img.width, img.height, img.ldrRgba8);
      std::vector<float> rgb = linearRgb(img);
      if (kind.reference) reference_[f] = std::move(rgb);
      rmse[f] = kind.reference ? 0.0 : std::sqrt(meanSquaredError(rgb, reference_.at(f)));
    }
    collect(renderer_.finish());
    std::vector<FrameTiming> recorded;
    for (const FrameTiming& t : all) {
      const auto at = std::find(recordedAt.begin(), recordedAt.end(), t.frame);
      if (at == recordedAt.end()) continue;
      const size_t f = size_t(at - recordedAt.begin());
      recorded.push_back(t);
      if (kind.recorded) writeRow(pathName, cfg, kind, f, f + 1 == path.size() ? leadIn_.size() : 0, t, rmse[f]);
    }
    csv_.flush();
    return recorded;
  }

  // A new camera path; `leadIn`: the cameras before its last recorded frame (--lead-in).
  void newPath(std::vector<Camera> leadIn) {
    reference_.clear();
    leadIn_ = std::move(leadIn);
  }

 private:
  void writeRow(const std::string& pathName, const Config& cfg, const RunKind& kind, size_t f, size_t leadIn, const FrameTiming& t, double rmse) {
    const bool budgeted = isBudgeted(cfg.policy);
    csv_ << std::filesystem::path(scene_.path).stem().string() << ',' << pathName << ',' << cfg.name() << ',' << cfg.budgetIndex << ','
         << (budgeted ? cfg.budgetMs : 0.0f) << ',' << kind.repeat << ',' << kind.order << ',' << f << ',' << leadIn << ',' << passCell(t, Pass::Coverage) << ','
         << passCell(t, Pass::Select) << ',' << t.traceMs() << ',' << passCell(t, Pass::TraceShadows) << ',' << passCell(t, Pass::TraceEffects) << ','
         << passCell(t, Pass::FillEffects) << ',' << t.rtStageMs() << ',' << passCell(t, Pass::ShadowMaps) << ','
         << t.totalMs() << ',' << t.predictedTraceMs << ',' << t.traceBudgetMs << ',' << t.candidatesMs << ','
         << t.selectedObjects << ',' << t.raysTraced << ',' << t.selectedValue << ',' << t.optimalValueBound << ',' << t.selectionChanges << ','
         << t.itemOptionChanges << ',' << t.partialShare << ',' << t.deadlineCutPixels << ',' << t.fillCutPixels << ',';
    if (rmse >= 0.0) {
      const double mse = rmse * rmse;
      csv_ << rmse << ',' << (mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity()) << ','
           << (std::filesystem::path(kind.imageDir) / frameFile(f)).string();
    } else {
      csv_ << ",,";
    }
    csv_ << '\n';
  }

  template <typename Collect>
  void render(const Camera& camera, Collect&& collect) {
    collect(renderer_.render(camera));
    ++rendered_;
    ++done_;
    if (done_ % 8 == 0 || done_ == total_) {
      std::printf("progress %llu %llu\n", (unsigned long long)done_, (unsigned long long)total_);
      std::fflush(stdout);
    }
  }

  const SweepCommand& c_;
  const Scene& scene_;
  Renderer& renderer_;
  std::ofstream& csv_;
  uint64_t total_, done_ = 0, rendered_ = 0;
  CostModel start_;
  std::map<size_t, std::vector<float>> reference_;
  std::vector<Camera> leadIn_;
};

// A run's mean stage time over its recorded frames: the statistic the benchmark's cost axis
// uses (a median over frames would miss the frames that cost: on a fly-through that leaves
// the object behind, most frames trace nothing).
double meanStageMs(const std::vector<FrameTiming>& t) {
  double sum = 0.0;
  for (const FrameTiming& x : t) sum += x.rtStageMs();
  return t.empty() ? 0.0 : sum / double(t.size());
}

// The budgets: the shares of the full-RT stage cost the benchmark's headline reads (100, 25,
// 50 and 10%, in that order of need), so that each headline figure reads a point measured at
// its own budget rather than one interpolated (or carried) across a gap; then 20%, so that a
// point that overshoots 25% still has a measured neighbour below it within the metric's
// factor 2 (else the metric carries the 10% point's error); then twice the stage's fixed cost
// (where something beyond the fixed passes can be traced) where that lies well below 10%;
// further budgets go to the widest gaps in log cost. Ascending.
std::vector<float> budgetSweep(double fixedMs, double fullMs, uint32_t count) {
  const double top = std::max(fullMs, 1e-3);
  std::vector<double> points;
  for (double share : {1.0, 0.25, 0.5, 0.1, 0.2})
    if (points.size() < count) points.push_back(share * top);
  const double low = std::clamp(2.0 * fixedMs, top / 64.0, top / 2.0);
  if (points.size() < count && low < 0.1 * top / 1.25) points.push_back(low);
  std::sort(points.begin(), points.end());
  while (points.size() < count) {
    size_t widest = 1;
    for (size_t i = 2; i < points.size(); ++i)
      if (points[i] / points[i - 1] > points[widest] / points[widest - 1]) widest = i;
    points.insert(points.begin() + ptrdiff_t(widest), std::sqrt(points[widest] * points[widest - 1]));
  }
  return std::vector<float>(points.begin(), points.end());
}

// Fisher-Yates with mt19937, which the standard specifies exactly (std::shuffle's
// algorithm is the library's): the same order on every platform.
template <typename T>
void shuffle(std::vector<T>& v, uint32_t seed) {
  std::mt19937 rng(seed);
  for (size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[rng() % i]);
}

}  // namespace

SweepPolicy parseSweepPolicy(const std::string& name) {
  const std::string prefix = "benefit-";
  if (name == "benefit-rates") return {Policy::Benefit, BenefitAblation::None, ItemRate::Auto};
  if (name.rfind(prefix, 0) == 0) return {Policy::Benefit, parseAblation(name.substr(prefix.size()))};
  const Policy policy = parsePolicy(name);
  if (!isBudgeted(policy)) throw Error("--policies takes budgeted policies (paper, density, nearest, random, benefit), got '" + name + "'");
  return {policy};
}

SweepCommand parseSweep(const std::vector<std::string>& args) {
  SweepCommand c;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& { return optionValue(args, i); };
    if (c.target.parse(args, i) || parseImageOption(args, i, c.image)) continue;
    if (a == "--out") c.out = value();
    else if (a == "--frames") c.frames = parseUint(a, value(), 1, 100000);
    else if (a == "--warmup") c.warmup = parseUint(a, value(), 0, 1000);
    else if (a == "--lead-in") c.leadIn = parseUint(a, value(), 0, 99);
    else if (a == "--budgets") c.budgets = parseUint(a, value(), 2, 64);
    else if (a == "--repeats") c.repeats = parseUint(a, value(), 1, 100);
    else if (a == "--order-seed") c.orderSeed = parseUint(a, value(), 0, 0x7FFFFFFF);
    else if (a == "--prior-time-scale") c.priorTimeScale = true;
    else if (a == "--budget-list") {
      c.budgetList.clear();
      for (const std::string& b : splitList(value())) c.budgetList.push_back(parsePositive(a, b));
      if (c.budgetList.empty()) throw Error("--budget-list needs at least one budget");
    } else if (a == "--no-classified") {
      c.classified = false;
    } else if (a == "--policies") {
      c.policies.clear();
      for (const std::string& p : splitList(value())) {
        c.policies.push_back(parseSweepPolicy(p));
      }
      if (c.policies.empty()) throw Error("--policies needs at least one policy");
    } else if (a == "--paths") {
      c.paths = splitList(value());
      for (const std::string& p : c.paths)
        if (p != "orbit" && p != "flythrough") throw Error("--paths takes orbit and flythrough, got '" + p + "'");
      if (c.paths.empty()) throw Error("--paths needs at least one path");
    } else if (a == "--replay-paths") {
      c.replayPaths = value();
    } else sceneArgument(a, c.scene, std::string("\n") + kSweepUsage);
  }
  if (c.scene.empty()) throw Error(std::string("sweep needs a scene file\n") + kSweepUsage);
  if (c.leadIn > 0 && !c.replayPaths.empty())
    throw Error("--lead-in follows the named camera paths: --replay-paths gives only the recorded cameras");
  return c;
}

int runSweep(const SweepCommand& c) {
  const Scene scene = loadScene(c.scene);
  RenderSettings s = c.image;
  c.target.applyTo(s);
  s.rayTracing.rate = ItemRate::Quarter;  // makes the fill's history; each configuration sets its own rate
  s.optimalBound = true;
  s.learnTimeScale = !c.priorTimeScale;
  s.policy = Policy::All;
  Renderer renderer(scene, s);
  const std::filesystem::path out(c.out);
  std::filesystem::create_directories(out / "paths");
  std::ofstream csv(out / "frames.csv");
  csv << "scene,path,policy,budget_index,budget_ms,repeat,order,frame,lead_in,coverage_ms,select_ms,trace_ms,trace_shadows_ms,trace_effects_ms,fill_effects_ms,rt_stage_ms,shadow_maps_ms,frame_ms,"
         "predicted_trace_ms,trace_budget_ms,candidates_ms,selected_objects,rays,selected_value,optimal_value_bound,selection_changes,item_option_changes,partial_share,deadline_cut_pixels,fill_cut_pixels,rmse,psnr,image\n";
  std::ofstream calibration(out / "calibration.csv");
  calibration << "path,full_rt_stage_ms,fixed_stage_ms,ms_per_work_unit,ms_per_paper_cost,ms_per_item_work_unit,stage_overhead_ms,trace_fixed_ms,ms_per_ray,ms_per_item_ray,budgets_ms\n";
  // The cost units the policies predict in, each calibrated with a policy that uses it.
  auto uses = [&](Policy unitPolicy) {
    return std::any_of(c.policies.begin(), c.policies.end(), [&](const SweepPolicy& p) { return costUnitPolicy(p.policy) == unitPolicy; });
  };
  std::vector<Policy> calibrated;
  for (const Policy p : {Policy::Paper, Policy::Density, Policy::Benefit})
    if (uses(p)) calibrated.push_back(p);
  const uint32_t budgets = c.budgetList.empty() ? c.budgets : uint32_t(c.budgetList.size());
  const uint32_t calibrationRuns = c.budgetList.empty() ? 2 + 1 + 2 * uint32_t(calibrated.size()) : 1;
  const uint64_t perPath = uint64_t(c.frames + c.warmup + c.leadIn) * (calibrationRuns + uint64_t(c.repeats) * (2 + uint64_t(c.classified) + c.policies.size() * budgets));
  Sweep sweep(c, scene, renderer, csv, perPath * c.paths.size());
  std::cout << "sweep " << c.scene << ": " << scene.objects.size() << " objects, device " << renderer.deviceName() << '\n';
  const Camera start = pathStartCamera(scene, renderer.aspect());
  const FlythroughShape shape = flythroughShape(scene, start);  // a scan of the scene's objects: once
  for (size_t pathIndex = 0; pathIndex < c.paths.size(); ++pathIndex) {
    const std::string& pathName = c.paths[pathIndex];
    const std::vector<Camera> path = c.replayPaths.empty() ? cameraPath(pathName, start, c.frames, shape) : replayedPath(c, pathName, start);
    writePathJson(out / "paths" / (pathName + ".json"), pathName, path);
    std::vector<Camera> leadIn;
    for (uint32_t back = c.leadIn; back > 0; --back) leadIn.push_back(cameraApproaching(pathName, start, c.frames - 1, c.frames, back, shape));
    sweep.newPath(std::move(leadIn));
    // Calibration, not recorded: the reference images (`all`, deterministic), the full-RT
    // stage cost (the mean of two runs' means over the path), the stage's fixed cost (a budget nothing fits:
    // coverage, select and the empty trace dispatches) and the cost model learned at the
    // full budget, twice over the path for each cost unit: the state every configuration
    // then starts from.
    const std::string pathImages = (std::filesystem::path("images") / pathName).string();
    std::vector<double> full{meanStageMs(sweep.run(pathName, path, {Policy::All}, {false, 0, 0, pathImages + "/reference", true}))};
    float fullMs = 0.0f, fixedMs = 0.0f;
    std::vector<float> points = c.budgetList;
    if (points.empty()) {
      full.push_back(meanStageMs(sweep.run(pathName, path, {Policy::All}, {})));
      fullMs = float(median(full));
      // Frames under a budget nothing fits time the stage's fixed cost, which the model keeps
      // (once it has, the stage leaves itself out: their mean stage time says nothing).
      (void)sweep.run(pathName, path, {Policy::Density, 0, 1e-4f}, {});
      const CostModel fixedRun = renderer.costModel();
      fixedMs = float(fixedRun.stageOverheadMs + fixedRun.traceFixedMs);
      CostModel learned{.stageOverheadMs = fixedRun.stageOverheadMs, .traceFixedMs = fixedRun.traceFixedMs};
      for (const Policy p : calibrated) {
        sweep.startFrom(learned);
        for (int pass = 0; pass < 2; ++pass) {
          sweep.run(pathName, path, {p, 0, fullMs}, {});
          sweep.startFrom(renderer.costModel());
        }
        learned = renderer.costModel();
      }
      sweep.startFrom(learned);
      points = budgetSweep(fixedMs, fullMs, c.budgets);
    } else {
      fullMs = float(median(full));
    }
    const CostModel model = renderer.costModel();
    calibration << pathName << ',' << fullMs << ',' << fixedMs << ',' << model.msPerWorkUnit << ',' << model.msPerPaperCost << ',' << model.msPerItemWorkUnit << ',' << model.stageOverheadMs << ',' << model.traceFixedMs << ',' << model.msPerRay << ',' << model.msPerItemRay << ',';
    for (size_t b = 0; b < points.size(); ++b) calibration << (b ? ";" : "") << points[b];
    calibration << '\n';
    std::printf("%s: full-RT stage %.3f ms, fixed stage cost %.4f ms, budgets %.4f..%.3f ms\n", pathName.c_str(), fullMs, fixedMs, points.front(), points.back());
    // The repeats: every configuration once per repeat, `all` and `none` among them, in an
    // order shuffled per repeat (or the canonical one with --order-seed 0).
    std::vector<Config> configs{{Policy::All}, {Policy::None}};
    if (c.classified) configs.push_back({Policy::Classified});
    for (uint32_t b = 0; b < points.size(); ++b)
      for (const SweepPolicy& p : c.policies) configs.push_back({p.policy, b, points[b], p.ablation, p.rate});
    for (uint32_t r = 0; r < c.repeats; ++r) {
      std::vector<Config> order = configs;
      if (c.orderSeed != 0) shuffle(order, c.orderSeed * 7919u + uint32_t(pathIndex) * 131u + r);
      for (uint32_t k = 0; k < order.size(); ++k) {
        const std::string dir = pathImages + "/" + order[k].label() + "/r" + std::to_string(r);
        sweep.run(pathName, path, order[k], {true, r, k, dir, false});
      }
    }
  }
  const auto messages = renderer.validationMessages();
  for (const std::string& m : messages) std::cerr << m << '\n';
  std::cout << "wrote " << c.out << "/frames.csv\n";
  return messages.empty() ? 0 : 3;
}

}  // namespace raybudget::cli
