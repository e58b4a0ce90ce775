#include "bvh/ray_binning.h"

#include <algorithm>

namespace raybudget::bvh {
namespace {

// Spreads the low 4 bits of v to bits 0, 3, 6 and 9 (one axis of a Morton code).
uint32_t spread4(uint32_t v) { return (v & 1u) | (v & 2u) << 2 | (v & 4u) << 4 | (v & 8u) << 6; }

// Which quarter of [-1, 1] the direction's component d / |d| falls in, without the root:
// the inner boundaries +-0.5 compare 4 d^2 with |d|^2.
uint32_t directionCell(float d, float lengthSquared) {
  const bool outer = 4.0f * d * d >= lengthSquared;
  return d < 0.0f ? (outer ? 0u : 1u) : (outer ? 3u : 2u);
}

}  // namespace

uint32_t rayBinKey(const gpu::GpuRay& ray, const glm::vec3& originMin, const glm::vec3& originMax) {
  const glm::vec3 d(ray.dirTMax);
  const float lengthSquared = glm::dot(d, d);
  const glm::vec3 extent = originMax - originMin;
  uint32_t key = 0;
  for (int k = 0; k < 3; ++k) {
    const float u = extent[k] > 0.0f ? (ray.originTMin[k] - originMin[k]) * (15.99f / extent[k]) : 0.0f;
    key |= directionCell(d[k], lengthSquared) << (2 * k);
    key |= spread4(u >= 0.0f ? uint32_t(std::min(u, 15.0f)) : 0u) << (6 + k);  // NaN goes to cell 0
  }
  return key;
}

const std::vector<uint32_t>& RayBinner::bin(const std::vector<gpu::GpuRay>& rays) {
  glm::vec3 lo(0.0f), hi(0.0f);
  if (!rays.empty()) lo = hi = glm::vec3(rays[0].originTMin);
  for (const gpu::GpuRay& r : rays) {
    lo = glm::min(lo, glm::vec3(r.originTMin));
    hi = glm::max(hi, glm::vec3(r.originTMin));
  }
  keys_.resize(rays.size());
  start_.assign(kRayBinCount + 1, 0u);
  for (size_t i = 0; i < rays.size(); ++i) {
    keys_[i] = rayBinKey(rays[i], lo, hi);
    ++start_[keys_[i] + 1];
  }
  for (uint32_t b = 1; b <= kRayBinCount; ++b) start_[b] += start_[b - 1];
  order_.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) order_[start_[keys_[i]]++] = uint32_t(i);
  return order_;
}

std::vector<uint32_t> binRays(const std::vector<gpu::GpuRay>& rays) {
  RayBinner binner;
  return binner.bin(rays);
}

}  // namespace raybudget::bvh
