/* lang.h — the few macros by which the shared kernel source (gpu/kernel/) is one text for C11,
 * OpenCL C 1.2 and GLSL 4.50 (docs/architecture.md "One kernel source"). The language is told:
 * a GLSL program defines ICS_GLSL before its first include; OpenCL C defines __OPENCL_VERSION__;
 * anything else is C. The shared functions keep to the common subset:
 *   - scalars, fixed arrays and if/for/while; no pointers, structs, vectors, 64-bit integers or
 *     goto; a condition is always a comparison (GLSL has no int-to-bool conversion);
 *   - out and in-out parameters are arrays, written ICS_OUT double x[3] (C and OpenCL C pass the
 *     array's address, GLSL copies it back: the same as long as no two arguments alias);
 *   - memory is read through accessor macros that the including file defines over its own
 *     storage (its "view": the buffer pointers as parameters in OpenCL C, a struct in C, the
 *     buffers by name in GLSL), passed as the first parameters ICS_VIEW_PARAM / arguments
 *     ICS_VIEW_ARG, both empty in GLSL;
 *   - a double literal that is not exact in float is spelled through ICS_DBL_CONST (GLSL reads
 *     an unsuffixed literal as float);
 *   - exp and pow, which GLSL has in float only, through ICS_EXP and ICS_POW.
 * Every shared function is named ics_k_*. */
#ifndef ICS_KERNEL_LANG_H
#define ICS_KERNEL_LANG_H

#if defined(ICS_GLSL)
#define ICS_FN
#define ICS_OUT out
#define ICS_INOUT inout
#define ICS_CONST_IN const in
#define ICS_PRECISE precise
#define ICS_UINT uint
#define ICS_TO_INT(x) int(x)
#define ICS_TO_UINT(x) uint(x)
#define ICS_TO_FLOAT(x) float(x)
#define ICS_TO_DOUBLE(x) double(x)
#define ICS_FABS(x) abs(x)
#define ICS_FMIN(a, b) min(a, b)
#define ICS_FMAX(a, b) max(a, b)
#define ICS_EXP(x) double(exp(float(x)))
#define ICS_POW(x, y) double(pow(float(x), float(y)))
#define ICS_LOG2_POW2(k) findLSB(k)
/* the high word of the 64-bit product of two 32-bit words */
uint ics_k_mulhi(uint a, uint b) {
  uint hi, lo;
  umulExtended(a, b, hi, lo);
  return hi;
}
#define ICS_MULHI(a, b) ics_k_mulhi(a, b)
/* copysign(m, s) and infinity for doubles (GLSL has neither): bits */
double ics_k_copysign(double m, double s) {
  return (unpackDouble2x32(s).y & 0x80000000u) != 0u ? -abs(m) : abs(m);
}
#define ICS_COPYSIGN(m, s) ics_k_copysign(m, s)
#define ICS_DBL_INF packDouble2x32(uvec2(0u, 0x7ff00000u))

#else /* C11 and OpenCL C spell the rest alike */
#define ICS_OUT
#define ICS_INOUT
#define ICS_CONST_IN const
#define ICS_PRECISE
#define ICS_TO_INT(x) ((int)(x))
#define ICS_TO_FLOAT(x) ((float)(x))
#define ICS_TO_DOUBLE(x) ((double)(x))
#define ICS_FABS(x) fabs(x)
#define ICS_FMIN(a, b) fmin(a, b)
#define ICS_FMAX(a, b) fmax(a, b)
#define ICS_EXP(x) exp(x)
#define ICS_POW(x, y) pow(x, y)
#define ICS_COPYSIGN(m, s) copysign(m, s)
#define ICS_DBL_INF ((double)INFINITY)
#if defined(__OPENCL_VERSION__)
#define ICS_FN static
#define ICS_UINT uint
#define ICS_TO_UINT(x) ((uint)(x))
#define ICS_LOG2_POW2(k) ((int)(31u - clz(k)))
#define ICS_MULHI(a, b) ((uint)(((ulong)(a) * (b)) >> 32))
#else /* C11 */
#include <math.h>
#include <stdint.h>
#define ICS_FN static inline
#define ICS_UINT uint32_t
#define ICS_TO_UINT(x) ((uint32_t)(x))
#define ICS_LOG2_POW2(k) __builtin_ctz(k)
#define ICS_MULHI(a, b) ((uint32_t)(((uint64_t)(a) * (b)) >> 32))
#endif
#endif

/* ICS_MASK, a set of up to 64 volumes (the inside mask: bit i for the volume with bit i), and
 * its operations: any member, the lowest member's bit, the set without it, the number of
 * members, the set with one bit flipped. GLSL has no 64-bit integers: two words, low first. */
#if defined(ICS_GLSL)
#define ICS_MASK uvec2
bool ics_mask_any(uvec2 m) { return (m.x | m.y) != 0u; }
int ics_mask_lowest(uvec2 m) { return m.x != 0u ? findLSB(m.x) : 32 + findLSB(m.y); }
uvec2 ics_mask_drop(uvec2 m) {
  return m.x != 0u ? uvec2(m.x & (m.x - 1u), m.y) : uvec2(0u, m.y & (m.y - 1u));
}
int ics_mask_count(uvec2 m) { return bitCount(m.x) + bitCount(m.y); }
uvec2 ics_mask_toggle(uvec2 m, int bit) {
  return bit < 32 ? uvec2(m.x ^ (1u << bit), m.y) : uvec2(m.x, m.y ^ (1u << (bit - 32)));
}
#elif defined(__OPENCL_VERSION__)
#define ICS_MASK ulong
#define ics_mask_any(m) ((m) != 0)
#define ics_mask_lowest(m) ((int)(63 - clz((m) & (~(m) + 1))))
#define ics_mask_drop(m) ((m) & ((m)-1))
#define ics_mask_count(m) ((int)popcount(m))
#define ics_mask_toggle(m, bit) ((m) ^ (1UL << (bit)))
#else
#define ICS_MASK uint64_t
#define ics_mask_any(m) ((m) != 0)
#define ics_mask_lowest(m) __builtin_ctzll(m)
#define ics_mask_drop(m) ((m) & ((m)-1))
#define ics_mask_count(m) __builtin_popcountll(m)
#define ics_mask_toggle(m, bit) ((m) ^ ((uint64_t)1 << (bit)))
#endif

/* a double literal v spelled twice, v and v with GLSL's suffix (lf) */
#if defined(ICS_GLSL)
#define ICS_DBL_CONST(v, vlf) vlf
#else
#define ICS_DBL_CONST(v, vlf) v
#endif

#endif
