// The ray-query interface of the effect shaders, mirroring GL_EXT_ray_query:
//   RayQuery q; rqInitialize(q, flags, cullMask, origin, tMin, dir, tMax);
//   while (rqProceed(q)) if (<candidate passes the alpha test>) rqConfirm(q);
//   rqCommittedHit(q), rqCommittedT(q), rqCommittedObject/Primitive/Material(q),
//   rqCommittedBarycentrics(q), rqCommittedFrontFace(q), rqCandidate*(q), rqWork(q).
// Flags are RB_RQ_* (shared/bvh.h), equal to gl_RayFlags*EXT. Two implementations, chosen
// when the shader is compiled (the build compiles each tracing shader twice): our compute
// BVH (default) and, with RB_NATIVE_RAY_QUERY, the device's VK_KHR_ray_query. The includer
// defines RB_BVH_SET and RB_BVH_BINDING (three consecutive bindings) first.
//
// One query at a time per invocation: queries may follow each other, not nest.
#ifndef RB_RAYQUERY_GLSL
#define RB_RAYQUERY_GLSL
#ifdef RB_NATIVE_RAY_QUERY
#include "include/rayquery_native.glsl"
#else
#include "include/rayquery_compute.glsl"
#endif
#endif
