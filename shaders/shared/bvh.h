// GPU layout of the two-level BVH, shared by C++ (engine/src/bvh) and GLSL
// (shaders/include/rayquery_compute.glsl). One node array holds every BLAS and the TLAS;
// child and primitive indices are absolute, so traversal never adds offsets.
#ifndef RAYBUDGET_SHARED_BVH_H
#define RAYBUDGET_SHARED_BVH_H

#ifdef __cplusplus
#include "shared/types.h"
namespace raybudget::gpu {
#endif

// 64 bytes: a BVH2 node holding both children's boxes, so one node fetch decides both.
// Child encoding (w components, uint bits): count == 0: `index` is an inner node;
// count > 0: a leaf of `count` triangles (BLAS) or instances (TLAS) from `index`.
// Boxes are rounded outwards to float; an empty child has min > max and is never entered.
struct GpuBvhNode {
  vec4 leftMinIndex;   // xyz left box min, w left index
  vec4 leftMaxCount;   // xyz left box max, w left count
  vec4 rightMinIndex;  // xyz right box min, w right index
  vec4 rightMaxCount;  // xyz right box max, w right count
};

// 48 bytes: a triangle in leaf order, in its mesh's object space.
struct GpuTriangle {
  vec4 v0Primitive;  // xyz vertex 0, w original triangle index in the mesh (uint bits)
  vec4 v1Material;   // xyz vertex 1, w material index relative to the instance's material base (uint bits)
  vec4 v2Flags;      // xyz vertex 2, w flags (uint bits): RB_TRIANGLE_OPAQUE
};

// 64 bytes: an object instance in the TLAS.
struct GpuInstance {
  vec4 worldToObject[3];  // rows of the affine world -> object transform
  // x BLAS root node, y object ID, z cull mask (8 bits), w material base: a hit's material
  // is w plus the triangle's material field. One-material meshes store 0 in every triangle
  // and their material here, so meshes that differ only in material share one BLAS.
  uvec4 blasObjectMask;
};

// 32 bytes: a ray for the batch tracer (tests, benchmarks).
struct GpuRay {
  vec4 originTMin;
  vec4 dirTMax;
};

// 32 bytes: what the batch tracer reports per ray.
struct GpuHit {
  float t;           // committed distance (tMax when nothing was hit)
  uint object;
  uint primitive;
  uint flags;        // bit 0 hit, bit 1 front face
  vec4 baryWork;     // xy barycentrics of v1 and v2, z nodes visited, w triangles tested (as floats)
};

#ifdef __cplusplus
}  // namespace raybudget::gpu
#endif

// The TLAS root is always node 0 (a copy of the root the builder placed after the BLAS
// nodes), so the traversal needs no root parameter.
#define RB_BVH_TLAS_ROOT_NODE 0u
#define RB_TRIANGLE_OPAQUE 1u

// Ray-query flags and hit types (mirroring GL_EXT_ray_query's gl_RayFlags*EXT and
// gl_RayQueryCommittedIntersection*EXT).
#define RB_RQ_OPAQUE 1u                  // treat every triangle as opaque: no candidates
#define RB_RQ_TERMINATE_ON_FIRST_HIT 4u  // any hit will do (shadow rays)
#define RB_RQ_CULL_BACK 16u
#define RB_RQ_CULL_FRONT 32u
#define RB_RQ_HIT_NONE 0u
#define RB_RQ_HIT_TRIANGLE 1u
// Stack entry that separates the BLAS part of the stack from the TLAS part below it.
#define RB_RQ_STACK_MARKER 0xFFFFFFFFu
// Traversal stack depth: the builder caps BLAS and TLAS depths so that both fit.
#define RB_BVH_STACK_SIZE 64
#define RB_BVH_MAX_LEAF_SIZE 4

#endif
