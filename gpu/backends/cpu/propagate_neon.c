/* propagate_neon.c — the vector loops of the CPU slab step (propagate_vec.h) for AArch64 Advanced SIMD (NEON, the AArch64 baseline): 4 lanes with fused multiply-add.
 * gpu/CMakeLists.txt compiles this file with the instruction set's flags where the compiler
 * targets it; elsewhere it only records that the path was not built. Nothing here runs before
 * simd_path.c has found the instructions on the processor. */
#include "propagate_simd.h"

#if defined(__aarch64__) && defined(__ARM_NEON)
#define ICS_VEC_W 4
#define ICS_VEC_FN ics_prop_rows_neon
#include "propagate_vec.h"
const int ics_prop_built_neon = 1;
#else
ICS_PROP_NOT_BUILT(neon)
#endif
