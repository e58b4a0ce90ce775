// Spatial splits for the BLAS build (Stich, Friedrich, Dietrich 2009, "Spatial splits in
// bounding volume hierarchies"; Embree's rtcBuildBVH makes them in high quality mode when
// given a split callback, which calls this): a triangle reference that straddles a split
// plane becomes two references with tighter boxes, so large or long triangles stop inflating
// the boxes of the nodes around them. A triangle may then sit in several leaves.
#pragma once
#include <glm/glm.hpp>

#include "bvh/embree_build.h"

namespace raybudget::bvh {

// Boxes of the parts of triangle `v` inside `clip` on either side of the plane
// x[axis] == position. Conservative: every point of the triangle inside `clip` with
// x[axis] <= position lies in `left`, every one with x[axis] >= position in `right`
// (edge crossings are widened by a bound on their rounding error). A side the triangle does
// not reach inside `clip` comes back empty (isEmpty).
void splitTriangleBox(const glm::vec3 (&v)[3], const Box& clip, int axis, float position, Box& left, Box& right);

// True when `b` holds no point (min > max on some axis).
bool isEmpty(const Box& b);

}  // namespace raybudget::bvh
