#include "bvh/spatial_split.h"

#include <limits>

namespace raybudget::bvh {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Box emptyBox() { return {glm::vec3(kInf), glm::vec3(-kInf)}; }

void grow(Box& b, const glm::vec3& p) {
  b.min = glm::min(b.min, p);
  b.max = glm::max(b.max, p);
}

// A box around the point where edge a-e crosses the plane x[axis] == position: computed in
// float, widened by 16 float epsilons of the edge's coordinates (the computation's error is
// a few), then kept within the edge's own box, where the exact point lies.
Box crossing(const glm::vec3& a, const glm::vec3& e, int axis, float position) {
  const float t = (position - a[axis]) / (e[axis] - a[axis]);
  const glm::vec3 p = a + t * (e - a);
  const glm::vec3 slack = (glm::abs(a) + glm::abs(e)) * 0x1p-20f;
  return {glm::max(p - slack, glm::min(a, e)), glm::min(p + slack, glm::max(a, e))};
}

Box intersect(const Box& a, const Box& b) { return {glm::max(a.min, b.min), glm::min(a.max, b.max)}; }

}  // namespace

void splitTriangleBox(const glm::vec3 (&v)[3], const Box& clip, int axis, float position, Box& left, Box& right) {
  left = emptyBox();
  right = emptyBox();
  for (int i = 0; i < 3; ++i) {
    const glm::vec3& a = v[i];
    const glm::vec3& b = v[(i + 1) % 3];
    if (a[axis] <= position) grow(left, a);
    if (a[axis] >= position) grow(right, a);
    if ((a[axis] < position && b[axis] > position) || (a[axis] > position && b[axis] < position)) {
      const Box c = crossing(a, b, axis, position);
      for (Box* side : {&left, &right}) {
        side->min = glm::min(side->min, c.min);
        side->max = glm::max(side->max, c.max);
      }
    }
  }
  // The crossing points were widened along the axis too: the plane bounds both sides exactly.
  left.max[axis] = std::min(left.max[axis], position);
  right.min[axis] = std::max(right.min[axis], position);
  left = intersect(left, clip);
  right = intersect(right, clip);
}

bool isEmpty(const Box& b) { return b.min.x > b.max.x || b.min.y > b.max.y || b.min.z > b.max.z; }

}  // namespace raybudget::bvh
