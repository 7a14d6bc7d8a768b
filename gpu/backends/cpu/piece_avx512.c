/* piece_avx512.c — a row's single-volume pieces (piece_vec.h) for AVX-512: 8 lanes of doubles.
 * gpu/CMakeLists.txt compiles this file with the instruction set's flags where the compiler
 * targets it (the same as propagate_avx512.c, whose built flag says whether the path exists);
 * elsewhere it builds entry points nothing calls. */
#include "piece_batch.h"

#if defined(__x86_64__) && defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__)
#define ICS_DVEC_W 8
#define ICS_PIECE_ISA avx512
#include "piece_vec.h"
#else
ICS_PIECE_NOT_BUILT(avx512)
#endif
