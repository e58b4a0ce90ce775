// Ray/box and ray/triangle tests written once for C++ (with glm) and GLSL, so that the CPU
// reference traversal computes bit-identical results to the compute tracer.
//
// Triangles: the watertight test of Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection" (JCGT 2013): the ray is sheared so that it runs along +z, and the three
// 2D edge functions are evaluated with the same operands for a shared edge from both
// sides, so a ray never slips between two triangles. `RB_PRECISE` keeps the compiler from
// fusing multiply-adds, which would break that symmetry.
//
// Boxes: the slab test with the far distance scaled by 1 + 2*gamma(3) (Ize, "Robust BVH Ray
// Traversal", JCGT 2013), so rounding never culls a box the ray touches; zero direction
// components are replaced by a signed tiny value, so no 0 * inf NaN can arise.
#ifndef RAYBUDGET_SHARED_INTERSECT_H
#define RAYBUDGET_SHARED_INTERSECT_H

#ifdef __cplusplus
#include <cmath>
#include <glm/glm.hpp>
#define RB_INOUT(T) T&
#define RB_OUT(T) T&
#define RB_PRECISE
#define RB_INLINE inline
namespace raybudget::gpu {
using glm::abs;
using glm::ivec3;
using glm::max;
using glm::min;
using glm::vec3;
#else
#define RB_INOUT(T) inout T
#define RB_OUT(T) out T
#define RB_PRECISE precise
#define RB_INLINE
#endif

// Per-ray constants of the watertight test.
struct RayShear {
  ivec3 k;     // kx, ky, kz: permutation with kz the dominant axis of the direction
  vec3 shear;  // Sx, Sy, Sz
};

RB_INLINE RayShear makeRayShear(vec3 dir) {
  vec3 a = abs(dir);
  int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  if (dir[kz] < 0.0f) {  // keep the triangle's winding
    int tmp = kx;
    kx = ky;
    ky = tmp;
  }
  RayShear s;
  s.k = ivec3(kx, ky, kz);
  s.shear = vec3(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0f / dir[kz]);
  return s;
}

// Returns true on a hit with tMin < t < tMax; `bary` gets the weights of v1 and v2, and
// `frontFace` whether the triangle is counter-clockwise as seen from the ray origin.
RB_INLINE bool intersectTriangle(vec3 org, RayShear s, vec3 v0, vec3 v1, vec3 v2, float tMin, float tMax, RB_OUT(float) t,
                                 RB_OUT(vec3) bary, RB_OUT(bool) frontFace) {
  vec3 A = v0 - org, B = v1 - org, C = v2 - org;
  int kx = s.k.x, ky = s.k.y, kz = s.k.z;
  RB_PRECISE float Ax = A[kx] - s.shear.x * A[kz];
  RB_PRECISE float Ay = A[ky] - s.shear.y * A[kz];
  RB_PRECISE float Bx = B[kx] - s.shear.x * B[kz];
  RB_PRECISE float By = B[ky] - s.shear.y * B[kz];
  RB_PRECISE float Cx = C[kx] - s.shear.x * C[kz];
  RB_PRECISE float Cy = C[ky] - s.shear.y * C[kz];
  RB_PRECISE float U = Cx * By - Cy * Bx;
  RB_PRECISE float V = Ax * Cy - Ay * Cx;
  RB_PRECISE float W = Bx * Ay - By * Ax;
  t = 0.0f;
  bary = vec3(0.0f);
  frontFace = false;
  if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f)) return false;
  RB_PRECISE float det = U + V + W;
  if (det == 0.0f) return false;
  RB_PRECISE float Az = s.shear.z * A[kz];
  RB_PRECISE float Bz = s.shear.z * B[kz];
  RB_PRECISE float Cz = s.shear.z * C[kz];
  RB_PRECISE float T = U * Az + V * Bz + W * Cz;
  // t = T / det must lie in (tMin, tMax): compare without dividing, on the sign of det.
  if (det > 0.0f ? (T <= tMin * det || T >= tMax * det) : (T >= tMin * det || T <= tMax * det)) return false;
  float invDet = 1.0f / det;
  t = T * invDet;
  bary = vec3(U * invDet, V * invDet, W * invDet);
  frontFace = det > 0.0f;
  return true;
}

// Signed, never-zero reciprocal of each direction component.
RB_INLINE vec3 safeInverse(vec3 d) {
  const float tiny = 1e-30f;
  vec3 s = vec3(d.x < 0.0f ? -tiny : tiny, d.y < 0.0f ? -tiny : tiny, d.z < 0.0f ? -tiny : tiny);
  return vec3(1.0f / (abs(d.x) > tiny ? d.x : s.x), 1.0f / (abs(d.y) > tiny ? d.y : s.y), 1.0f / (abs(d.z) > tiny ? d.z : s.z));
}

// Entry distance of the ray into [bmin, bmax] within [tMin, tMax], or a negative number.
// Near and far planes are chosen by the direction's sign (not by min/max), so a box with
// min > max is empty: the builder uses one for the missing child of a one-leaf tree.
RB_INLINE float intersectBox(vec3 org, vec3 invDir, vec3 bmin, vec3 bmax, float tMin, float tMax) {
  vec3 t0 = (bmin - org) * invDir;
  vec3 t1 = (bmax - org) * invDir;
  vec3 lo = vec3(invDir.x >= 0.0f ? t0.x : t1.x, invDir.y >= 0.0f ? t0.y : t1.y, invDir.z >= 0.0f ? t0.z : t1.z);
  vec3 hi = vec3(invDir.x >= 0.0f ? t1.x : t0.x, invDir.y >= 0.0f ? t1.y : t0.y, invDir.z >= 0.0f ? t1.z : t0.z);
  float tNear = max(max(lo.x, lo.y), max(lo.z, tMin));
  // 1 + 2 * gamma(3), gamma(n) = n * eps / (1 - n * eps), eps = 2^-24.
  float tFar = min(min(hi.x, hi.y), min(hi.z, tMax)) * 1.0000003576279f;
  return tNear <= tFar ? tNear : -1.0f;
}

#ifdef __cplusplus
}  // namespace raybudget::gpu
#endif
#endif
