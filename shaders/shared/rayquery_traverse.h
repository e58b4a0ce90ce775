// The ray-query traversal of our two-level BVH, written once for GLSL (the compute tracer,
// through shaders/include/rayquery.glsl) and C++ (the CPU reference in
// engine/src/bvh/cpu_rayquery.h). The includer defines how nodes, triangles and instances
// are read: RB_BVH_NODE(i), RB_BVH_TRIANGLE(i), RB_BVH_INSTANCE(i), RB_BVH_TLAS_ROOT.
//
// The interface mirrors GL_EXT_ray_query: rqInitialize, then rqProceed until it returns
// false; it returns true for each non-opaque candidate (alpha-masked triangles), which the
// caller tests and accepts with rqConfirm. Opaque hits are committed during traversal.
// The traversal state lives in the RayQuery, so rqProceed resumes where it stopped.
#ifndef RAYBUDGET_SHARED_RAYQUERY_TRAVERSE_H
#define RAYBUDGET_SHARED_RAYQUERY_TRAVERSE_H

#include "shared/bvh.h"
#include "shared/intersect.h"

#ifdef __cplusplus
namespace raybudget::gpu {
using glm::uvec4;
using glm::vec2;
using glm::vec4;
inline uint floatBitsToUint(float f) { return std::bit_cast<uint>(f); }
#endif

#ifndef RB_RQ_EXTERNAL_STACK
#define RB_RQ_STACK_READ(q, i) q.stack[i]
#define RB_RQ_STACK_WRITE(q, i, v) q.stack[i] = (v)
#endif

struct RayQuery {
  // The ray in world space, and in the current instance's object space while in a BLAS.
  vec3 worldOrigin;
  vec3 worldDir;
  vec3 origin;
  vec3 dir;
  vec3 invDir;
  RayShear shear;
  float tMin;
  uint flags;
  uint cullMask;
  // Traversal state.
#ifndef RB_RQ_EXTERNAL_STACK
  uint stack[RB_BVH_STACK_SIZE];
#endif
  int sp;
  uint node;         // next inner node to visit, RB_RQ_STACK_MARKER when none
  uint leafCursor;   // BLAS leaf triangles still to test: [leafCursor, leafEnd)
  uint leafEnd;
  uint instance;     // the instance (TLAS leaf) whose BLAS is being traversed
  uint instanceObject;  // its object ID
  uint instanceMaterialBase;  // added to the triangles' material fields
  bool inBlas;
  bool done;
  // Committed hit; tMax shrinks to it.
  float tMax;
  uint committedType;
  uint committedObject;
  uint committedPrimitive;
  uint committedMaterial;
  vec2 committedBary;
  bool committedFrontFace;
  // The candidate rqProceed returned true for.
  float candidateT;
  uint candidateObject;
  uint candidatePrimitive;
  uint candidateMaterial;
  vec2 candidateBary;
  bool candidateFrontFace;
  // Work counters (the per-object cost the budget learns from).
  uint nodesVisited;
  uint trianglesTested;
};

RB_INLINE void rqSetRay(RB_INOUT(RayQuery) q, vec3 origin, vec3 dir) {
  q.origin = origin;
  q.dir = dir;
  q.invDir = safeInverse(dir);
  q.shear = makeRayShear(dir);
}

RB_INLINE void rqInitialize(RB_INOUT(RayQuery) q, uint flags, uint cullMask, vec3 origin, float tMin, vec3 dir, float tMax) {
  q.worldOrigin = origin;
  q.worldDir = dir;
  rqSetRay(q, origin, dir);
  q.tMin = tMin;
  q.tMax = tMax;
  q.flags = flags;
  q.cullMask = cullMask;
  q.sp = 0;
  q.node = RB_BVH_TLAS_ROOT;
  q.leafCursor = 0u;
  q.leafEnd = 0u;
  q.instance = 0u;
  q.instanceObject = 0u;
  q.instanceMaterialBase = 0u;
  q.inBlas = false;
  q.done = false;
  q.committedType = RB_RQ_HIT_NONE;
  q.committedObject = 0u;
  q.committedPrimitive = 0u;
  q.committedMaterial = 0u;
  q.committedBary = vec2(0.0f);
  q.committedFrontFace = false;
  q.candidateT = 0.0f;
  q.candidateObject = 0u;
  q.candidatePrimitive = 0u;
  q.candidateMaterial = 0u;
  q.candidateBary = vec2(0.0f);
  q.candidateFrontFace = false;
  q.nodesVisited = 0u;
  q.trianglesTested = 0u;
}

// Accepts the current candidate as a hit.
RB_INLINE void rqConfirm(RB_INOUT(RayQuery) q) {
  q.tMax = q.candidateT;
  q.committedType = RB_RQ_HIT_TRIANGLE;
  q.committedObject = q.candidateObject;
  q.committedPrimitive = q.candidatePrimitive;
  q.committedMaterial = q.candidateMaterial;
  q.committedBary = q.candidateBary;
  q.committedFrontFace = q.candidateFrontFace;
  if ((q.flags & RB_RQ_TERMINATE_ON_FIRST_HIT) != 0u) q.done = true;
}

// Stack entries: an inner node index (bit 31 clear) or a leaf (bit 31 set). A BLAS leaf
// packs its first triangle in bits 0-27 and its count - 1 in bits 28-30 (the builder
// checks both fit); a TLAS leaf holds one instance, its index in bits 0-30.
#define RB_RQ_LEAF_BIT 0x80000000u

RB_INLINE uint rqChildEntry(bool inBlas, uint index, uint count) {
  if (count == 0u) return index;
  return inBlas ? (RB_RQ_LEAF_BIT | ((count - 1u) << 28) | index) : (RB_RQ_LEAF_BIT | index);
}

// Pops the next entry to visit into q.node (RB_RQ_STACK_MARKER when the stack is empty);
// crossing the marker leaves the BLAS and restores the world-space ray.
RB_INLINE void rqPop(RB_INOUT(RayQuery) q) {
  q.node = RB_RQ_STACK_MARKER;
  while (q.sp > 0) {
    --q.sp;
    uint entry = RB_RQ_STACK_READ(q, q.sp);
    if (entry != RB_RQ_STACK_MARKER) {
      q.node = entry;
      return;
    }
    q.inBlas = false;
    rqSetRay(q, q.worldOrigin, q.worldDir);
  }
}

// Tests both children of inner node `index`; continues with the nearer hit child and
// pushes the farther one.
RB_INLINE void rqVisitInner(RB_INOUT(RayQuery) q, uint index) {
  GpuBvhNode n = RB_BVH_NODE(index);
  ++q.nodesVisited;
  float tl = intersectBox(q.origin, q.invDir, vec3(n.leftMinIndex), vec3(n.leftMaxCount), q.tMin, q.tMax);
  float tr = intersectBox(q.origin, q.invDir, vec3(n.rightMinIndex), vec3(n.rightMaxCount), q.tMin, q.tMax);
  uint left = rqChildEntry(q.inBlas, floatBitsToUint(n.leftMinIndex.w), floatBitsToUint(n.leftMaxCount.w));
  uint right = rqChildEntry(q.inBlas, floatBitsToUint(n.rightMinIndex.w), floatBitsToUint(n.rightMaxCount.w));
  if (tl >= 0.0f && tr >= 0.0f) {
    bool leftFirst = tl <= tr;
    RB_RQ_STACK_WRITE(q, q.sp, leftFirst ? right : left);
    ++q.sp;
    q.node = leftFirst ? left : right;
  } else if (tl >= 0.0f) {
    q.node = left;
  } else if (tr >= 0.0f) {
    q.node = right;
  } else {
    rqPop(q);
  }
}

// Tests one triangle of the current BLAS leaf. Returns true when it produced a candidate
// for the caller (a non-opaque hit).
RB_INLINE bool rqTestTriangle(RB_INOUT(RayQuery) q, uint index) {
  GpuTriangle tri = RB_BVH_TRIANGLE(index);
  ++q.trianglesTested;
  float t;
  vec3 bary;
  bool front;
  if (!intersectTriangle(q.origin, q.shear, vec3(tri.v0Primitive), vec3(tri.v1Material), vec3(tri.v2Flags), q.tMin, q.tMax, t, bary, front))
    return false;
  if ((q.flags & RB_RQ_CULL_BACK) != 0u && !front) return false;
  if ((q.flags & RB_RQ_CULL_FRONT) != 0u && front) return false;
  q.candidateT = t;
  q.candidateObject = q.instanceObject;
  q.candidatePrimitive = floatBitsToUint(tri.v0Primitive.w);
  q.candidateMaterial = q.instanceMaterialBase + floatBitsToUint(tri.v1Material.w);
  q.candidateBary = vec2(bary.y, bary.z);
  q.candidateFrontFace = front;
  bool opaque = (q.flags & RB_RQ_OPAQUE) != 0u || (floatBitsToUint(tri.v2Flags.w) & RB_TRIANGLE_OPAQUE) != 0u;
  if (opaque) {
    rqConfirm(q);
    return false;
  }
  return true;
}

// Advances the traversal; true: a non-opaque candidate waits for rqConfirm (or is ignored
// by calling rqProceed again); false: traversal is complete.
//
// "While-while" structure (Aila & Laine, "Understanding the Efficiency of Ray Traversal on
// GPUs", 2009): a loop that only visits inner nodes until it holds a leaf, then a loop that
// only tests that leaf's triangles. SIMD lanes then run the same kind of work together;
// one loop doing one step of either kind per iteration made every lane pay for both.
RB_INLINE bool rqProceed(RB_INOUT(RayQuery) q) {
  while (!q.done) {
    while (q.leafCursor < q.leafEnd) {
      uint index = q.leafCursor;
      ++q.leafCursor;
      if (rqTestTriangle(q, index)) return true;
      if (q.done) return false;
    }
    if (q.node == RB_RQ_STACK_MARKER) rqPop(q);
    while (q.node != RB_RQ_STACK_MARKER && (q.node & RB_RQ_LEAF_BIT) == 0u) rqVisitInner(q, q.node);
    uint entry = q.node;
    if (entry == RB_RQ_STACK_MARKER) {
      q.done = true;
      break;
    }
    q.node = RB_RQ_STACK_MARKER;
    if (q.inBlas) {
      q.leafCursor = entry & 0x0FFFFFFFu;
      q.leafEnd = q.leafCursor + ((entry >> 28) & 7u) + 1u;
    } else {
      // A TLAS leaf: enter the instance's BLAS with the ray in its object space.
      uint inst = entry & 0x7FFFFFFFu;
      GpuInstance instance = RB_BVH_INSTANCE(inst);
      if ((instance.blasObjectMask.z & q.cullMask) == 0u) continue;
      q.instance = inst;
      q.instanceObject = instance.blasObjectMask.y;
      q.instanceMaterialBase = instance.blasObjectMask.w;
      vec4 o = vec4(q.worldOrigin, 1.0f), d = vec4(q.worldDir, 0.0f);
      rqSetRay(q, vec3(dot(instance.worldToObject[0], o), dot(instance.worldToObject[1], o), dot(instance.worldToObject[2], o)),
               vec3(dot(instance.worldToObject[0], d), dot(instance.worldToObject[1], d), dot(instance.worldToObject[2], d)));
      RB_RQ_STACK_WRITE(q, q.sp, RB_RQ_STACK_MARKER);
      ++q.sp;
      q.inBlas = true;
      q.node = instance.blasObjectMask.x;
    }
  }
  return false;
}

#ifdef __cplusplus
}  // namespace raybudget::gpu
#endif
#endif
