/* detail_neon.c — the volume detail functions over many points (detail_vec.h) for AArch64 NEON: 2 lanes of
 * doubles, no fused multiply-adds (bit for bit core/detail.c). gpu/CMakeLists.txt compiles this
 * file with the instruction set's flags where the compiler targets it (the same as
 * propagate_neon.c, whose built flag says whether the path exists); elsewhere it builds an entry
 * point nothing calls. */
#include "detail_batch.h"

#if defined(__aarch64__) && defined(__ARM_NEON)
#define ICS_DVEC_W 2
#define ICS_DVEC_FN ics_detail_batch_neon
#include "detail_vec.h"
#else
ICS_DETAIL_NOT_BUILT(neon)
#endif
