// How the compute tracer's BVH is built, settable from the renderer and the CLI.
#pragma once

namespace raybudget {

// Spatial splits in the per-mesh BVH build (Stich et al. 2009): a large or long triangle
// among small ones is cut into pieces with tighter boxes, so it stops inflating every node
// around it. They pay on such meshes (ToyCar: +21-34% rays/s) and cost 10-13x the build
// time with no gain on evenly tessellated ones (docs/TRACER.md).
enum class SpatialSplits {
  Auto,    // per mesh, where the mean triangle box area is at least twice the median
  Always,
  Never,
};

}  // namespace raybudget
