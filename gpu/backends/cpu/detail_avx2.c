/* detail_avx2.c — the volume detail functions over many points (detail_vec.h) for AVX2: 4 lanes of
 * doubles, no fused multiply-adds (bit for bit core/detail.c). gpu/CMakeLists.txt compiles this
 * file with the instruction set's flags where the compiler targets it (the same as
 * propagate_avx2.c, whose built flag says whether the path exists); elsewhere it builds an entry
 * point nothing calls. */
#include "detail_batch.h"

#if defined(__x86_64__) && defined(__AVX2__) && defined(__FMA__)
#define ICS_DVEC_W 4
#define ICS_DVEC_FN ics_detail_batch_avx2
#include "detail_vec.h"
#else
ICS_DETAIL_NOT_BUILT(avx2)
#endif
