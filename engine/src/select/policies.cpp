#include "select/policies.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>

#include "raybudget/error.h"
#include "select/cost_model.h"
#include "select/paper_graph.h"
#include "shared/random_rank.h"

namespace raybudget::select {
namespace {

// Adds candidates in `order` while they fit what is left of the budget (fill-in: one that
// does not fit is skipped, later cheaper ones may still go in). Float arithmetic in
// selection order, as the GPU does it.
std::vector<uint32_t> greedyFit(std::span<const Candidate> c, const std::vector<uint32_t>& order, float budget) {
  std::vector<uint32_t> chosen;
  float remaining = budget;
  for (uint32_t i : order)
    if (c[i].cost <= remaining) {
      chosen.push_back(i);
      remaining -= c[i].cost;
    }
  return chosen;
}

constexpr uint32_t kSegmentSlots = 4;  // shared/selection.h's RB_SEGMENT_SLOTS

// Whether candidate `id` (a rate segment) may become the partial item: the first segment of a
// reflection or refraction item (select_walk.comp's partialCandidate says why not a shadow's).
bool partialCandidate(uint32_t id) {
  return id % kSegmentSlots == 0 && id / kSegmentSlots % RB_ITEMS_PER_OBJECT != RB_ITEM_SHADOWS;
}
// A shadow item's first segment: the partial item only with what the whole walk left, where no
// reflection or refraction item took it (select_walk.comp's takeShadowPartial).
bool shadowPartialCandidate(uint32_t id) {
  return id % kSegmentSlots == 0 && id / kSegmentSlots % RB_ITEMS_PER_OBJECT == RB_ITEM_SHADOWS;
}

// The same over rate segments: one goes in only onto its item's previous segment. `partial`
// (when given) gets the first candidate in `order` that partialCandidate allows and that did
// not fit, and `partialBudget` what the budget left then. Where that pays for at least
// RB_PARTIAL_MIN_SHARE of it, the walk stops there (the fractional knapsack's greedy: what
// follows in the order is worth less per cost than the partial item's share). Where none was
// or its share is under that, the first shadow item's first segment that did not fit gets what
// the walk left at its end, at least RB_PARTIAL_MIN_SHARE of it.
std::vector<uint32_t> greedyFitSegments(std::span<const Candidate> c, const std::vector<uint32_t>& order, float budget,
                                        uint32_t* partial = nullptr, float* partialBudget = nullptr) {
  std::unordered_map<uint32_t, uint32_t> level;  // item -> segments taken
  std::vector<uint32_t> chosen;
  float remaining = budget;
  uint32_t shadow = UINT32_MAX;
  // Whether `left` pays for RB_PARTIAL_MIN_SHARE of candidate i.
  const auto sharePays = [&](uint32_t i, float left) { return exactQuotient(left, c[i].cost) >= float(RB_PARTIAL_MIN_SHARE); };
  for (uint32_t i : order) {
    uint32_t& taken = level[c[i].id / kSegmentSlots];
    if (c[i].cost <= remaining && taken == c[i].id % kSegmentSlots) {
      chosen.push_back(i);
      remaining -= c[i].cost;
      ++taken;
    } else if (partial && *partial == UINT32_MAX && partialCandidate(c[i].id)) {
      *partial = i;
      *partialBudget = remaining;
      if (sharePays(i, remaining)) remaining = 0.0f;
    } else if (partial && shadow == UINT32_MAX && shadowPartialCandidate(c[i].id)) {
      shadow = i;
    }
  }
  if (shadow != UINT32_MAX && (*partial == UINT32_MAX || !sharePays(*partial, *partialBudget)) && sharePays(shadow, remaining)) {
    *partial = shadow;
    *partialBudget = remaining;
  }
  return chosen;
}

std::vector<uint32_t> indices(size_t n) {
  std::vector<uint32_t> v(n);
  std::iota(v.begin(), v.end(), 0u);
  return v;
}

}  // namespace

uint32_t randomRank(uint32_t seed, uint32_t id) { return gpu::randomRank(seed, id); }

float densityKey(const Candidate& c) { return c.cost > 0.0f ? c.value / c.cost : std::numeric_limits<float>::infinity(); }

namespace {

// Greedy by value density with fill-in, then the better of that and the most valuable
// single candidate that fits: the classic 1/2-approximation of the 0/1 knapsack
// (Funkhouser and Séquin 1993 use the greedy part for level-of-detail selection).
// `partial` (frame mode's `benefit` with rate segments, when given): the item traced on a share
// of its tiles with the budget the greedy left (shared/selection.h's RB_PARTIAL_MIN_SHARE).
std::vector<uint32_t> density(std::span<const Candidate> c, float budget, bool segments, PartialItem* partial = nullptr) {
  std::vector<uint32_t> order = indices(c.size());
  // The key is a float division (zero cost: +inf, first), one total order: key descending,
  // then ID (as every policy's ties: the GPU's sort keys are one word and the ID order);
  // float sums in selection order. The GPU does the same.
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    const float ka = densityKey(c[a]), kb = densityKey(c[b]);
    return ka != kb ? ka > kb : c[a].id < c[b].id;
  });
  uint32_t partialIndex = UINT32_MAX;
  float partialBudget = 0.0f;
  std::vector<uint32_t> greedy = segments ? greedyFitSegments(c, order, budget, partial ? &partialIndex : nullptr, &partialBudget) : greedyFit(c, order, budget);
  float greedyValue = 0.0f;
  for (uint32_t i : greedy) greedyValue += c[i].value;
  PartialItem part;
  if (partialIndex != UINT32_MAX) {
    const float share = exactQuotient(partialBudget, c[partialIndex].cost);
    if (share >= float(RB_PARTIAL_MIN_SHARE)) part = {c[partialIndex].id, share, partialBudget, c[partialIndex].value * share};
  }
  // With rate segments a single option is an item's first segment.
  uint32_t best = UINT32_MAX;
  for (uint32_t i = 0; i < c.size(); ++i)
    if (c[i].cost <= budget && (!segments || c[i].id % kSegmentSlots == 0) && (best == UINT32_MAX || c[i].value > c[best].value || (c[i].value == c[best].value && c[i].id < c[best].id)))
      best = i;
  if (best != UINT32_MAX && c[best].value > greedyValue + part.value) return {best};
  if (part.id != UINT32_MAX) {
    *partial = part;
    greedy.push_back(partialIndex);
  }
  return greedy;
}

// 0/1 knapsack by dynamic programming over the budget cut into `steps` units; each cost
// rounded up (`roundUp`: the selection stays within the real budget) or down (an upper
// bound on the value). Returns the chosen indices and the programme's best value.
std::pair<std::vector<uint32_t>, double> knapsack(std::span<const Candidate> c, float budget, uint32_t steps, bool roundUp) {
  if (steps == 0 || steps > (1u << 20)) throw Error("optimal selection: steps must be within 1..2^20");
  const size_t n = c.size(), w = steps;
  if (double(n) * double(w + 1) > 4e8) throw Error("optimal selection: " + std::to_string(n) + " candidates x " + std::to_string(steps) +
                                                  " steps is beyond the benchmark-only dynamic programme");
  std::vector<uint32_t> units(n);
  for (size_t i = 0; i < n; ++i) {
    const double u = budget > 0.0f ? double(c[i].cost) / double(budget) * double(w) : (c[i].cost > 0.0f ? double(w) + 1.0 : 0.0);
    units[i] = uint32_t(std::min(double(w) + 1.0, roundUp ? std::ceil(u) : std::floor(u)));
  }
  std::vector<double> best(w + 1, 0.0);
  std::vector<char> take(n * (w + 1), 0);
  for (size_t i = 0; i < n; ++i) {
    if (units[i] > w) continue;
    for (size_t b = w + 1; b-- > units[i];) {
      const double with = best[b - units[i]] + double(c[i].value);
      if (with > best[b]) {
        best[b] = with;
        take[i * (w + 1) + b] = 1;
      }
    }
  }
  std::vector<uint32_t> chosen;
  for (size_t i = n, b = w; i-- > 0;)
    if (take[i * (w + 1) + b]) {
      chosen.push_back(uint32_t(i));
      b -= units[i];
    }
  return {chosen, best[w]};
}


}  // namespace

void validateCandidates(std::span<const Candidate> c, float budget) {
  if (!std::isfinite(budget) || budget < 0.0f) throw Error("selection budget must be a finite number >= 0, got " + std::to_string(budget));
  for (const Candidate& x : c)
    if (!std::isfinite(x.cost) || x.cost < 0.0f || !std::isfinite(x.value) || x.value < 0.0f)
      throw Error("object " + std::to_string(x.id) + ": selection cost and value must be finite and >= 0 (cost " + std::to_string(x.cost) +
                  ", value " + std::to_string(x.value) + ")");
}

const char* policyName(Policy policy) {
  switch (policy) {
    case Policy::None: return "none";
    case Policy::All: return "all";
    case Policy::Paper: return "paper";
    case Policy::Density: return "density";
    case Policy::Optimal: return "optimal";
    case Policy::Nearest: return "nearest";
    case Policy::Random: return "random";
    case Policy::Benefit: return "benefit";
  }
  return "?";
}

Policy parsePolicy(const std::string& name) {
  for (Policy p : {Policy::None, Policy::All, Policy::Paper, Policy::Density, Policy::Optimal, Policy::Nearest, Policy::Random, Policy::Benefit})
    if (name == policyName(p)) return p;
  throw Error("unknown policy '" + name + "' (none, all, paper, density, optimal, nearest, random, benefit)");
}

Selection selectObjects(Policy policy, std::span<const Candidate> c, float budget, const PolicyOptions& options) {
  validateCandidates(c, budget);
  std::vector<uint32_t> chosen;
  PartialItem partial;
  switch (policy) {
    case Policy::None: break;
    case Policy::All: chosen = indices(c.size()); break;
    case Policy::Paper: chosen = walkPaperGraph(buildPaperGraph(c, options.graphPointers), c, budget, options.paperHops); break;
    case Policy::Density:
    case Policy::Benefit: {
      const bool segments = policy == Policy::Benefit && options.rateSegments;
      chosen = density(c, budget, segments, segments && options.partialItem ? &partial : nullptr);
      break;
    }
    case Policy::Optimal: chosen = knapsack(c, budget, options.optimalSteps, true).first; break;
    case Policy::Nearest: {
      std::vector<uint32_t> order = indices(c.size());
      std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return c[a].distance != c[b].distance ? c[a].distance < c[b].distance : c[a].id < c[b].id;
      });
      chosen = greedyFit(c, order, budget);
      break;
    }
    case Policy::Random: {
      // A seeded random order: by a hash of (seed, ID), ties by ID.
      std::vector<uint32_t> order = indices(c.size());
      const uint32_t seed = uint32_t(options.seed);
      std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const uint32_t ra = randomRank(seed, c[a].id), rb = randomRank(seed, c[b].id);
        return ra != rb ? ra < rb : c[a].id < c[b].id;
      });
      chosen = greedyFit(c, order, budget);
      break;
    }
  }
  Selection s;
  for (uint32_t i : chosen) {
    s.ids.push_back(c[i].id);
    const bool share = partial.id == c[i].id;
    s.cost += share ? partial.cost : c[i].cost;
    s.value += share ? partial.value : c[i].value;
  }
  std::sort(s.ids.begin(), s.ids.end());
  s.partial = partial;
  return s;
}

double optimalValueBound(std::span<const Candidate> c, float budget, uint32_t steps, bool segments) {
  validateCandidates(c, budget);
  if (!segments) return knapsack(c, budget, steps, false).second;
  // The options: each item's segment prefixes (in segment order), costs rounded down to the
  // grid; a dynamic programme over items, at most one option each.
  std::map<uint32_t, std::vector<const Candidate*>> items;
  for (const Candidate& x : c) items[x.id / kSegmentSlots].push_back(&x);
  if (steps == 0 || steps > (1u << 20)) throw Error("optimal selection: steps must be within 1..2^20");
  const size_t w = steps;
  std::vector<double> best(w + 1, 0.0), next;
  for (auto& [item, segs] : items) {
    std::sort(segs.begin(), segs.end(), [](const Candidate* a, const Candidate* b) { return a->id < b->id; });
    next = best;
    double cost = 0.0, value = 0.0;
    for (const Candidate* s : segs) {
      cost += double(s->cost);
      value += double(s->value);
      const double u = budget > 0.0f ? cost / double(budget) * double(w) : (cost > 0.0 ? double(w) + 1.0 : 0.0);
      const size_t units = size_t(std::min(double(w) + 1.0, std::floor(u)));
      if (units > w) break;
      for (size_t b = units; b <= w; ++b) next[b] = std::max(next[b], best[b - units] + value);
    }
    best.swap(next);
  }
  return best[w];
}

}  // namespace raybudget::select
