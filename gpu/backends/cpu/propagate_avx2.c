/* propagate_avx2.c — the vector loops of the CPU slab step (propagate_vec.h) for AVX2 with FMA: 8 lanes.
 * gpu/CMakeLists.txt compiles this file with the instruction set's flags where the compiler
 * targets it; elsewhere it only records that the path was not built. Nothing here runs before
 * simd_path.c has found the instructions on the processor. */
#include "propagate_simd.h"

#if defined(__x86_64__) && defined(__AVX2__) && defined(__FMA__)
#define ICS_VEC_W 8
#define ICS_VEC_FN ics_prop_rows_avx2
#include "propagate_vec.h"
const int ics_prop_built_avx2 = 1;
#else
ICS_PROP_NOT_BUILT(avx2)
#endif
