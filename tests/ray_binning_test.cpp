// Binning rays for the batch tracer (bvh/ray_binning.h): a permutation, bins in key order,
// and neighbours that share a direction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "bvh/ray_binning.h"
#include "bvh/ray_sets.h"

namespace raybudget {
namespace {

std::vector<gpu::GpuRay> randomRays(size_t n, uint64_t seed) {
  bvh::Rng rng(seed);
  std::vector<gpu::GpuRay> rays(n);
  for (gpu::GpuRay& r : rays) {
    const glm::vec3 o(rng.next() * 20.0f - 10.0f, rng.next() * 5.0f, rng.next() * 20.0f - 10.0f);
    const glm::vec3 d = glm::normalize(glm::vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f) + glm::vec3(1e-4f));
    r = {glm::vec4(o, 1e-3f), glm::vec4(d, 100.0f)};
  }
  return rays;
}

TEST(RayBinning, IsAPermutationInKeyOrder) {
  const std::vector<gpu::GpuRay> rays = randomRays(20000, 7);
  const std::vector<uint32_t> order = bvh::binRays(rays);
  ASSERT_EQ(order.size(), rays.size());
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
  glm::vec3 omin(std::numeric_limits<float>::max()), omax(-std::numeric_limits<float>::max());
  for (const auto& r : rays) {
    omin = glm::min(omin, glm::vec3(r.originTMin));
    omax = glm::max(omax, glm::vec3(r.originTMin));
  }
  for (size_t i = 1; i < order.size(); ++i) {
    const uint32_t a = bvh::rayBinKey(rays[order[i - 1]], omin, omax), b = bvh::rayBinKey(rays[order[i]], omin, omax);
    ASSERT_LE(a, b) << "at " << i;
    if (a == b) {
      ASSERT_LT(order[i - 1], order[i]) << "stable within a bin";
    }
  }
}

TEST(RayBinning, NeighboursShareARegionAndADirection) {
  // Rays from 40 surface points, in random order: consecutive rays start far apart and point
  // 90 degrees apart on average; binned, neighbours start together and point alike.
  bvh::Rng rng(11);
  std::vector<glm::vec3> points(40);
  for (glm::vec3& p : points) p = glm::vec3(rng.next() * 20.0f - 10.0f, rng.next() * 5.0f, rng.next() * 20.0f - 10.0f);
  std::vector<gpu::GpuRay> rays = randomRays(20000, 13);
  for (gpu::GpuRay& r : rays) r.originTMin = glm::vec4(points[size_t(rng.next() * 40.0f) % 40], 1e-3f);
  const std::vector<uint32_t> order = bvh::binRays(rays);
  double givenAngle = 0.0, binnedAngle = 0.0, givenDistance = 0.0, binnedDistance = 0.0;
  auto angle = [&](uint32_t a, uint32_t b) {
    return std::acos(std::clamp(glm::dot(glm::vec3(rays[a].dirTMax), glm::vec3(rays[b].dirTMax)), -1.0f, 1.0f));
  };
  auto distance = [&](uint32_t a, uint32_t b) { return glm::distance(glm::vec3(rays[a].originTMin), glm::vec3(rays[b].originTMin)); };
  for (uint32_t i = 1; i < rays.size(); ++i) {
    givenAngle += angle(i - 1, i);
    binnedAngle += angle(order[i - 1], order[i]);
    givenDistance += distance(i - 1, i);
    binnedDistance += distance(order[i - 1], order[i]);
  }
  const double n = double(rays.size() - 1);
  EXPECT_GT(givenAngle / n, 1.4);
  EXPECT_LT(binnedAngle / n, 0.8) << "mean angle between neighbours, radians";
  EXPECT_GT(givenDistance / n, 5.0);
  EXPECT_LT(binnedDistance / n, 0.1) << "mean distance between neighbours' origins";
}

TEST(RayBinning, DegenerateRaysStillGetABin) {
  // NaN and zero directions, one origin for all: no crash, still a permutation.
  std::vector<gpu::GpuRay> rays(5, gpu::GpuRay{glm::vec4(1.0f, 2.0f, 3.0f, 0.0f), glm::vec4(0.0f, 0.0f, 1.0f, 1.0f)});
  rays[1].dirTMax = glm::vec4(std::nanf(""), 0.0f, 0.0f, 1.0f);
  rays[2].dirTMax = glm::vec4(0.0f);
  rays[3].originTMin = glm::vec4(std::nanf(""));
  std::vector<uint32_t> order = bvh::binRays(rays);
  std::sort(order.begin(), order.end());
  EXPECT_EQ(order, (std::vector<uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(bvh::binRays({}).empty());
}

}  // namespace
}  // namespace raybudget
