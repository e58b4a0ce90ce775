// Cost of the GPU selection (keys, sort, sequential walk) per policy for 10, 1k,
// 10k and 100k candidates, against the CPU reference, median of `repeats`. Candidates are
// random (log-uniform costs and relevance; "-tied" rows: drawn from 11 values, many equal
// keys), the budget a third of their total cost.
// Then the coverage and select passes in the frame on generated scenes of 10 to 100k
// cubes (640x360, density and paper with a binding budget and with one every candidate
// fits, and all; median of frames 3-19: one frame on a busy 2-core machine can be 0.5 ms off).
//
// usage: select_bench [--repeats R]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "select/gpu_selector.h"
#include "raybudget/raybudget.h"
#include "select/policies.h"
#include "vk/context.h"

using namespace raybudget;

namespace {


double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  uint32_t repeats = 5;
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = uint32_t(std::stoul(argv[++i]));
  try {
    vk::Context ctx(vk::ContextOptions{false, ""});
    select::GpuSelector gpu(ctx, 100000);
    std::printf("select_bench: median of %u, device %s\n", repeats, ctx.properties().deviceName);
    std::printf("%-12s %10s %12s %12s %10s\n", "policy", "candidates", "GPU ms", "CPU ms", "selected");
    std::mt19937 rng(3), tiedRng(5);  // two streams: the random sets stay those of earlier runs
    std::uniform_real_distribution<float> u(-5.0f, 5.0f);
    bool allEqual = true;  // every GPU selection above equals the CPU reference's
    for (uint32_t n : {10u, 1000u, 10000u, 100000u}) {
      // Random candidates, and the same drawn from 11 values each: many equal keys, as in a
      // symmetric view of repeated objects (equal distances, densities), which random
      // candidates alone hide.
      std::vector<select::Candidate> c(n), tied(n);
      for (uint32_t i = 0; i < n; ++i) {
        c[i] = {i, std::exp(u(rng)), std::exp(u(rng)), std::exp(u(rng))};
        tied[i] = {i, std::exp(std::round(u(tiedRng)) * 0.5f), std::exp(std::round(u(tiedRng)) * 0.5f), std::exp(std::round(u(tiedRng)) * 0.5f)};
      }
      // "paper-climb": the paper's walk climbing relevance pointers while one fits (the
      // superlinear reading; up to 10k only, it takes seconds at 100k).
      struct Row {
        const char* name;
        select::Policy policy;
        uint32_t paperHops;
        const std::vector<select::Candidate>* set;
      };
      for (const Row& row : {Row{"paper", select::Policy::Paper, 1, &c}, Row{"paper-climb", select::Policy::Paper, 0, &c},
                             Row{"density", select::Policy::Density, 1, &c}, Row{"nearest", select::Policy::Nearest, 1, &c},
                             Row{"random", select::Policy::Random, 1, &c}, Row{"density-tied", select::Policy::Density, 1, &tied},
                             Row{"nearest-tied", select::Policy::Nearest, 1, &tied}}) {
        const select::Policy p = row.policy;
        double total = 0.0;
        for (const select::Candidate& x : *row.set) total += x.cost;
        const float budget = float(total / 3.0);
        select::PolicyOptions options;
        options.paperHops = row.paperHops;
        if (row.paperHops == 0 && n > 10000) continue;
        std::vector<double> g, cpu;
        size_t selected = 0;
        bool rowEqual = true;
        for (uint32_t r = 0; r < repeats; ++r) {
          const select::Selection onGpu = gpu.select(*row.set, p, budget, options);
          g.push_back(gpu.lastGpuMs());
          const auto t0 = std::chrono::steady_clock::now();
          const select::Selection onCpu = select::selectObjects(p, *row.set, budget, options);
          cpu.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
          selected = onGpu.ids.size();
          rowEqual = rowEqual && onGpu.ids == onCpu.ids;
        }
        allEqual = allEqual && rowEqual;
        std::printf("%-12s %10u %12.3f %12.3f %10zu%s\n", row.name, n, median(g), median(cpu), selected, rowEqual ? "" : "  (differs from the CPU's)");
      }
    }
    std::printf("GPU selections equal to the CPU reference's: %s\n", allEqual ? "all" : "NOT ALL");
    std::printf("\n%-16s %8s %12s %12s %12s %8s %8s\n", "in the frame", "objects", "coverage ms", "select ms", "select min", "visible", "sorted");
    // density-binds: T a third of what the candidates cost (from density-fits' last frame,
    // with the time scale frozen so both predict alike): the sort runs every frame.
    // density-fits: T far above it, every candidate fits: the select pass skips the sort.
    // paper-fits, paper-binds: the same for `paper` (its costs are the paper's C, so its
    // own total sets its binding T), whose walk is the sequential graph walk.
    // all: the select pass without the GPU selector, the fixed part (marking objects, the
    // tile list). "sorted": frames whose selection needed the sort; "select min": the
    // fastest frame's select pass (this 2-core machine preempts the device's threads while
    // the host records the next frame: medians carry that noise).
    for (uint32_t n : {10u, 1000u, 10000u, 100000u}) {
      const Scene scene = cubeGridScene(n);
      double fitsTotalMs = 0.0;
      struct FrameRow {
        const char* name;
        Policy policy;
        bool binds;
      };
      for (const FrameRow& row : {FrameRow{"density-fits", Policy::Density, false}, FrameRow{"density-binds", Policy::Density, true},
                                  FrameRow{"paper-fits", Policy::Paper, false}, FrameRow{"paper-binds", Policy::Paper, true},
                                  FrameRow{"all", Policy::All, false}}) {
        RenderSettings s;
        s.width = 640;
        s.height = 360;
        s.policy = row.policy;
        s.budgetMs = row.binds ? float(fitsTotalMs / 3.0) : 1e6f;
        s.learnTimeScale = false;
        s.objectMetrics = true;
        Renderer renderer(scene, s);
        Camera cam = defaultCamera(scene, 640.0f / 360.0f);
        std::vector<FrameTiming> t;
        for (int f = 0; f < 20; ++f)
          for (const FrameTiming& x : renderer.render(cam)) t.push_back(x);
        for (const FrameTiming& x : renderer.finish()) t.push_back(x);
        size_t visible = 0, sorted = 0;
        for (const ObjectMetrics& m : renderer.objectMetrics()) visible += m.pixels > 0;
        std::vector<double> cov, sel;
        for (size_t f = 3; f < t.size(); ++f) {
          cov.push_back(t[f].ms(Pass::Coverage));
          sel.push_back(t[f].ms(Pass::Select));
          sorted += t[f].selectionSorted;
        }
        if (!row.binds) fitsTotalMs = t.back().predictedTraceMs;  // the next row's policy, binding
        std::printf("%-16s %8u %12.3f %12.3f %12.3f %8zu %5zu/%zu\n", row.name, n, median(cov), median(sel), *std::min_element(sel.begin(), sel.end()),
                    visible, sorted, sel.size());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "select_bench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
