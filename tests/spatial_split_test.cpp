// Splitting a triangle's box at a plane (bvh/spatial_split.h) must stay conservative: every
// point of the triangle inside the clip box lies in the box of its side, at any scale and
// far from the origin, through repeated splits. Points are placed exactly (in double) on the
// float triangle; the edge crossings of the plane, where rounding bites, are among them.
#include <gtest/gtest.h>

#include <vector>

#include "bvh/ray_sets.h"
#include "bvh/spatial_split.h"

namespace raybudget {
namespace {

bool contains(const bvh::Box& b, const glm::dvec3& p) {
  for (int k = 0; k < 3; ++k)
    if (p[k] < double(b.min[k]) || p[k] > double(b.max[k])) return false;
  return true;
}

struct Checker {
  const glm::vec3 (&v)[3];
  std::vector<glm::dvec3> samples;  // exact points of the triangle
  bvh::Rng& rng;
  size_t checked = 0, outside = 0, splits = 0;

  // Splits `clip` at a random plane inside it, checks both sides, and recurses `depth` times.
  void splitAndCheck(const bvh::Box& clip, int depth) {
    const int axis = int(rng.next() * 3.0f) % 3;
    if (!(clip.max[axis] > clip.min[axis])) return;
    const float position = clip.min[axis] + (clip.max[axis] - clip.min[axis]) * (0.05f + 0.9f * rng.next());
    bvh::Box left, right;
    bvh::splitTriangleBox(v, clip, axis, position, left, right);
    ++splits;
    std::vector<glm::dvec3> points = samples;
    for (int i = 0; i < 3; ++i) {  // where the edges cross the plane, exactly
      const glm::dvec3 a(v[i]), b(v[(i + 1) % 3]);
      if ((a[axis] - position) * (b[axis] - position) < 0.0) points.push_back(a + (double(position) - a[axis]) / (b[axis] - a[axis]) * (b - a));
    }
    for (const glm::dvec3& p : points) {
      if (!contains(clip, p)) continue;
      if (p[axis] <= double(position)) ++checked, outside += !contains(left, p);
      if (p[axis] >= double(position)) ++checked, outside += !contains(right, p);
    }
    if (depth == 0) return;
    if (!bvh::isEmpty(left)) splitAndCheck(left, depth - 1);
    if (!bvh::isEmpty(right)) splitAndCheck(right, depth - 1);
  }
};

TEST(SpatialSplit, BothSidesHoldEveryPointOfTheTriangle) {
  bvh::Rng rng(17);
  size_t checked = 0, outside = 0, splits = 0;
  // (scale, distance from the origin): tiny to large triangles, near and far.
  for (const auto& [scale, distance] : {std::pair{1e-3f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1e3f}, {1e4f, 0.0f}, {1e3f, 1e5f}}) {
    for (int t = 0; t < 200; ++t) {
      const glm::vec3 place = glm::vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f) * 2.0f * distance;
      glm::vec3 v[3];
      for (glm::vec3& p : v) p = place + glm::vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f) * scale;
      if (t % 4 == 0) v[2] = v[0] + (v[1] - v[0]) * 0.37f + glm::vec3(0.0f, scale * 1e-3f, 0.0f);  // a sliver
      Checker c{v, {}, rng};
      for (int s = 0; s < 200; ++s) {
        double b1 = rng.next(), b2 = rng.next();
        if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
        c.samples.push_back(glm::dvec3(v[0]) * (1.0 - b1 - b2) + glm::dvec3(v[1]) * b1 + glm::dvec3(v[2]) * b2);
      }
      for (const glm::vec3& p : v) c.samples.push_back(glm::dvec3(p));
      const bvh::Box box{glm::min(v[0], glm::min(v[1], v[2])), glm::max(v[0], glm::max(v[1], v[2]))};
      c.splitAndCheck(box, 5);
      checked += c.checked, outside += c.outside, splits += c.splits;
    }
  }
  EXPECT_GT(splits, 10000u);
  EXPECT_GT(checked, 1000000u);
  EXPECT_EQ(outside, 0u) << outside << " of " << checked << " triangle points fell outside their side's box";
}

TEST(SpatialSplit, ASideTheTriangleMissesComesBackEmpty) {
  const glm::vec3 v[3] = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  // Clip to x in [3, 4]; split at the plane y = 2. Above it the triangle (x + y <= 4) has
  // x <= 2: nothing inside the clip box. Below it: the box of that part, cut by the clip box.
  const bvh::Box clip{{3, 0, -1}, {4, 4, 1}};
  bvh::Box left, right;
  bvh::splitTriangleBox(v, clip, 1, 2.0f, left, right);
  EXPECT_TRUE(bvh::isEmpty(right));
  ASSERT_FALSE(bvh::isEmpty(left));
  EXPECT_EQ(left.min, glm::vec3(3, 0, 0));
  EXPECT_EQ(left.max, glm::vec3(4, 2, 0)) << "bounded by the plane, not widened past it";
}

}  // namespace
}  // namespace raybudget
