/* propagate_sse2.c — the vector loops of the CPU slab step (propagate_vec.h) for SSE2 (the x86-64 baseline): 4 lanes, a multiply and an add (no FMA).
 * gpu/CMakeLists.txt compiles this file with the instruction set's flags where the compiler
 * targets it; elsewhere it only records that the path was not built. Nothing here runs before
 * simd_path.c has found the instructions on the processor. */
#include "propagate_simd.h"

#if defined(__x86_64__) && defined(__SSE2__)
#define ICS_VEC_W 4
#define ICS_VEC_FN ics_prop_rows_sse2
#include "propagate_vec.h"
const int ics_prop_built_sse2 = 1;
#else
ICS_PROP_NOT_BUILT(sse2)
#endif
