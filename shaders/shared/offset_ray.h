// Secondary-ray origins: offset a surface point along its geometric normal by a few
// integer ULPs (Waechter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems ch. 6), so the new ray never re-hits its own surface at any scale and
// any distance from the origin, where a fixed epsilon fails one way or the other.
// Shared by C++ and GLSL.
#ifndef RAYBUDGET_SHARED_OFFSET_RAY_H
#define RAYBUDGET_SHARED_OFFSET_RAY_H

#ifdef __cplusplus
#include <bit>
#include <cstdint>
#include <glm/glm.hpp>
namespace raybudget::gpu {
using glm::abs;
using glm::ivec3;
using glm::vec3;
inline vec3 rbIntBitsToFloat(ivec3 i) {
  return vec3(std::bit_cast<float>(i.x), std::bit_cast<float>(i.y), std::bit_cast<float>(i.z));
}
inline ivec3 rbFloatBitsToInt(vec3 f) { return ivec3(std::bit_cast<int32_t>(f.x), std::bit_cast<int32_t>(f.y), std::bit_cast<int32_t>(f.z)); }
#define RB_OFFSET_INLINE inline
#else
#define rbIntBitsToFloat intBitsToFloat
#define rbFloatBitsToInt floatBitsToInt
#define RB_OFFSET_INLINE
#endif

// p: the hit point; n: the geometric normal on the side the new ray leaves from.
RB_OFFSET_INLINE vec3 offsetRay(vec3 p, vec3 n) {
  const float origin = 1.0f / 32.0f;
  const float floatScale = 1.0f / 65536.0f;
  const float intScale = 256.0f;
  ivec3 ofi = ivec3(int(intScale * n.x), int(intScale * n.y), int(intScale * n.z));
  ivec3 pbits = rbFloatBitsToInt(p);
  // Move the bit patterns away from the surface: ulps grow with |p|, so the offset scales.
  vec3 pi = rbIntBitsToFloat(ivec3(pbits.x + (p.x < 0.0f ? -ofi.x : ofi.x), pbits.y + (p.y < 0.0f ? -ofi.y : ofi.y),
                                   pbits.z + (p.z < 0.0f ? -ofi.z : ofi.z)));
  // Near the origin ulps are tiny: there a small fixed offset is used instead.
  return vec3(abs(p.x) < origin ? p.x + floatScale * n.x : pi.x, abs(p.y) < origin ? p.y + floatScale * n.y : pi.y,
              abs(p.z) < origin ? p.z + floatScale * n.z : pi.z);
}

#ifdef __cplusplus
}  // namespace raybudget::gpu
#endif
#endif
