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

// Rate segments (PolicyOptions::rateSegments): items of one to three segments, ID item * 4 +
// k, mostly with falling densities along an item (a convex hull), some not, some with a
// segment missing (a later one then never goes in); costs and values as randomCandidates'.
inline std::vector<select::Candidate> randomSegments(bvh::Rng& rng, size_t n) {
  const std::vector<select::Candidate> base = randomCandidates(rng, n);
  std::vector<select::Candidate> c;
  for (size_t i = 0, item = 0; i < n; ++item) {
    const size_t count = 1 + size_t(rng.next() * 2.999f);
    const bool gap = rng.next() < 0.1f;
    for (size_t k = 0; k < count && i < n; ++k, ++i) {
      if (gap && k == 1) continue;
      select::Candidate x = base[i];
      x.id = uint32_t(item * 3 + 1) * 4 + uint32_t(k);
      if (k > 0 && rng.next() < 0.8f) x.value = std::min(x.value, c.back().value * x.cost / std::max(c.back().cost, 1e-30f));  // falling density
      c.push_back(x);
    }
  }
  return c;
}

// 0 one time in ten, else up to 60% of the candidates' total cost.
inline float randomBudget(bvh::Rng& rng, const std::vector<select::Candidate>& c) {
  double total = 0.0;
  for (const select::Candidate& x : c) total += x.cost;
  return rng.next() < 0.1f ? 0.0f : float(total * rng.next() * 0.6);
}

}  // namespace raybudget::test
