// The heuristic's CPU reference: the paper's quantities from coverage, and every selection
// policy: semantics on hand-worked cases, and on thousands of random candidate sets the
// budget holds, no policy beats the knapsack bound, and density keeps its 1/2 guarantee.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "bvh/ray_sets.h"
#include "raybudget/error.h"
#include "select/metrics.h"
#include "select/paper_graph.h"
#include "select/policies.h"
#include "support/random_candidates.h"

namespace raybudget {
namespace {

using select::Candidate;
using select::Policy;

// Coverage of the pixels [x0, x1) x [y0, y1).
select::Coverage rect(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
  select::Coverage c;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x) {
      ++c.pixels;
      c.sumX += x;
      c.sumY += y;
    }
  return c;
}

TEST(SelectionMetrics, FollowThePaperEquations) {
  const select::ObjectParams params{2.0f, 3.0f, 0.5f};
  // A centred 20x10 block of a 100x50 frame, 4 units away.
  const select::Metrics m = select::objectMetrics(rect(40, 20, 60, 30), 100, 50, 4.0f, 0.1f, params, false);
  EXPECT_FLOAT_EQ(m.A, 200.0f / 5000.0f);
  EXPECT_FLOAT_EQ(m.P, 1.0f);
  EXPECT_FLOAT_EQ(m.D, 4.0f);
  EXPECT_FLOAT_EQ(m.V, m.A * m.P / 4.0f) << "V = A*P/D (the text; equation 1 misprints the divisor as P)";
  EXPECT_FLOAT_EQ(m.C, m.V * 3.0f);
  EXPECT_FLOAT_EQ(m.R, m.V * 2.0f);
  EXPECT_TRUE(m.candidate);
  const select::Metrics s = select::objectMetrics(rect(40, 20, 60, 30), 100, 50, 4.0f, 0.1f, params, true);
  EXPECT_FLOAT_EQ(s.R, (0.5f + m.V) * 2.0f) << "R = (S*I + V)*K";
  // Centrality falls linearly to 0 at the nearest edge: a block hugging the left edge.
  const select::Metrics edge = select::objectMetrics(rect(0, 20, 2, 30), 100, 50, 4.0f, 0.1f, params, false);
  EXPECT_NEAR(edge.P, 0.02f, 1e-6f);
  const select::Metrics half = select::objectMetrics(rect(24, 20, 26, 30), 100, 50, 4.0f, 0.1f, params, false);
  EXPECT_NEAR(half.P, 0.5f, 1e-6f);
}

TEST(SelectionMetrics, DegenerateInputsGiveNoNaNAndNoCandidate) {
  const select::ObjectParams params;
  // Camera inside the object: D clamps to the near plane.
  const select::Metrics inside = select::objectMetrics(rect(0, 0, 100, 50), 100, 50, 0.0f, 0.05f, params, false);
  EXPECT_FLOAT_EQ(inside.D, 0.05f);
  EXPECT_TRUE(std::isfinite(inside.V) && inside.candidate);
  // Not visible (A = 0), or behind the camera (no pixels either): never a candidate.
  const select::Metrics hidden = select::objectMetrics({}, 100, 50, 3.0f, 0.05f, params, true);
  EXPECT_EQ(hidden.A, 0.0f);
  EXPECT_EQ(hidden.V, 0.0f);
  EXPECT_FALSE(hidden.candidate) << "selected last frame but not visible now";
  // Q = 0: nothing to trace; K = 0: nothing to gain.
  EXPECT_FALSE(select::objectMetrics(rect(0, 0, 10, 10), 100, 50, 3.0f, 0.05f, {1.0f, 0.0f, 0.5f}, false).candidate);
  EXPECT_FALSE(select::objectMetrics(rect(0, 0, 10, 10), 100, 50, 3.0f, 0.05f, {0.0f, 1.0f, 0.5f}, false).candidate);
  // A NaN or infinite distance counts as far away: finite, tiny V.
  for (float d : {NAN, INFINITY, 1e38f}) {
    const select::Metrics far = select::objectMetrics(rect(40, 20, 60, 30), 100, 50, d, 0.05f, params, false);
    EXPECT_TRUE(std::isfinite(far.V) && std::isfinite(far.C) && std::isfinite(far.R)) << d;
  }
}

// The worked example of docs/SELECTION.md: costs A 5, B 4, C 3, D 1; relevance A 1, B 3,
// C 2, D 4; budget 6. The cost chain is A, B, C, D; A points (N = 2) to B then C, B to D.
TEST(SelectionPaper, WalksTheGraphAsTheDocumentSays) {
  const std::vector<Candidate> c = {{0, 5, 1, 0}, {1, 4, 3, 0}, {2, 3, 2, 0}, {3, 1, 4, 0}};
  const select::PaperGraph g = select::buildPaperGraph(c, 2);
  EXPECT_EQ(g.byCost, (std::vector<uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(g.pointers[0 * 2 + 0], 1u);
  EXPECT_EQ(g.pointers[0 * 2 + 1], 2u);
  EXPECT_EQ(g.pointers[1 * 2 + 0], 3u);
  EXPECT_EQ(g.pointers[1 * 2 + 1], UINT32_MAX);
  EXPECT_EQ(g.pointers[3 * 2 + 0], UINT32_MAX) << "the most relevant node points nowhere";
  // Climbing while a pointer fits: A -> B -> D, select D, 5 left; A fits, climb to B (D is
  // taken), select B; 1 left: nothing else fits.
  EXPECT_EQ(select::walkPaperGraph(g, c, 6.0f, 0), (std::vector<uint32_t>{3, 1}));
  // One hop per pick (the default): A fits, hop to B (4 fits): select B, 2 left; then A, B
  // and C do not fit or are taken, D fits (no pointers): select D.
  EXPECT_EQ(select::walkPaperGraph(g, c, 6.0f, 1), (std::vector<uint32_t>{1, 3}));
  // Without pointers the walk takes the most costly node that fits, again and again.
  EXPECT_EQ(select::walkPaperGraph(select::buildPaperGraph(c, 0), c, 6.0f), (std::vector<uint32_t>{0, 3}));
  // Equal relevance is not "higher": no pointers between ties.
  const std::vector<Candidate> tie = {{0, 2, 1, 0}, {1, 1, 1, 0}};
  const select::PaperGraph t = select::buildPaperGraph(tie, 3);
  for (uint32_t p : t.pointers) EXPECT_EQ(p, UINT32_MAX);
}

TEST(SelectionPolicies, BaselinesAndDensityDoWhatTheySay) {
  const std::vector<Candidate> c = {{10, 4, 4, 9}, {11, 1, 3, 1}, {12, 2, 1, 2}, {13, 3, 3, 5}};
  EXPECT_TRUE(select::selectObjects(Policy::None, c, 100.0f).ids.empty());
  EXPECT_EQ(select::selectObjects(Policy::All, c, 0.0f).ids, (std::vector<uint32_t>{10, 11, 12, 13})) << "all ignores the budget";
  EXPECT_EQ(select::selectObjects(Policy::Nearest, c, 4.0f).ids, (std::vector<uint32_t>{11, 12})) << "nearest first, skipping what does not fit";
  // Density: 11 (3/1), 13 (1), 10 (1, costlier), 12 (0.5): 11 + 13 fit in 4.
  EXPECT_EQ(select::selectObjects(Policy::Density, c, 4.0f).ids, (std::vector<uint32_t>{11, 13}));
  EXPECT_EQ(select::selectObjects(Policy::Optimal, c, 4.0f).ids, (std::vector<uint32_t>{11, 13}));
  // The single-item fallback: a tiny dense object would block the valuable one.
  const std::vector<Candidate> trap = {{0, 0.1f, 1, 0}, {1, 10, 10, 0}};
  EXPECT_EQ(select::selectObjects(Policy::Density, trap, 10.0f).ids, (std::vector<uint32_t>{1}));
  // Random is reproducible by seed.
  std::vector<Candidate> many;
  for (uint32_t i = 0; i < 200; ++i) many.push_back({i, 1.0f, 1.0f, 0.0f});
  const auto r1 = select::selectObjects(Policy::Random, many, 20.0f, {4, 7u}), r2 = select::selectObjects(Policy::Random, many, 20.0f, {4, 7u});
  const auto r3 = select::selectObjects(Policy::Random, many, 20.0f, {4, 8u});
  EXPECT_EQ(r1.ids, r2.ids);
  EXPECT_NE(r1.ids, r3.ids);
  EXPECT_EQ(r1.ids.size(), 20u);
}

// Rate segments: a segment goes in only onto its item's previous one, in density order with
// fill-in; the multiple-choice bound takes at most one prefix per item and equals a brute
// force over the options.
TEST(SelectionPolicies, RateSegmentsClimbEachItemsHullInOrder) {
  select::PolicyOptions o;
  o.rateSegments = true;
  // Item 0: densities 10, 2, 0.5; item 1: one segment of density 2; item 2: its second
  // segment is denser than its first (not a hull), so it must wait for the first.
  const std::vector<Candidate> c = {{0, 1, 10, 0}, {1, 1, 2, 0}, {2, 2, 1, 0}, {4, 4, 8, 0}, {8, 5, 5, 0}, {9, 1, 100, 0}};
  // Density order: 9, 0, 1 and 4 (tied, by ID), 8, 2. Budget 5: 9 waits for 8, 0 (4 left),
  // 1 (3 left), 4 and 8 do not fit, 2 (1 left).
  EXPECT_EQ(select::selectObjects(Policy::Benefit, c, 5.0f, o).ids, (std::vector<uint32_t>{0, 1, 2}));
  // Budget 6: 0, 1, 4 (0 left).
  EXPECT_EQ(select::selectObjects(Policy::Benefit, c, 6.0f, o).ids, (std::vector<uint32_t>{0, 1, 4}));
  // Budget 11: 0, 1, 4 (5 left), 8 (0 left); 9 came before 8 in the order, so it stays out.
  EXPECT_EQ(select::selectObjects(Policy::Benefit, c, 11.0f, o).ids, (std::vector<uint32_t>{0, 1, 4, 8}));
  // Rates that do not fit select nothing: every first segment costs 1 or more.
  EXPECT_TRUE(select::selectObjects(Policy::Benefit, c, 0.5f, o).ids.empty());
  // Without segments the same candidates are independent: 9 goes in first (4 left), 0, 1, 2.
  EXPECT_EQ(select::selectObjects(Policy::Benefit, c, 5.0f).ids, (std::vector<uint32_t>{0, 1, 2, 9}));
  // The bound: options per item are the prefixes; brute force over them.
  for (float budget : {0.0f, 1.0f, 3.0f, 5.0f, 6.0f, 7.0f, 11.0f, 14.0f}) {
    const std::vector<std::vector<std::pair<double, double>>> options = {{{1, 10}, {2, 12}, {4, 13}}, {{4, 8}}, {{5, 5}, {6, 105}}};
    double best = 0.0;
    for (int a = -1; a < 3; ++a)
      for (int b = -1; b < 1; ++b)
        for (int d = -1; d < 2; ++d) {
          double cost = 0.0, value = 0.0;
          if (a >= 0) cost += options[0][size_t(a)].first, value += options[0][size_t(a)].second;
          if (b >= 0) cost += options[1][size_t(b)].first, value += options[1][size_t(b)].second;
          if (d >= 0) cost += options[2][size_t(d)].first, value += options[2][size_t(d)].second;
          if (cost <= budget) best = std::max(best, value);
        }
    EXPECT_DOUBLE_EQ(select::optimalValueBound(c, budget, 1024, true), best) << "budget " << budget;
    EXPECT_GE(select::optimalValueBound(c, budget, 1024, true), select::selectObjects(Policy::Benefit, c, budget, o).value - 1e-9);
  }
}

// The partial item (frame mode's after-step over rate segments): the first item in density
// order whose first segment did not fit takes the share of its tiles the budget left, at
// least an eighth; never a shadow item (its one segment is full rate), never when the best
// single candidate replaces the greedy selection.
TEST(SelectionPolicies, ThePartialItemTakesTheShareOfItsTilesTheBudgetLeft) {
  select::PolicyOptions o;
  o.rateSegments = true;
  o.partialItem = true;
  // IDs item * 4 + segment; item = object * 3 + effect (0 shadows, 1 reflections).
  const uint32_t reflections0 = (0 * 3 + 1) * 4, shadows1 = (1 * 3 + 0) * 4, reflections1 = (1 * 3 + 1) * 4, reflections2 = (2 * 3 + 1) * 4,
                 reflections3 = (3 * 3 + 1) * 4;
  const std::vector<Candidate> c = {{reflections0, 1, 10, 0}, {shadows1, 2.5f, 15, 0}, {reflections1, 4, 20, 0}, {reflections2, 0.5f, 20, 0},
                                    {reflections3, 0.25f, 0.5f, 0}};
  // Density order: reflections 2 (40), 0 (10), shadows 1 (6), reflections 1 (5), 3 (2). Budget
  // 3.5: reflections 2 and 0 (2 left); shadows 1 does not fit and is no partial item while a
  // reflection item takes what is left (below);
  // reflections 1 takes 2 / 4 of its tiles, and the walk stops there: reflections 3, which
  // fits, is worth less per cost than the partial item's share.
  const select::Selection s = select::selectObjects(Policy::Benefit, c, 3.5f, o);
  EXPECT_EQ(s.ids, (std::vector<uint32_t>{reflections0, reflections1, reflections2}));
  EXPECT_EQ(s.partial.id, reflections1);
  EXPECT_EQ(s.partial.share, 0.5f);
  EXPECT_DOUBLE_EQ(s.cost, 3.5);
  EXPECT_DOUBLE_EQ(s.value, 40.0);
  // Without the partial item (the GPU's select(), the benchmark's bound): the greedy alone,
  // with its fill-in.
  o.partialItem = false;
  EXPECT_EQ(select::selectObjects(Policy::Benefit, c, 3.5f, o).ids, (std::vector<uint32_t>{reflections0, reflections2, reflections3}));
  o.partialItem = true;
  // Under an eighth left (1.75 leaves 0.25 of 4): no partial item, and the walk goes on to
  // reflections 3, which fits.
  EXPECT_EQ(select::selectObjects(Policy::Benefit, c, 1.75f, o).partial.id, UINT32_MAX);
  EXPECT_EQ(select::selectObjects(Policy::Benefit, c, 1.75f, o).ids, (std::vector<uint32_t>{reflections0, reflections2, reflections3}));
  // The greedy with its partial item beats the best single candidate it would have lost to.
  const std::vector<Candidate> pair = {{reflections0, 1, 10, 0}, {reflections1, 3, 25, 0}};
  const select::Selection g = select::selectObjects(Policy::Benefit, pair, 3.0f, o);
  EXPECT_EQ(g.ids, (std::vector<uint32_t>{reflections0, reflections1}));
  EXPECT_EQ(g.partial.id, reflections1);
  EXPECT_FLOAT_EQ(g.partial.share, 2.0f / 3.0f);
  // The best single candidate beats the greedy, whose partial share is under an eighth: no
  // partial item beside it.
  const std::vector<Candidate> single = {{reflections0, 2.8f, 30, 0}, {reflections1, 3, 31, 0}};
  const select::Selection b = select::selectObjects(Policy::Benefit, single, 3.0f, o);
  EXPECT_EQ(b.ids, (std::vector<uint32_t>{reflections1}));
  EXPECT_EQ(b.partial.id, UINT32_MAX);
  // A shadow item takes what the whole walk left, where no reflection or refraction item took
  // it: alone, 1 of its 2.5; beside a reflection item whose share is under an eighth (0.5 of
  // 40), the 0.5 left after reflections 0.
  const std::vector<Candidate> shadow = {{shadows1, 2.5f, 15, 0}};
  const select::Selection alone = select::selectObjects(Policy::Benefit, shadow, 1.0f, o);
  EXPECT_EQ(alone.ids, (std::vector<uint32_t>{shadows1}));
  EXPECT_EQ(alone.partial.id, shadows1);
  EXPECT_FLOAT_EQ(alone.partial.share, 0.4f);
  const std::vector<Candidate> under = {{reflections0, 1, 10, 0}, {shadows1, 2.5f, 15, 0}, {reflections1, 40, 41, 0}};
  const select::Selection left = select::selectObjects(Policy::Benefit, under, 1.5f, o);
  EXPECT_EQ(left.ids, (std::vector<uint32_t>{reflections0, shadows1}));
  EXPECT_EQ(left.partial.id, shadows1);
  EXPECT_FLOAT_EQ(left.partial.share, 0.2f);
  EXPECT_EQ(select::selectObjects(Policy::Benefit, shadow, 0.25f, o).ids, std::vector<uint32_t>{}) << "under an eighth: nothing";
}

TEST(SelectionPolicies, RejectBadInput) {
  const std::vector<Candidate> ok = {{0, 1, 1, 0}};
  EXPECT_THROW(select::selectObjects(Policy::Paper, ok, -1.0f), Error);
  EXPECT_THROW(select::selectObjects(Policy::Paper, ok, NAN), Error);
  EXPECT_THROW(select::selectObjects(Policy::Paper, ok, INFINITY), Error);
  for (const Candidate& bad : {Candidate{0, NAN, 1, 0}, Candidate{0, -1, 1, 0}, Candidate{0, 1, INFINITY, 0}, Candidate{0, 1, -2, 0}})
    EXPECT_THROW(select::selectObjects(Policy::Density, std::vector<Candidate>{bad}, 1.0f), Error);
  EXPECT_THROW(select::parsePolicy("greedy"), Error);
  EXPECT_EQ(select::parsePolicy("paper"), Policy::Paper);
}

TEST(SelectionPolicies, ThousandsOfRandomSetsKeepTheBudgetAndTheBounds) {
  bvh::Rng rng(123);
  size_t sets = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const size_t n = 1 + size_t(rng.next() * (trial % 10 == 0 ? 400.0f : 40.0f));
    const std::vector<Candidate> c = test::randomCandidates(rng, n);
    const float budget = test::randomBudget(rng, c);
    const double bound = select::optimalValueBound(c, budget);
    const select::Selection optimal = select::selectObjects(Policy::Optimal, c, budget);
    for (Policy p : {Policy::Paper, Policy::Density, Policy::Optimal, Policy::Nearest, Policy::Random}) {
      const select::Selection s = select::selectObjects(p, c, budget, {uint32_t(trial % 6), uint32_t(trial), uint32_t(trial % 3)});
      ASSERT_LE(s.cost, double(budget) * (1.0 + 1e-5) + 1e-12) << select::policyName(p) << " overspends, trial " << trial;
      ASSERT_EQ(std::set<uint32_t>(s.ids.begin(), s.ids.end()).size(), s.ids.size()) << "an object selected twice";
      ASSERT_LE(s.value, bound * (1.0 + 1e-9) + 1e-9) << select::policyName(p) << " beats the knapsack bound, trial " << trial;
      ASSERT_TRUE(std::isfinite(s.value));
    }
    const double densityValue = select::selectObjects(Policy::Density, c, budget).value;
    ASSERT_GE(densityValue, 0.5 * optimal.value * (1.0 - 1e-9)) << "density lost its 1/2 guarantee, trial " << trial;
    ++sets;
  }
  EXPECT_EQ(sets, 3000u);
}

TEST(SelectionPolicies, HundredThousandObjects) {
  bvh::Rng rng(9);
  const std::vector<Candidate> c = test::randomCandidates(rng, 100000);
  for (Policy p : {Policy::Paper, Policy::Density, Policy::Nearest, Policy::Random}) {
    const select::Selection s = select::selectObjects(p, c, 5000.0f);
    EXPECT_LE(s.cost, 5000.0 * (1.0 + 1e-5));
    EXPECT_GT(s.ids.size(), 100u) << select::policyName(p);
  }
  EXPECT_THROW(select::selectObjects(Policy::Optimal, c, 5000.0f), Error) << "the dynamic programme is for benchmark-sized sets";
}

}  // namespace
}  // namespace raybudget
