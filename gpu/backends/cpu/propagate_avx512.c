/* propagate_avx512.c — the vector loops of the CPU slab step (propagate_vec.h) for AVX-512
 * (F, BW, VL) with FMA: 16 lanes. Not DQ: with it the compiler takes the slow 64-bit multiply
 * (vpmullq) for Philox's 32 x 32 -> 64 bit products instead of vpmuludq.
 * gpu/CMakeLists.txt compiles this file with the instruction set's flags where the compiler
 * targets it; elsewhere it only records that the path was not built. Nothing here runs before
 * simd_path.c has found the instructions on the processor. */
#include "propagate_simd.h"

#if defined(__x86_64__) && defined(__AVX512F__) && defined(__AVX512BW__) && \
    defined(__AVX512VL__) && defined(__FMA__)
#define ICS_VEC_W 16
#define ICS_VEC_FN ics_prop_rows_avx512
#include "propagate_vec.h"
const int ics_prop_built_avx512 = 1;
#else
ICS_PROP_NOT_BUILT(avx512)
#endif
