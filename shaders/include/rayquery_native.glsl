// The VK_KHR_ray_query implementation of rayquery.glsl: a thin mapping onto
// GL_EXT_ray_query. The TLAS is at RB_BVH_BINDING, the geometry table (uvec2 per BLAS
// geometry: first mesh triangle, material; see engine/src/passes/native_accel.h) at
// RB_BVH_BINDING + 1. Hits report the same object, primitive and material numbers as the
// compute tracer. The driver's traversal counts no work: rqWork is zero.
#ifndef RB_RAYQUERY_NATIVE_GLSL
#define RB_RAYQUERY_NATIVE_GLSL
#extension GL_EXT_ray_query : require
#include "shared/bvh.h"

layout(set = RB_BVH_SET, binding = RB_BVH_BINDING) uniform accelerationStructureEXT rqTlas;
layout(set = RB_BVH_SET, binding = RB_BVH_BINDING + 1, std430) readonly buffer RqGeometryBlock { uvec2 rqGeometries[]; };

// One query in flight per invocation, as with the compute tracer's global stack.
rayQueryEXT rqNative;

struct RayQuery {
  uint flags;
};

void rqInitialize(inout RayQuery q, uint flags, uint cullMask, vec3 origin, float tMin, vec3 dir, float tMax) {
  q.flags = flags;
  rayQueryInitializeEXT(rqNative, rqTlas, flags, cullMask, origin, tMin, dir, tMax);
}
bool rqProceed(inout RayQuery q) { return rayQueryProceedEXT(rqNative); }
void rqConfirm(inout RayQuery q) { rayQueryConfirmIntersectionEXT(rqNative); }

// `committed` must be a constant expression for the GL_EXT_ray_query getters: macros.
#define RQ_GEOMETRY(committed)                                                                  \
  rqGeometries[rayQueryGetIntersectionInstanceShaderBindingTableRecordOffsetEXT(rqNative, committed) + \
               uint(rayQueryGetIntersectionGeometryIndexEXT(rqNative, committed))]
#define RQ_PRIMITIVE(committed) (RQ_GEOMETRY(committed).x + uint(rayQueryGetIntersectionPrimitiveIndexEXT(rqNative, committed)))

bool rqCommittedHit(RayQuery q) { return rayQueryGetIntersectionTypeEXT(rqNative, true) == gl_RayQueryCommittedIntersectionTriangleEXT; }
float rqCommittedT(RayQuery q) { return rayQueryGetIntersectionTEXT(rqNative, true); }
uint rqCommittedObject(RayQuery q) { return uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rqNative, true)); }
uint rqCommittedPrimitive(RayQuery q) { return RQ_PRIMITIVE(true); }
uint rqCommittedMaterial(RayQuery q) { return RQ_GEOMETRY(true).y; }
vec2 rqCommittedBarycentrics(RayQuery q) { return rayQueryGetIntersectionBarycentricsEXT(rqNative, true); }
bool rqCommittedFrontFace(RayQuery q) { return rayQueryGetIntersectionFrontFaceEXT(rqNative, true); }
uint rqCandidateObject(RayQuery q) { return uint(rayQueryGetIntersectionInstanceCustomIndexEXT(rqNative, false)); }
uint rqCandidatePrimitive(RayQuery q) { return RQ_PRIMITIVE(false); }
uint rqCandidateMaterial(RayQuery q) { return RQ_GEOMETRY(false).y; }
vec2 rqCandidateBarycentrics(RayQuery q) { return rayQueryGetIntersectionBarycentricsEXT(rqNative, false); }
uvec2 rqWork(RayQuery q) { return uvec2(0u); }

#endif
