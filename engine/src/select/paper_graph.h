// The paper's selection graph (section 4.2), built and walked as the paper describes it,
// with each ambiguity resolved as documented in docs/SELECTION.md:
//  - the cost chain runs from the most to the least costly node (ties: lower ID first);
//  - each node points to the N nodes just above it in relevance (ties: lower ID first), most
//    relevant first;
//  - the walk skips nodes that do not fit the remaining budget (they go to the graph of the
//    next frame), takes the first that fits, then follows its relevance pointers to the most
//    relevant unselected node that fits (one hop by default; optionally for as long as one
//    fits), and selects where it stops.
#pragma once
#include <span>
#include <vector>

#include "select/policies.h"

namespace raybudget::select {

struct PaperGraph {
  std::vector<uint32_t> byCost;     // candidate indices, the cost chain
  std::vector<uint32_t> pointers;   // N per candidate (index into candidates), UINT32_MAX: none
  uint32_t pointersPerNode = 0;
};

PaperGraph buildPaperGraph(std::span<const Candidate> candidates, uint32_t pointersPerNode);

// Candidate indices selected by walking `graph` within `budget`, in selection order; each
// pick follows at most `hops` relevance pointers (0: as many as keep fitting).
std::vector<uint32_t> walkPaperGraph(const PaperGraph& graph, std::span<const Candidate> candidates, float budget, uint32_t hops = 1);

}  // namespace raybudget::select
