#include "select/metrics.h"

#include <algorithm>
#include <cmath>

namespace raybudget::select {

Metrics objectMetrics(const Coverage& coverage, uint32_t width, uint32_t height, float distance, float nearPlane, const ObjectParams& params,
                      bool selectedLastFrame) {
  Metrics m;
  m.D = std::isnan(distance) ? 3.4e38f : std::clamp(distance, nearPlane, 3.4e38f);
  if (coverage.pixels > 0) {
    const float pixels = float(coverage.pixels);
    m.A = pixels / (float(width) * float(height));
    // The centroid of the pixel centres in [-1, 1]^2; P falls linearly from the centre to
    // the nearest screen edge (Chebyshev distance), so it is 0 on any edge.
    // Float operations in the order shaders/select/object_metrics.comp does them (the 64-bit sums
    // arrive there as two 32-bit words).
    auto wide = [](uint64_t v) { return float(uint32_t(v >> 32)) * 4294967296.0f + float(uint32_t(v)); };
    const float cx = (wide(coverage.sumX) / pixels + 0.5f) / float(width) * 2.0f - 1.0f;
    const float cy = (wide(coverage.sumY) / pixels + 0.5f) / float(height) * 2.0f - 1.0f;
    m.P = std::clamp(1.0f - std::max(std::fabs(cx), std::fabs(cy)), 0.0f, 1.0f);
  }
  m.V = m.A * m.P / m.D;
  m.C = m.V * params.Q;
  m.R = ((selectedLastFrame ? params.I : 0.0f) + m.V) * params.K;
  m.candidate = coverage.pixels > 0 && params.Q > 0.0f && m.R > 0.0f;
  return m;
}

}  // namespace raybudget::select
