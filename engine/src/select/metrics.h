// The paper's per-object quantities (Andrade et al., section 4.2; ../shared/DESIGN.md
// section 1) from an object's coverage of the frame: A, P, D, V = A·P/D, C = V·Q and
// R = (S·I + V)·K. The CPU reference of the GPU coverage and select passes, so the
// arithmetic is written once in a fixed order (the library builds without FMA contraction).
#pragma once
#include <cstdint>

namespace raybudget::select {

// What the coverage pass gathers per object: its pixels in the object-ID buffer and the
// sums of their integer pixel coordinates.
struct Coverage {
  uint32_t pixels = 0;
  uint64_t sumX = 0;
  uint64_t sumY = 0;
};

struct ObjectParams {
  float K = 1.0f;  // importance
  float Q = 1.0f;  // estimated secondary rays per covered pixel
  float I = 0.5f;  // weight of "selected last frame"
};

struct Metrics {
  float A = 0.0f;  // covered fraction of the frame, [0, 1]
  float P = 0.0f;  // centrality of the pixel centroid: 1 at the centre, 0 at the edge
  float D = 0.0f;  // camera to bounds centre, clamped below by the near plane
  float V = 0.0f;  // visibility A·P/D
  float C = 0.0f;  // cost V·Q
  float R = 0.0f;  // relevance (S·I + V)·K
  bool candidate = false;  // A > 0, Q > 0 and R > 0: something to trace and to gain
};

// `distance` may be anything (0 inside the object, huge far away, NaN from a broken
// transform): it is clamped to [nearPlane, 3.4e38] and NaN counts as far. Width and height
// must be positive, nearPlane positive; K, Q, I are validated at load (non-negative, finite).
Metrics objectMetrics(const Coverage& coverage, uint32_t width, uint32_t height, float distance, float nearPlane, const ObjectParams& params,
                      bool selectedLastFrame);

}  // namespace raybudget::select
