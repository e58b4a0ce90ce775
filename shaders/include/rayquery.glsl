// The ray-query interface for effect shaders, implemented by our compute BVH traversal
// (shaders/shared/rayquery_traverse.h). The includer chooses where the BVH is bound by
// defining RB_BVH_SET and RB_BVH_BINDING (three consecutive storage buffers: nodes,
// triangles, instances) before including this file.
#ifndef RB_RAYQUERY_GLSL
#define RB_RAYQUERY_GLSL
#include "shared/bvh.h"

layout(set = RB_BVH_SET, binding = RB_BVH_BINDING, std430) readonly buffer BvhNodeBlock { GpuBvhNode bvhNodes[]; };
layout(set = RB_BVH_SET, binding = RB_BVH_BINDING + 1, std430) readonly buffer BvhTriangleBlock { GpuTriangle bvhTriangles[]; };
layout(set = RB_BVH_SET, binding = RB_BVH_BINDING + 2, std430) readonly buffer BvhInstanceBlock { GpuInstance bvhInstances[]; };

#define RB_BVH_NODE(i) bvhNodes[i]
#define RB_BVH_TRIANGLE(i) bvhTriangles[i]
#define RB_BVH_INSTANCE(i) bvhInstances[i]
#define RB_BVH_TLAS_ROOT RB_BVH_TLAS_ROOT_NODE
#include "shared/rayquery_traverse.h"

#endif
