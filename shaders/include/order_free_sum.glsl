#ifndef RB_ORDER_FREE_SUM_GLSL
#define RB_ORDER_FREE_SUM_GLSL
// A subgroup's sum of non-negative floats that does not depend on the order of its terms.
// The candidates lie in their list in the order select_candidates.comp's atomics appended
// them, which the GPU's scheduling decides: a float sum in list order differed between two
// identical frames in its last bits, and a probe stride taken from one could differ by one.
// Each term becomes a fixed-point integer at 2^-30 of the power of two above the largest
// term (a maximum, exact in any order), in three 10-bit parts whose sums are exact (below
// 2^32 for up to 2^22 terms); the float sum is then three products and adds in one order.
// RB_ORDER_FREE_MAX_TERMS (shared/selection.h) bounds the terms. Needs
// GL_KHR_shader_subgroup_arithmetic.

// 2^k for k in [-126, 127], exactly (exp2 may round).
float powerOfTwo(int k) { return uintBitsToFloat(uint(k + 127) << 23); }

// The lanes' largest term (-0 counts as 0; a NaN sorts above +inf and stays NaN).
float subgroupLargest(float laneLargest) { return uintBitsToFloat(subgroupMax(floatBitsToUint(laneLargest) & 0x7FFFFFFFu)); }
float largerTerm(float largest, float x) { return uintBitsToFloat(max(floatBitsToUint(largest), floatBitsToUint(x) & 0x7FFFFFFFu)); }

// The exponent e of the sum's scale: largest < 2^e (at least -96, so that 2^(30 - e) is a float).
int fixedExponent(float largest) {
  int e;
  frexp(largest, e);
  return max(e, -96);
}

// The factor that takes a term to fixed point at the scale of `largest` (0 where the largest
// is +inf or NaN: fixedSum then returns it).
float fixedScale(float largest) { return largest < uintBitsToFloat(0x7F800000u) ? powerOfTwo(30 - fixedExponent(largest)) : 0.0; }

// A term's three parts at a sum's fixedScale.
uvec3 fixedParts(float x, float scale) {
  uint q = uint(roundEven(x * scale));
  return uvec3(q & 1023u, (q >> 10) & 1023u, q >> 20);
}

// The sum of every lane's terms from the lanes' sums of their parts.
float fixedSum(uvec3 laneParts, float largest) {
  uvec3 s = subgroupAdd(laneParts);
  if (!(largest < uintBitsToFloat(0x7F800000u))) return largest;
  precise float f = float(s.z) * 1048576.0 + float(s.y) * 1024.0 + float(s.x);
  return f * powerOfTwo(fixedExponent(largest) - 30);
}

#endif
