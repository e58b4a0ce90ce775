// The compute-BVH implementation of rayquery.glsl (shaders/shared/rayquery_traverse.h):
// nodes and triangles as RGBA32UI uniform texel buffers at RB_BVH_BINDING and
// RB_BVH_BINDING + 1 (unsigned: their w components hold integer bits, which a GPU's
// texture unit could flush as float denormals), the instances as a storage buffer at
// RB_BVH_BINDING + 2.
//
// Texel fetches rather than storage-buffer loads: on lavapipe they are ~20% faster for
// the node and triangle reads that dominate traversal (docs/TRACER.md).
//
// The traversal stack is a global of the invocation, not a member of RayQuery: GLSL passes
// the query by copy-in/copy-out, and copying a 64-entry array at every call halved the
// tracer's speed on lavapipe. So one query at a time per invocation (queries may follow
// each other, not nest).
#ifndef RB_RAYQUERY_COMPUTE_GLSL
#define RB_RAYQUERY_COMPUTE_GLSL
#include "shared/bvh.h"

layout(set = RB_BVH_SET, binding = RB_BVH_BINDING) uniform usamplerBuffer bvhNodeTexels;
layout(set = RB_BVH_SET, binding = RB_BVH_BINDING + 1) uniform usamplerBuffer bvhTriangleTexels;
layout(set = RB_BVH_SET, binding = RB_BVH_BINDING + 2, std430) readonly buffer BvhInstanceBlock { GpuInstance bvhInstances[]; };

GpuBvhNode rqLoadNode(uint i) {
  int t = int(i) * 4;
  return GpuBvhNode(uintBitsToFloat(texelFetch(bvhNodeTexels, t)), uintBitsToFloat(texelFetch(bvhNodeTexels, t + 1)),
                    uintBitsToFloat(texelFetch(bvhNodeTexels, t + 2)), uintBitsToFloat(texelFetch(bvhNodeTexels, t + 3)));
}

GpuTriangle rqLoadTriangle(uint i) {
  int t = int(i) * 3;
  return GpuTriangle(uintBitsToFloat(texelFetch(bvhTriangleTexels, t)), uintBitsToFloat(texelFetch(bvhTriangleTexels, t + 1)),
                     uintBitsToFloat(texelFetch(bvhTriangleTexels, t + 2)));
}

uint rqStack[RB_BVH_STACK_SIZE];

#define RB_BVH_NODE(i) rqLoadNode(i)
#define RB_BVH_TRIANGLE(i) rqLoadTriangle(i)
#define RB_BVH_INSTANCE(i) bvhInstances[i]
#define RB_RQ_EXTERNAL_STACK
#define RB_RQ_STACK_READ(q, i) rqStack[i]
#define RB_RQ_STACK_WRITE(q, i, v) rqStack[i] = (v)
#define RB_BVH_TLAS_ROOT RB_BVH_TLAS_ROOT_NODE
#include "shared/rayquery_traverse.h"

bool rqCommittedHit(RayQuery q) { return q.committedType == RB_RQ_HIT_TRIANGLE; }
float rqCommittedT(RayQuery q) { return q.tMax; }
uint rqCommittedObject(RayQuery q) { return q.committedObject; }
uint rqCommittedPrimitive(RayQuery q) { return q.committedPrimitive; }
uint rqCommittedMaterial(RayQuery q) { return q.committedMaterial; }
vec2 rqCommittedBarycentrics(RayQuery q) { return q.committedBary; }
bool rqCommittedFrontFace(RayQuery q) { return q.committedFrontFace; }
uint rqCandidateObject(RayQuery q) { return q.candidateObject; }
uint rqCandidatePrimitive(RayQuery q) { return q.candidatePrimitive; }
uint rqCandidateMaterial(RayQuery q) { return q.candidateMaterial; }
vec2 rqCandidateBarycentrics(RayQuery q) { return q.candidateBary; }
uvec2 rqWork(RayQuery q) { return uvec2(q.nodesVisited, q.trianglesTested); }

#endif
