#include "soak.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <thread>

#include "cli_options.h"
#include "raybudget/raybudget.h"

namespace raybudget::cli {

const char* kSoakUsage = R"(usage: raybudget soak SCENE.gltf|SCENE.glb [options]

A long run as an engine runs it: the camera alternates between an orbit and a fly-through, T
is a square wave between two budgets, a competing CPU load runs part of the time. Every
--scan-every frames the image and the selection's per-object records are scanned for NaN and
Inf and host RSS and device memory (VK_EXT_memory_budget) are sampled. Exit 1 when memory at
the end is 1% or more above its peak over the first half of the frames after the warm-up (a
leak keeps growing past it, a one-off allocation does not) or a NaN or Inf was found, 3 on a
validation message.

options:
  --frames N            frames in all (default 10000)
  --width W --height H  image size (default 320x180)
  --budgets LOW,HIGH    the square wave's budgets in ms (default 0.25 and 0.75 of the full-RT
                        stage cost, measured first)
  --period P            frames per half-wave (default 100)
  --path-frames F       frames per camera path before the other one (default 1000)
  --load-share S        share of the time with the CPU load, 0..1 (default 0.25)
  --scan-every K        frames between scans and memory samples (default 100)
  --warmup W            frames before the memory baseline (default a tenth of the frames)
  --policy P            a budgeted policy (default benefit)
  --rate R              full, half, quarter or auto (default auto)
  --device NAME, --validation
)";

namespace {

uint64_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  uint64_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * uint64_t(sysconf(_SC_PAGESIZE));
}

bool finiteHalf(uint16_t h) { return (h & 0x7C00u) != 0x7C00u; }

size_t nonFinite(const FrameImages& images) {
  return size_t(std::count_if(images.hdrRgba16.begin(), images.hdrRgba16.end(), [](uint16_t h) { return !finiteHalf(h); }));
}

size_t nonFinite(const std::vector<ObjectMetrics>& metrics) {
  size_t n = 0;
  auto count = [&](float v) { n += std::isfinite(v) ? 0 : 1; };
  for (const ObjectMetrics& m : metrics) {
    for (float v : {m.A, m.P, m.D, m.V, m.C, m.R}) count(v);
    for (int e = 0; e < 3; ++e) {
      count(m.itemError[size_t(e)]);
      count(m.itemBenefit[size_t(e)]);
      count(m.itemCostPerPixel[size_t(e)]);
    }
  }
  return n;
}

// Busy threads (half the cores, at least one) that spin while switched on.
class CpuLoad {
 public:
  CpuLoad() {
    const unsigned n = std::max(1u, std::thread::hardware_concurrency() / 2);
    for (unsigned i = 0; i < n; ++i)
      threads_.emplace_back([this] {
        volatile double x = 1.0;
        while (!stop_.load(std::memory_order_relaxed))
          if (on_.load(std::memory_order_relaxed)) x = std::sqrt(x + 1.0);
          else std::this_thread::sleep_for(std::chrono::milliseconds(1));
      });
  }
  ~CpuLoad() {
    stop_ = true;
    for (std::thread& t : threads_) t.join();
  }
  void set(bool on) { on_ = on; }

 private:
  std::atomic<bool> on_{false}, stop_{false};
  std::vector<std::thread> threads_;
};

struct MemorySample {
  uint32_t frame;
  uint64_t hostBytes;
  DeviceMemoryUsage device;
};

double growth(uint64_t from, uint64_t to) { return from == 0 ? 0.0 : (double(to) - double(from)) / double(from); }

}  // namespace

SoakCommand parseSoak(const std::vector<std::string>& args) {
  SoakCommand c;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& { return optionValue(args, i); };
    if (c.target.parse(args, i)) continue;
    if (a == "--frames") c.frames = parseUint(a, value(), 1, 10000000);
    else if (a == "--period") c.period = parseUint(a, value(), 1, 1000000);
    else if (a == "--path-frames") c.pathFrames = parseUint(a, value(), 2, 1000000);
    else if (a == "--scan-every") c.scanEvery = parseUint(a, value(), 1, 1000000);
    else if (a == "--warmup") c.warmup = parseUint(a, value(), 0, 10000000);
    else if (a == "--load-share") {
      const std::string& v = value();
      char* end = nullptr;
      const float share = std::strtof(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(share >= 0.0f && share <= 1.0f)) throw Error("--load-share takes a share in 0..1, got '" + v + "'");
      c.loadShare = share;
    } else if (a == "--budgets") {
      const std::string& v = value();
      const size_t comma = v.find(',');
      if (comma == std::string::npos) throw Error("--budgets takes LOW,HIGH in ms, got '" + v + "'");
      c.budgets = {parsePositive(a, v.substr(0, comma)), parsePositive(a, v.substr(comma + 1))};
    } else if (a == "--policy") {
      c.policy = parsePolicy(value());
      if (!isBudgeted(c.policy)) throw Error("--policy takes a budgeted policy (paper, density, nearest, random, benefit)");
    } else if (a == "--rate") c.rate = parseItemRate(value());
    else sceneArgument(a, c.scene, std::string("\n") + kSoakUsage);
  }
  if (c.scene.empty()) throw Error(std::string("soak needs a scene file\n") + kSoakUsage);
  if (c.warmup >= c.frames) throw Error("--warmup must be below --frames");
  return c;
}

int runSoak(const SoakCommand& c) {
  const Scene scene = loadScene(c.scene);
  RenderSettings s = c.target.settings();
  s.objectMetrics = true;  // the per-object records the scans read
  s.policy = Policy::All;
  s.rayTracing.rate = c.rate;  // made with the rate, so that its fill's history exists
  Renderer renderer(scene, s);
  renderer.restartSelection(Policy::All, s.budgetMs, BenefitAblation::None, ItemRate::Full);  // full RT calibrates
  const Camera start = pathStartCamera(scene, renderer.aspect());
  const FlythroughShape shape = flythroughShape(scene, start);
  auto cameraAt = [&](uint32_t f) {
    const uint32_t leg = f / c.pathFrames, step = f % c.pathFrames;
    return leg % 2 == 0 ? orbitCamera(start, step, c.pathFrames) : flythroughCamera(start, step, c.pathFrames, shape);
  };

  std::vector<float> budgets = c.budgets;
  if (budgets.empty()) {
    std::vector<double> stage;
    for (uint32_t f = 0; f < 8; ++f)
      for (const FrameTiming& t : renderer.render(cameraAt(f * c.pathFrames / 8))) stage.push_back(t.rtStageMs());
    for (const FrameTiming& t : renderer.finish()) stage.push_back(t.rtStageMs());
    stage.erase(stage.begin(), stage.begin() + 2);  // pipelines and caches warm up
    const double full = median(stage);
    budgets = {float(0.25 * full), float(0.75 * full)};
    std::printf("full-RT stage cost %.2f ms (median of %zu frames): budgets %.2f and %.2f ms\n", full, stage.size(), double(budgets[0]),
                double(budgets[1]));
  }
  renderer.restartSelection(c.policy, budgets[0], BenefitAblation::None, c.rate);
  std::printf("%s: %zu objects, %ux%u on %s, %s, %u frames; T %.2f / %.2f ms every %u frames; CPU load %.0f%% of the time\n", c.scene.c_str(),
              scene.objects.size(), c.target.width, c.target.height, renderer.deviceName().c_str(), policyName(c.policy), c.frames, double(budgets[0]),
              double(budgets[1]), c.period, 100.0 * c.loadShare);

  const uint32_t warmup = c.warmup > 0 ? c.warmup : std::max(c.frames / 10, std::min(c.scanEvery, c.frames - 1));
  CpuLoad load;
  std::vector<FrameTiming> timings;
  std::vector<bool> loaded(c.frames, false);
  std::vector<MemorySample> samples;
  size_t nanPixels = 0, nanRecords = 0, scans = 0;
  const uint32_t cycle = 4 * c.period;
  for (uint32_t f = 0; f < c.frames; ++f) {
    const float budget = budgets[(f / c.period) % 2];
    if (f > 0 && f % c.period == 0) renderer.setBudget(budget);
    loaded[f] = c.loadShare > 0.0f && float(f % cycle) >= (1.0f - c.loadShare) * float(cycle);
    load.set(loaded[f]);
    for (const FrameTiming& t : renderer.render(cameraAt(f))) timings.push_back(t);
    if ((f + 1) % c.scanEvery == 0 || f + 1 == c.frames) {
      nanPixels += nonFinite(renderer.readback());
      nanRecords += nonFinite(renderer.objectMetrics());
      ++scans;
      samples.push_back({f + 1, residentBytes(), renderer.deviceMemoryUsage()});
      if (samples.size() % 10 == 0 || f + 1 == c.frames)
        std::printf("frame %u: host RSS %.1f MiB, device memory %s, non-finite pixels %zu, records %zu\n", f + 1,
                    double(samples.back().hostBytes) / 1048576.0,
                    samples.back().device.known ? (std::to_string(samples.back().device.usedBytes / 1048576) + " MiB").c_str() : "unknown",
                    nanPixels, nanRecords);
      std::fflush(stdout);  // progress shows when the output goes to a log
    }
  }
  load.set(false);
  for (const FrameTiming& t : renderer.finish()) timings.push_back(t);
  if (timings.size() != c.frames) throw Error("soak: " + std::to_string(timings.size()) + " frame timings for " + std::to_string(c.frames) + " frames");

  // Memory: the last sample against the first half's peak after the warm-up (a leak grows
  // past it; an allocator's pages or a pipeline built late settle in it), and the largest
  // sample after the warm-up.
  const auto firstAfterWarmup = std::find_if(samples.begin(), samples.end(), [&](const MemorySample& m) { return m.frame >= warmup; });
  auto baseline = firstAfterWarmup;
  double hostGrowth = 0.0, deviceGrowth = 0.0, hostPeak = 0.0, devicePeak = 0.0;
  if (firstAfterWarmup != samples.end()) {
    const auto half = firstAfterWarmup + (samples.end() - firstAfterWarmup + 1) / 2;
    uint64_t deviceBaseline = 0;
    for (auto m = firstAfterWarmup; m != half; ++m) {
      if (m->hostBytes > baseline->hostBytes) baseline = m;
      deviceBaseline = std::max(deviceBaseline, m->device.usedBytes);
    }
    hostGrowth = growth(baseline->hostBytes, samples.back().hostBytes);
    deviceGrowth = growth(deviceBaseline, samples.back().device.usedBytes);
    for (auto m = firstAfterWarmup; m != samples.end(); ++m) {
      hostPeak = std::max(hostPeak, growth(firstAfterWarmup->hostBytes, m->hostBytes));
      devicePeak = std::max(devicePeak, growth(firstAfterWarmup->device.usedBytes, m->device.usedBytes));
    }
  }
  // Adherence after the warm-up, by load and by budget.
  auto adherence = [&](auto keep, const char* what) {
    size_t n = 0, within = 0;
    std::vector<double> use;
    for (uint32_t f = warmup; f < c.frames; ++f) {
      const FrameTiming& t = timings[f];
      if (!keep(f, t)) continue;
      ++n;
      within += t.rtStageMs() <= 1.05 * t.budgetMs ? 1 : 0;
      use.push_back(t.rtStageMs() / t.budgetMs);
    }
    if (n > 0)
      std::printf("  %-26s %6zu frames, stage <= T + 5%% in %.3f, stage / T median %.2f, 99th percentile %.2f\n", what, n,
                  double(within) / double(n), median(use), [&] {
                    std::sort(use.begin(), use.end());
                    return use[std::min(use.size() - 1, size_t(0.99 * double(use.size())))];
                  }());
  };
  std::printf("after %u warm-up frames:\n", warmup);
  adherence([](uint32_t, const FrameTiming&) { return true; }, "all");
  adherence([&](uint32_t f, const FrameTiming&) { return !loaded[f]; }, "without CPU load");
  adherence([&](uint32_t f, const FrameTiming&) { return bool(loaded[f]); }, "with CPU load");
  adherence([&](uint32_t, const FrameTiming& t) { return t.budgetMs == double(budgets[0]); }, "low T");
  adherence([&](uint32_t, const FrameTiming& t) { return t.budgetMs == double(budgets[1]); }, "high T");
  adherence([&](uint32_t f, const FrameTiming&) { return f % c.period < 5; }, "first 5 frames after a step");
  // On a CPU device the driver's figures are the whole system's: host RSS is the measure.
  const DeviceMemoryUsage lastDevice = samples.empty() ? DeviceMemoryUsage{} : samples.back().device;
  const bool deviceKnown = lastDevice.known && !lastDevice.cpuDevice;
  char deviceText[96];
  if (deviceKnown) std::snprintf(deviceText, sizeof(deviceText), "%+.2f%% (peak %+.2f%%)", 100.0 * deviceGrowth, 100.0 * devicePeak);
  else std::snprintf(deviceText, sizeof(deviceText), "%s", lastDevice.cpuDevice ? "not judged (a CPU device: its memory is the host RSS above)"
                                                                                 : "unknown (no VK_EXT_memory_budget)");
  std::printf("memory at frame %u against the first half's peak (frame %u): host RSS %+.2f%% (largest after the warm-up %+.2f%%), device %s\n",
              samples.empty() ? 0 : samples.back().frame, baseline != samples.end() ? baseline->frame : 0,
              100.0 * hostGrowth, 100.0 * hostPeak, deviceText);
  std::printf("scans: %zu, non-finite pixels %zu, non-finite selection records %zu\n", scans, nanPixels, nanRecords);
  const auto messages = renderer.validationMessages();
  for (const std::string& m : messages) std::cerr << m << '\n';
  const bool memoryFlat = hostGrowth < 0.01 && (!deviceKnown || deviceGrowth < 0.01);
  const bool finite = nanPixels == 0 && nanRecords == 0;
  if (memoryFlat && finite && messages.empty()) {
    std::printf("soak passed\n");
    return 0;
  }
  std::printf("soak FAILED:%s%s%s\n", memoryFlat ? "" : " memory grew past its early peak by 1% or more", finite ? "" : " non-finite values",
              messages.empty() ? "" : " validation messages");
  return messages.empty() ? 1 : 3;
}

}  // namespace raybudget::cli
