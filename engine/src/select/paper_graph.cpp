#include "select/paper_graph.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace raybudget::select {

PaperGraph buildPaperGraph(std::span<const Candidate> c, uint32_t n) {
  PaperGraph g;
  g.pointersPerNode = n;
  g.byCost.resize(c.size());
  std::iota(g.byCost.begin(), g.byCost.end(), 0u);
  std::sort(g.byCost.begin(), g.byCost.end(), [&](uint32_t a, uint32_t b) {
    return c[a].cost != c[b].cost ? c[a].cost > c[b].cost : c[a].id < c[b].id;
  });
  // Relevance order, most relevant first; a node's pointers are its predecessors here.
  std::vector<uint32_t> byValue(c.size());
  std::iota(byValue.begin(), byValue.end(), 0u);
  std::sort(byValue.begin(), byValue.end(), [&](uint32_t a, uint32_t b) {
    return c[a].value != c[b].value ? c[a].value > c[b].value : c[a].id < c[b].id;
  });
  g.pointers.assign(c.size() * n, UINT32_MAX);
  for (size_t rank = 0; rank < byValue.size(); ++rank) {
    const uint32_t node = byValue[rank];
    // Strictly higher relevance only: equal-R nodes ahead in the tie order are not "bigger".
    size_t first = rank;
    while (first > 0 && c[byValue[first - 1]].value == c[node].value) --first;
    const size_t from = first > n ? first - n : 0;
    for (size_t k = from, slot = 0; k < first; ++k, ++slot) g.pointers[size_t(node) * n + slot] = byValue[k];
  }
  return g;
}

std::vector<uint32_t> walkPaperGraph(const PaperGraph& g, std::span<const Candidate> c, float budget, uint32_t hops) {
  std::vector<uint32_t> chosen;
  std::vector<char> taken(c.size(), 0);
  float remaining = budget;
  size_t head = 0;
  while (true) {
    // Nodes too costly for what is left go to the next frame's graph: the budget only
    // shrinks, so they cannot fit later in this frame either.
    while (head < g.byCost.size() && (taken[g.byCost[head]] || c[g.byCost[head]].cost > remaining)) ++head;
    if (head == g.byCost.size()) break;
    uint32_t node = g.byCost[head];
    for (uint32_t hop = 0; hops == 0 || hop < hops; ++hop) {
      bool climbed = false;
      for (uint32_t slot = 0; slot < g.pointersPerNode; ++slot) {
        const uint32_t p = g.pointers[size_t(node) * g.pointersPerNode + slot];
        if (p == UINT32_MAX || taken[p] || c[p].cost > remaining) continue;
        node = p;  // pointers are ordered most relevant first: the first that fits
        climbed = true;
        break;
      }
      if (!climbed) break;
    }
    taken[node] = 1;
    remaining -= c[node].cost;
    chosen.push_back(node);
  }
  return chosen;
}

}  // namespace raybudget::select
