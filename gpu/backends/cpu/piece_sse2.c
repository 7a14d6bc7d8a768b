/* piece_sse2.c — a row's single-volume pieces (piece_vec.h) for SSE2 (the x86-64 baseline):
 * 2 lanes of doubles.
 * gpu/CMakeLists.txt compiles this file with the instruction set's flags where the compiler
 * targets it (the same as propagate_sse2.c, whose built flag says whether the path exists);
 * elsewhere it builds entry points nothing calls. */
#include "piece_batch.h"

#if defined(__x86_64__) && defined(__SSE2__)
#define ICS_DVEC_W 2
#define ICS_PIECE_ISA sse2
#include "piece_vec.h"
#else
ICS_PIECE_NOT_BUILT(sse2)
#endif
