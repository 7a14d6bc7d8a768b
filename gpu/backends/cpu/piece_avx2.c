/* piece_avx2.c — a row's single-volume pieces (piece_vec.h) for AVX2: 4 lanes of doubles.
 * gpu/CMakeLists.txt compiles this file with the instruction set's flags where the compiler
 * targets it (the same as propagate_avx2.c, whose built flag says whether the path exists);
 * elsewhere it builds entry points nothing calls. */
#include "piece_batch.h"

#if defined(__x86_64__) && defined(__AVX2__) && defined(__FMA__)
#define ICS_DVEC_W 4
#define ICS_PIECE_ISA avx2
#include "piece_vec.h"
#else
ICS_PIECE_NOT_BUILT(avx2)
#endif
