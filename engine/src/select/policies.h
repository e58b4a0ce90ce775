// Which objects get ray-traced effects this frame: every policy of ../shared/DESIGN.md
// section 1 as a CPU reference (the GPU select pass must reproduce these exactly). A policy
// sees candidates with a cost in budget units and a value (the relevance R), and returns
// the selected IDs; every policy but `all` keeps the summed cost within the budget.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace raybudget::select {

// `benefit` selects items (an object's shadows, reflections, refractions) by the density of
// their value R' (cost_model.h) with density's greedy fill-in: on candidates it is density.
enum class Policy { None, All, Paper, Density, Optimal, Nearest, Random, Benefit };
const char* policyName(Policy policy);
// Throws raybudget::Error naming the valid policies.
Policy parsePolicy(const std::string& name);

struct Candidate {
  uint32_t id = 0;
  float cost = 0.0f;      // predicted trace time (budget units), >= 0
  float value = 0.0f;     // relevance R, > 0
  float distance = 0.0f;  // D, for `nearest`
};

struct PolicyOptions {
  uint32_t graphPointers = 4;  // `paper`: N, the higher-relevance pointers per node
  uint32_t seed = 1;           // `random`
  uint32_t paperHops = 1;      // `paper`: pointer hops per pick (0: climb while one fits); docs/SELECTION.md
  uint32_t optimalSteps = 4096;  // `optimal`: the budget's resolution in the dynamic programme
  // `benefit`: the candidates are rate segments, ID item * 4 + k (shared/selection.h's
  // RB_SEGMENT_SLOTS), segment k taken only after k - 1 of the same item: the greedy of the
  // multiple-choice knapsack on each item's convex hull.
  bool rateSegments = false;
  // With rateSegments, frame mode's after-step: the first item in the walk's order whose first
  // segment (below full rate) did not fit is taken on the share of its tiles the budget left
  // pays for (shared/selection.h's RB_PARTIAL_MIN_SHARE; select_walk.comp).
  bool partialItem = false;
};

// The partial item: its first segment's candidate ID, the share of its tiles traced, and the
// cost (the budget the greedy left) and value (its value times the share) it adds.
struct PartialItem {
  uint32_t id = UINT32_MAX;
  float share = 0.0f;
  float cost = 0.0f, value = 0.0f;
};

struct Selection {
  std::vector<uint32_t> ids;  // ascending; the partial item's ID among them
  double cost = 0.0;
  double value = 0.0;
  PartialItem partial;
};

// The order keys the policies share with the GPU select pass.
uint32_t randomRank(uint32_t seed, uint32_t id);
float densityKey(const Candidate& candidate);  // value / cost, +inf for zero cost

// Throws raybudget::Error on a negative, NaN or infinite cost, value or budget.
void validateCandidates(std::span<const Candidate> candidates, float budget);

// Validates as above, then selects.
Selection selectObjects(Policy policy, std::span<const Candidate> candidates, float budget, const PolicyOptions& options = {});

// An upper bound on the value any selection within the budget can reach: the 0/1 knapsack
// with every cost rounded down to the dynamic programme's grid. With rate segments
// (`segments`) the multiple-choice knapsack: at most one option per item, an option being a
// prefix of its segments (their summed cost and value).
double optimalValueBound(std::span<const Candidate> candidates, float budget, uint32_t steps = 4096, bool segments = false);

}  // namespace raybudget::select
