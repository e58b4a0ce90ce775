#include "sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

#include <glm/gtc/packing.hpp>

#include "cli_options.h"
#include "raybudget/raybudget.h"

namespace raybudget::cli {

const char* kSweepUsage = R"(usage: raybudget sweep SCENE.gltf|SCENE.glb [options]
  --out DIR             output folder (default ./sweep): frames.csv, paths/*.json, images/
  --width W --height H  image size (default 320x180)
  --frames N            recorded frames per camera path (default 8)
  --warmup N            frames on the path's first camera before it, not recorded (default 4)
  --budgets N           log-spaced budgets from the cheapest object to full RT (default 8)
  --repeats N           runs of each configuration; images from the first (default 3)
  --policies LIST       comma-separated budgeted policies (default paper,density,nearest,random)
  --paths LIST          comma-separated camera paths: orbit, flythrough (default both)
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

std::vector<Camera> cameraPath(const std::string& name, const Camera& start, uint32_t frames) {
  std::vector<Camera> path;
  for (uint32_t f = 0; f < frames; ++f) path.push_back(cameraOnPath(name, start, f, frames));
  return path;
}

void writePathJson(const std::filesystem::path& file, const std::string& name, const std::vector<Camera>& path) {
  std::ofstream out(file);
  auto vec = [](const glm::vec3& v) { return "[" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + "]"; };
  out << "{\n  \"path\": \"" << name << "\",\n  \"frames\": [\n";
  for (size_t i = 0; i < path.size(); ++i)
    out << "    {\"position\": " << vec(path[i].position) << ", \"target\": " << vec(path[i].target) << ", \"up\": " << vec(path[i].up)
        << ", \"yfov\": " << path[i].yfov << "}" << (i + 1 < path.size() ? "," : "") << "\n";
  out << "  ]\n}\n";
  if (!out) throw Error("cannot write " + file.string());
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

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string frameFile(size_t frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "%04zu.png", frame);
  return name;
}

double traceMs(const FrameTiming& t) {
  return t.passMs[size_t(Pass::TraceShadows)].value_or(0.0) + t.passMs[size_t(Pass::TraceEffects)].value_or(0.0);
}

// One configuration over one camera path: warm-up, then the recorded frames; with images,
// each frame is read back, its display image written and its HDR error taken against the
// reference (or kept as the reference).
struct Run {
  Policy policy;
  uint32_t budgetIndex;  // 0 for all / none
  float budgetMs;
  uint32_t repeat;
};

class Sweep {
 public:
  Sweep(const SweepCommand& c, const Scene& scene, Renderer& renderer, std::ofstream& csv, uint64_t totalFrames)
      : c_(c), scene_(scene), renderer_(renderer), csv_(csv), total_(totalFrames) {}

  // Returns the recorded frames' timings.
  std::vector<FrameTiming> run(const std::string& pathName, const std::vector<Camera>& path, const Run& r, bool record) {
    renderer_.restartSelection(r.policy, r.budgetMs);
    const bool images = record && r.repeat == 0;
    const std::string label = policyName(r.policy) + (isBudgeted(r.policy) ? "-b" + std::to_string(r.budgetIndex) : std::string());
    const std::filesystem::path dir = std::filesystem::path(c_.out) / "images" / pathName / label;
    if (images) std::filesystem::create_directories(dir);
    std::vector<FrameTiming> all;
    std::vector<double> rmse(path.size(), -1.0);
    auto collect = [&](const std::vector<FrameTiming>& done) { all.insert(all.end(), done.begin(), done.end()); };
    const uint64_t first = rendered_ + c_.warmup;
    for (uint32_t w = 0; w < c_.warmup; ++w) render(path.front(), collect);
    for (size_t f = 0; f < path.size(); ++f) {
      render(path[f], collect);
      if (!images) continue;
      const FrameImages img = renderer_.readback();
      writePng(dir / frameFile(f), img.width, img.height, img.ldrRgba8);
      std::vector<float> rgb = linearRgb(img);
      if (r.policy == Policy::All) reference_[f] = std::move(rgb);  // the reference: error 0
      rmse[f] = r.policy == Policy::All ? 0.0 : std::sqrt(meanSquaredError(rgb, reference_.at(f)));
    }
    collect(renderer_.finish());
    std::vector<FrameTiming> recorded;
    for (const FrameTiming& t : all) {
      if (t.frame < first) continue;
      const size_t f = size_t(t.frame - first);
      recorded.push_back(t);
      if (!record) continue;
      csv_ << std::filesystem::path(scene_.path).stem().string() << ',' << pathName << ',' << policyName(r.policy) << ',' << r.budgetIndex << ',' << (isBudgeted(r.policy) ? r.budgetMs : 0.0f)
           << ',' << r.repeat << ',' << f << ',' << traceMs(t) << ',' << t.totalMs() << ',' << t.predictedTraceMs << ',' << t.selectedObjects << ','
           << t.raysTraced << ',' << t.selectedValue << ',' << t.optimalValueBound << ',' << t.selectionChanges << ',';
      if (images) {
        const double mse = rmse[f] * rmse[f];
        csv_ << rmse[f] << ',' << (mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity()) << ','
             << (std::filesystem::path("images") / pathName / label / frameFile(f)).string();
      } else {
        csv_ << ",,";
      }
      csv_ << '\n';
    }
    csv_.flush();
    return recorded;
  }

 private:
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
  std::map<size_t, std::vector<float>> reference_;
};

}  // namespace

SweepCommand parseSweep(const std::vector<std::string>& args) {
  SweepCommand c;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw Error(a + " needs a value");
      return args[++i];
    };
    if (a == "--out") c.out = value();
    else if (a == "--width") c.width = parseUint(a, value(), 16, 16384);
    else if (a == "--height") c.height = parseUint(a, value(), 16, 16384);
    else if (a == "--frames") c.frames = parseUint(a, value(), 1, 100000);
    else if (a == "--warmup") c.warmup = parseUint(a, value(), 0, 1000);
    else if (a == "--budgets") c.budgets = parseUint(a, value(), 2, 64);
    else if (a == "--repeats") c.repeats = parseUint(a, value(), 1, 100);
    else if (a == "--device") c.device = value();
    else if (a == "--validation") c.validation = true;
    else if (a == "--policies") {
      c.policies.clear();
      for (const std::string& p : splitList(value())) {
        const Policy policy = parsePolicy(p);
        if (!isBudgeted(policy)) throw Error("--policies takes budgeted policies (paper, density, nearest, random), got '" + p + "'");
        c.policies.push_back(policy);
      }
      if (c.policies.empty()) throw Error("--policies needs at least one policy");
    } else if (a == "--paths") {
      c.paths = splitList(value());
      for (const std::string& p : c.paths)
        if (p != "orbit" && p != "flythrough") throw Error("--paths takes orbit and flythrough, got '" + p + "'");
      if (c.paths.empty()) throw Error("--paths needs at least one path");
    } else if (!a.empty() && a[0] == '-') throw Error("unknown option " + a + "\n" + kSweepUsage);
    else if (c.scene.empty()) c.scene = a;
    else throw Error("more than one scene given: '" + c.scene + "' and '" + a + "'");
  }
  if (c.scene.empty()) throw Error(std::string("sweep needs a scene file\n") + kSweepUsage);
  return c;
}

int runSweep(const SweepCommand& c) {
  const Scene scene = loadScene(c.scene);
  RenderSettings s;
  s.width = c.width;
  s.height = c.height;
  s.device = c.device;
  s.validation = c.validation;
  s.optimalBound = true;
  s.policy = Policy::All;
  Renderer renderer(scene, s);
  std::filesystem::create_directories(std::filesystem::path(c.out) / "paths");
  std::ofstream csv(std::filesystem::path(c.out) / "frames.csv");
  csv << "scene,path,policy,budget_index,budget_ms,repeat,frame,trace_ms,frame_ms,predicted_trace_ms,selected_objects,rays,selected_value,"
         "optimal_value_bound,selection_changes,rmse,psnr,image\n";
  const uint64_t perPath = uint64_t(c.frames + c.warmup) * (uint64_t(c.repeats) * (2 + c.policies.size() * c.budgets) + c.policies.size());
  Sweep sweep(c, scene, renderer, csv, perPath * c.paths.size());
  std::cout << "sweep " << c.scene << ": " << scene.objects.size() << " objects, device " << renderer.deviceName() << '\n';
  const Camera start = pathStartCamera(scene, renderer.aspect());
  for (const std::string& pathName : c.paths) {
    const std::vector<Camera> path = cameraPath(pathName, start, c.frames);
    writePathJson(std::filesystem::path(c.out) / "paths" / (pathName + ".json"), pathName, path);
    std::vector<double> fullTrace;
    for (uint32_t r = 0; r < c.repeats; ++r)
      for (const FrameTiming& t : sweep.run(pathName, path, {Policy::All, 0, 1.0f, r}, true)) fullTrace.push_back(traceMs(t));
    for (uint32_t r = 0; r < c.repeats; ++r) sweep.run(pathName, path, {Policy::None, 0, 1.0f, r}, true);
    // The sweep's ends: full RT's trace time, and the cheapest candidate's predicted cost.
    // Each policy runs the path once at the full budget first, not recorded: the cost
    // model learns the device's time scale (kept across restarts, per cost unit) as an
    // engine running for a while would have, and the probes give the cheapest candidate.
    const double most = std::max(median(fullTrace), 1e-3);
    std::vector<double> cheapest;
    for (const Policy p : c.policies)
      for (const FrameTiming& t : sweep.run(pathName, path, {p, 0, float(most), 0}, false))
        if (t.cheapestCandidateMs > 0.0 && p != Policy::Paper) cheapest.push_back(t.cheapestCandidateMs);
    double least = cheapest.empty() ? most / 64.0 : median(cheapest);
    if (least > most / 8.0) least = most / 8.0;
    std::printf("%s: full-RT trace %.3f ms, cheapest object %.4f ms\n", pathName.c_str(), most, least);
    for (uint32_t b = 0; b < c.budgets; ++b) {
      const float budget = float(least * std::pow(most / least, double(b) / double(c.budgets - 1)));
      for (const Policy p : c.policies)
        for (uint32_t r = 0; r < c.repeats; ++r) sweep.run(pathName, path, {p, b, budget, r}, true);
    }
  }
  const auto messages = renderer.validationMessages();
  for (const std::string& m : messages) std::cerr << m << '\n';
  std::cout << "wrote " << c.out << "/frames.csv\n";
  return messages.empty() ? 0 : 3;
}

}  // namespace raybudget::cli
