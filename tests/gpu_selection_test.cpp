// The selection policies on the GPU equal their CPU reference exactly: thousands of random
// candidate sets (1 to 100,000 candidates; ties, zeros, huge and tiny values).
#include <algorithm>
#include <bit>
#include <cmath>

#include <gtest/gtest.h>

#include "bvh/ray_sets.h"
#include "select/gpu_selector.h"
#include "select/policies.h"
#include "support/random_candidates.h"
#include "support/render_helpers.h"

namespace raybudget {
namespace {

using select::Candidate;
using select::Policy;

using GpuSelection = test::ValidatedGpuTest;

// Both sorts (the bitonic one of a GPU, the merge sort of a CPU device) on every set; every
// third set drawn from a few levels (near-equal densities).
TEST_F(GpuSelection, EqualsTheCpuReferenceOnThousandsOfRandomSets) {
  select::GpuSelector bitonic(ctx, 4096, select::SortMethod::Bitonic), merge(ctx, 4096, select::SortMethod::Merge);
  bvh::Rng rng(77);
  size_t compared = 0;
  for (int trial = 0; trial < 500; ++trial) {
    select::GpuSelector& gpu = trial % 2 ? bitonic : merge;
    const size_t n = 1 + size_t(rng.next() * (trial % 25 == 0 ? 4000.0f : 60.0f));
    const std::vector<Candidate> c = trial % 3 == 2 ? test::leveledCandidates(rng, n) : test::randomCandidates(rng, n);
    const float budget = test::randomBudget(rng, c);
    // N from 0 to 5, and 40 (more pointers than a subgroup's lanes: the scan takes batches).
    const select::PolicyOptions options{trial % 7 == 6 ? 40u : uint32_t(trial % 7), uint32_t(trial * 31 + 1), uint32_t(trial % 3)};
    for (Policy p : {Policy::None, Policy::All, Policy::Paper, Policy::Density, Policy::Nearest, Policy::Random}) {
      const select::Selection cpu = select::selectObjects(p, c, budget, options), g = gpu.select(c, p, budget, options);
      ASSERT_EQ(g.ids, cpu.ids) << select::policyName(p) << ", trial " << trial << ", " << n << " candidates, budget " << budget;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 3000u);
}

// `benefit` over rate segments (the multiple-choice knapsack's greedy: a segment only onto its
// item's previous one) equals its CPU reference on random sets too.
TEST_F(GpuSelection, RateSegmentsEqualTheCpuReferenceOnRandomSets) {
  select::GpuSelector bitonic(ctx, 4096, select::SortMethod::Bitonic), merge(ctx, 4096, select::SortMethod::Merge);
  bvh::Rng rng(91);
  select::PolicyOptions options;
  options.rateSegments = true;
  size_t upgraded = 0;
  for (int trial = 0; trial < 300; ++trial) {
    select::GpuSelector& gpu = trial % 2 ? bitonic : merge;
    const size_t n = 1 + size_t(rng.next() * (trial % 25 == 0 ? 900.0f : 60.0f));
    const std::vector<Candidate> c = test::randomSegments(rng, n);
    const float budget = test::randomBudget(rng, c);
    const select::Selection cpu = select::selectObjects(Policy::Benefit, c, budget, options), g = gpu.select(c, Policy::Benefit, budget, options);
    ASSERT_EQ(g.ids, cpu.ids) << "trial " << trial << ", " << c.size() << " segments, budget " << budget;
    for (uint32_t id : cpu.ids) upgraded += id % 4 != 0;
  }
  EXPECT_GT(upgraded, 100u) << "the sets should take later segments too";
}

// Where everything is taken the walk sums cost and value in no order (the order of frame mode's
// candidates is the GPU scheduling's): the same pairs under other IDs, so in another order,
// give the same sums bit for bit, within the fixed-point bound of the exact sum.
TEST_F(GpuSelection, EverythingTakenSumsTheSameInAnyOrder) {
  select::GpuSelector gpu(ctx, 6000);
  bvh::Rng rng(13);
  size_t floatOrderMattered = 0;
  for (size_t n : {1u, 2u, 37u, 1000u, 5000u}) {
    const std::vector<Candidate> c = test::randomCandidates(rng, n);
    std::vector<Candidate> shuffled = c;
    for (size_t i = n; i > 1; --i) std::swap(shuffled[i - 1].id, shuffled[size_t(rng.next() * float(i)) % i].id);
    gpu.select(c, Policy::All, 1.0f);
    const select::GpuSelector::WalkSums a = gpu.lastWalkSums();
    gpu.select(shuffled, Policy::All, 1.0f);
    const select::GpuSelector::WalkSums b = gpu.lastWalkSums();
    EXPECT_EQ(std::bit_cast<uint32_t>(a.cost), std::bit_cast<uint32_t>(b.cost)) << n << " candidates";
    EXPECT_EQ(std::bit_cast<uint32_t>(a.value), std::bit_cast<uint32_t>(b.value)) << n << " candidates";
    double cost = 0.0, value = 0.0;
    float inIdOrder = 0.0f, inShuffledOrder = 0.0f;
    for (const Candidate& x : c) cost += x.cost, value += x.value;
    std::vector<Candidate> byId = shuffled;
    std::sort(byId.begin(), byId.end(), [](const Candidate& l, const Candidate& r) { return l.id < r.id; });
    for (const Candidate& x : c) inIdOrder += x.value;
    for (const Candidate& x : byId) inShuffledOrder += x.value;
    floatOrderMattered += inIdOrder != inShuffledOrder;
    // Each term rounds to 2^-30 of a power of two at most twice the largest; three float roundings.
    const double bound = double(n) * std::ldexp(1.0, -30) + 4.0 * std::ldexp(1.0, -24);
    EXPECT_NEAR(a.cost, cost, bound * cost) << n << " candidates";
    EXPECT_NEAR(a.value, value, bound * value) << n << " candidates";
  }
  EXPECT_GT(floatOrderMattered, 0u) << "a float sum in list order should differ for some set";
}

class GpuSelectionSort : public test::ValidatedGpuTest, public ::testing::WithParamInterface<select::SortMethod> {};

TEST_P(GpuSelectionSort, EqualsTheCpuReferenceAtOneHundredThousand) {
  select::GpuSelector gpu(ctx, 100000, GetParam());
  bvh::Rng rng(5);
  const std::vector<Candidate> c = test::randomCandidates(rng, 100000);
  for (Policy p : {Policy::Paper, Policy::Density, Policy::Nearest, Policy::Random}) {
    const select::Selection cpu = select::selectObjects(p, c, 3000.0f), g = gpu.select(c, p, 3000.0f);
    EXPECT_EQ(g.ids, cpu.ids) << select::policyName(p);
    EXPECT_GT(g.ids.size(), 100u);
  }
  // All-equal relevance and cost: ties everywhere, decided by ID alone.
  const std::vector<Candidate> same(5000, Candidate{0, 1.0f, 1.0f, 1.0f});
  std::vector<Candidate> ids = same;
  for (uint32_t i = 0; i < ids.size(); ++i) ids[i].id = 5000 - i;
  for (Policy p : {Policy::Paper, Policy::Density, Policy::Nearest, Policy::Random})
    EXPECT_EQ(gpu.select(ids, p, 100.0f).ids, select::selectObjects(p, ids, 100.0f).ids) << select::policyName(p);
}

INSTANTIATE_TEST_SUITE_P(Sorts, GpuSelectionSort, ::testing::Values(select::SortMethod::Bitonic, select::SortMethod::Merge),
                         [](const ::testing::TestParamInfo<select::SortMethod>& p) {
                           return std::string(p.param == select::SortMethod::Bitonic ? "bitonic" : "merge");
                         });

TEST_F(GpuSelection, RejectsWhatTheCpuRejects) {
  select::GpuSelector gpu(ctx, 16);
  const std::vector<Candidate> ok = {{0, 1, 1, 0}};
  EXPECT_THROW(gpu.select(ok, Policy::Density, NAN), Error);
  EXPECT_THROW(gpu.select(ok, Policy::Optimal, 1.0f), Error);
  EXPECT_THROW(gpu.select(std::vector<Candidate>(17, Candidate{0, 1, 1, 0}), Policy::Density, 1.0f), Error);
  EXPECT_TRUE(gpu.select({}, Policy::Paper, 1.0f).ids.empty());
}

}  // namespace
}  // namespace raybudget
