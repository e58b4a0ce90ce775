// Random selection candidates for the policy tests: log-uniform costs and relevance with
// ties, zeros, huge and tiny values mixed in, and a budget of a random share of the total.
#pragma once
#include <cmath>
#include <vector>

#include "bvh/ray_sets.h"
#include "select/policies.h"

namespace raybudget::test {

inline std::vector<select::Candidate> randomCandidates(bvh::Rng& rng, size_t n) {
  std::vector<select::Candidate> c(n);
  for (size_t i = 0; i < n; ++i) {
    const float u = rng.next(), v = rng.next(), w = rng.next();
    c[i].id = uint32_t(i * 7 + 3);
    c[i].cost = u < 0.05f ? 0.0f : u < 0.15f ? 1.0f : u < 0.2f ? 1e-6f : u < 0.25f ? 1e4f : std::exp(rng.next() * 10.0f - 5.0f);
    c[i].value = v < 0.1f ? 1.0f : v < 0.15f ? 1e-7f : v < 0.2f ? 1e5f : std::exp(rng.next() * 10.0f - 5.0f);
    c[i].distance = w < 0.2f ? 2.0f : rng.next() * 100.0f;
  }
  return c;
}

// Costs, values and distances from 11 levels each (e^(k/2), k = -5..5), as in a symmetric view
// of repeated objects: many densities are equal or a few ULP apart (e^a / e^b against
// e^c / e^d with a - b = c - d), where a float division that is not correctly rounded (Vulkan
// allows 2.5 ULP) orders them unlike the CPU.
inline std::vector<select::Candidate> leveledCandidates(bvh::Rng& rng, size_t n) {
  auto level = [&] { return std::exp(std::floor(rng.next() * 11.0f - 5.0f) * 0.5f); };
  std::vector<select::Candidate> c(n);
  for (size_t i = 0; i < n; ++i) c[i] = {uint32_t(i * 5 + 1), level(), level(), level()};
  return c;
}

// 0 one time in ten, else up to 60% of the candidates' total cost.
inline float randomBudget(bvh::Rng& rng, const std::vector<select::Candidate>& c) {
  double total = 0.0;
  for (const select::Candidate& x : c) total += x.cost;
  return rng.next() < 0.1f ? 0.0f : float(total * rng.next() * 0.6);
}

}  // namespace raybudget::test
