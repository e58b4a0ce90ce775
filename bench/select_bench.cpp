// Cost of the GPU selection (keys, bitonic sort, sequential walk) per policy for 10, 1k,
// 10k and 100k candidates, against the CPU reference, median of `repeats`. Candidates are
// random (log-uniform costs and relevance), the budget a third of their total cost.
//
// usage: select_bench [--repeats R]
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "passes/gpu_selector.h"
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
    passes::GpuSelector gpu(ctx, 100000);
    std::printf("select_bench: median of %u, device %s\n", repeats, ctx.properties().deviceName);
    std::printf("%-12s %10s %12s %12s %10s\n", "policy", "candidates", "GPU ms", "CPU ms", "selected");
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-5.0f, 5.0f);
    for (uint32_t n : {10u, 1000u, 10000u, 100000u}) {
      std::vector<select::Candidate> c(n);
      double total = 0.0;
      for (uint32_t i = 0; i < n; ++i) {
        c[i] = {i, std::exp(u(rng)), std::exp(u(rng)), std::exp(u(rng))};
        total += c[i].cost;
      }
      const float budget = float(total / 3.0);
      // "paper-climb": the paper's walk climbing relevance pointers while one fits (the
      // superlinear reading; up to 10k only, it takes seconds at 100k).
      for (int row = 0; row < 5; ++row) {
        const select::Policy p = row == 1 ? select::Policy::Paper
                                          : std::array{select::Policy::Paper, select::Policy::Paper, select::Policy::Density, select::Policy::Nearest,
                                                       select::Policy::Random}[size_t(row)];
        select::PolicyOptions options;
        options.paperHops = row == 1 ? 0 : 1;
        if (row == 1 && n > 10000) continue;
        std::vector<double> g, cpu;
        size_t selected = 0;
        for (uint32_t r = 0; r < repeats; ++r) {
          selected = gpu.select(c, p, budget, options).ids.size();
          g.push_back(gpu.lastGpuMs());
          const auto t0 = std::chrono::steady_clock::now();
          (void)select::selectObjects(p, c, budget, options);
          cpu.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        }
        std::printf("%-12s %10u %12.3f %12.3f %10zu\n", row == 1 ? "paper-climb" : select::policyName(p), n, median(g), median(cpu), selected);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "select_bench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
