/* detail_sse2.c — the volume detail functions over many points (detail_vec.h) for SSE2 (the x86-64 baseline): 2 lanes of
 * doubles, no fused multiply-adds (bit for bit core/detail.c). gpu/CMakeLists.txt compiles this
 * file with the instruction set's flags where the compiler targets it (the same as
 * propagate_sse2.c, whose built flag says whether the path exists); elsewhere it builds an entry
 * point nothing calls. */
#include "detail_batch.h"

#if defined(__x86_64__) && defined(__SSE2__)
#define ICS_DVEC_W 2
#define ICS_DVEC_FN ics_detail_batch_sse2
#include "detail_vec.h"
#else
ICS_DETAIL_NOT_BUILT(sse2)
#endif
