// The order of the `random` policy: a 32-bit integer hash (lowbias32, Wellons) of the seed
// and the object ID. Shared by C++ (select::randomRank) and GLSL (the GPU selection's
// keys), so that both order the candidates the same way.
#ifndef RAYBUDGET_SHARED_RANDOM_RANK_H
#define RAYBUDGET_SHARED_RANDOM_RANK_H

#ifdef __cplusplus
#include <cstdint>
namespace raybudget::gpu {
#define RB_RANK_UINT uint32_t
#define RB_RANK_INLINE inline
#else
#define RB_RANK_UINT uint
#define RB_RANK_INLINE
#endif

RB_RANK_INLINE RB_RANK_UINT randomRank(RB_RANK_UINT seed, RB_RANK_UINT id) {
  RB_RANK_UINT x = id ^ (seed * 0x9E3779B9u);
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return x;
}

#ifdef __cplusplus
}  // namespace raybudget::gpu
#endif
#endif
