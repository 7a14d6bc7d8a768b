/* simd_path.h — which vector loops the CPU backend runs: the widest this processor has, or the
 * one ICS_SIMD names (auto | scalar | sse2 | avx2 | avx512 | neon), so every path can be run and
 * compared on one machine (a test, a benchmark, or a processor without AVX-512 imitated on one
 * that has it). Paths in order of preference: scalar (the portable loops) < sse2 < neon < avx2 <
 * avx512; auto takes the last this processor has. */
#ifndef ICS_RENDER_SIMD_PATH_H
#define ICS_RENDER_SIMD_PATH_H

#include <stddef.h>

#include "icshadow/status.h"

typedef enum ics_simd_path {
  ICS_SIMD_SCALAR,
  ICS_SIMD_SSE2,
  ICS_SIMD_NEON,
  ICS_SIMD_AVX2,
  ICS_SIMD_AVX512,
  ICS_SIMD_PATHS_
} ics_simd_path;

/* "scalar", "sse2", "neon", "avx2", "avx512" */
const char *ics_simd_name(ics_simd_path p);
/* 1 when this processor (and this build) can run path p */
int ics_simd_has(ics_simd_path p);
/* The path ICS_SIMD asks for ("auto", unset or empty: the widest available). An unknown name or
 * a path this processor lacks: ICS_ERR_UNSUPPORTED, with a message naming the paths it has. */
ics_status ics_simd_choose(ics_simd_path *out, char *msg, size_t msg_size);

#endif
