/* piece_neon.c — a row's single-volume pieces (piece_vec.h) for AArch64 NEON: 2 lanes of doubles.
 * gpu/CMakeLists.txt compiles this file with the instruction set's flags where the compiler
 * targets it (the same as propagate_neon.c, whose built flag says whether the path exists);
 * elsewhere it builds entry points nothing calls. */
#include "piece_batch.h"

#if defined(__aarch64__) && defined(__ARM_NEON)
#define ICS_DVEC_W 2
#define ICS_PIECE_ISA neon
#include "piece_vec.h"
#else
ICS_PIECE_NOT_BUILT(neon)
#endif
