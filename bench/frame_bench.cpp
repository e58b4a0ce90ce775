// Frame time per pass at 1280x720 for a scene (default: the bundled court), on the device
// the renderer picks. Three repeats of 30 measured frames after 5 warm-up frames; prints
// the median per pass of each repeat and the median of those, with each pass's share.
//
// usage: frame_bench [SCENE] [--width W --height H] [--frames N] [--repeats R] [--orbit]
// The camera is the scene's own (static) unless --orbit moves it around the target.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "raybudget/raybudget.h"

using namespace raybudget;

int main(int argc, char** argv) {
  std::string scenePath = std::string(RAYBUDGET_BENCH_DEFAULT_SCENE);
  uint32_t width = 1280, height = 720, frames = 30, repeats = 3, warmup = 5;
  bool orbit = false;
  for (int i = 1; i < argc; ++i) {
    auto next = [&]() { return i + 1 < argc ? std::stoul(argv[++i]) : 0ul; };
    if (!std::strcmp(argv[i], "--width")) width = uint32_t(next());
    else if (!std::strcmp(argv[i], "--height")) height = uint32_t(next());
    else if (!std::strcmp(argv[i], "--frames")) frames = uint32_t(next());
    else if (!std::strcmp(argv[i], "--repeats")) repeats = uint32_t(next());
    else if (!std::strcmp(argv[i], "--orbit")) orbit = true;
    else scenePath = argv[i];
  }
  try {
    const Scene scene = loadScene(scenePath);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    std::vector<PassSummary> runs;
    std::string device;
    for (uint32_t r = 0; r < repeats; ++r) {
      Renderer renderer(scene, settings);  // fresh each repeat: includes nothing cached
      device = renderer.deviceName();
      const Camera start = defaultCamera(scene, renderer.aspect());
      std::vector<FrameTiming> timings;
      for (uint32_t f = 0; f < warmup + frames; ++f)
        for (const FrameTiming& t : renderer.render(orbit ? orbitCamera(start, f, warmup + frames) : start))
          if (t.frame >= warmup) timings.push_back(t);
      for (const FrameTiming& t : renderer.finish())
        if (t.frame >= warmup) timings.push_back(t);
      runs.push_back(summarize(timings));
    }
    std::printf("frame_bench: %s, %ux%u, %s camera, %s, %u repeats x %u frames (after %u warm-up)\n", std::filesystem::path(scenePath).filename().c_str(), width, height,
                orbit ? "orbit" : "static", device.c_str(), repeats, frames, warmup);
    std::printf("%-14s %12s %8s   per repeat\n", "pass", "median ms", "share");
    auto medianOf = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    std::vector<double> totals;
    for (const PassSummary& s : runs) totals.push_back(s.medianTotalMs);
    const double total = medianOf(totals);
    for (size_t p = 0; p < kPassCount; ++p) {
      if (Pass(p) == Pass::Environment) continue;  // built once at start, not per frame
      if (runs[0].frames[p] == 0) {
        std::printf("%-14s %12s\n", passName(Pass(p)), "skipped");
        continue;
      }
      std::vector<double> v;
      for (const PassSummary& s : runs) v.push_back(s.medianMs[p]);
      std::printf("%-14s %12.2f %7.1f%%  ", passName(Pass(p)), medianOf(v), 100.0 * medianOf(v) / total);
      for (double x : v) std::printf(" %.2f", x);
      std::printf("\n");
    }
    std::printf("%-14s %12.2f %7.1f%%  ", "frame", total, 100.0);
    for (double x : totals) std::printf(" %.2f", x);
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "frame_bench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
