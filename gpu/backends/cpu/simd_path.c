/* simd_path.c — the CPU backend's vector path (simd_path.h). */
#include "simd_path.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "propagate_simd.h"

static const char *const names[ICS_SIMD_PATHS_] = {"scalar", "sse2", "neon", "avx2", "avx512"};

/* the processor's instructions (x86: cpuid through the compiler's builtins; AArch64 always has
 * NEON); this file is compiled for the baseline, so the checks themselves run anywhere */
static int cpu_has(ics_simd_path p) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  switch (p) {
  case ICS_SIMD_SSE2: return __builtin_cpu_supports("sse2");
  case ICS_SIMD_AVX2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  case ICS_SIMD_AVX512:
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("fma");
  default: return 0;
  }
#elif defined(__aarch64__)
  return p == ICS_SIMD_NEON;
#else
  (void)p;
  return 0;
#endif
}

const char *ics_simd_name(ics_simd_path p) {
  return p >= 0 && p < ICS_SIMD_PATHS_ ? names[p] : "?";
}

int ics_simd_has(ics_simd_path p) {
  switch (p) {
  case ICS_SIMD_SCALAR: return 1;
  case ICS_SIMD_SSE2: return ics_prop_built_sse2 && cpu_has(p);
  case ICS_SIMD_NEON: return ics_prop_built_neon && cpu_has(p);
  case ICS_SIMD_AVX2: return ics_prop_built_avx2 && cpu_has(p);
  case ICS_SIMD_AVX512: return ics_prop_built_avx512 && cpu_has(p);
  default: return 0;
  }
}

ics_status ics_simd_choose(ics_simd_path *out, char *msg, size_t msg_size) {
  const char *v = getenv("ICS_SIMD");
  *out = ICS_SIMD_SCALAR;
  if (!v || !*v || !strcmp(v, "auto")) {
    for (int p = ICS_SIMD_PATHS_ - 1; p > ICS_SIMD_SCALAR; p--)
      if (ics_simd_has((ics_simd_path)p)) {
        *out = (ics_simd_path)p;
        break;
      }
    return ICS_OK;
  }
  for (int p = 0; p < ICS_SIMD_PATHS_; p++)
    if (!strcmp(v, names[p]) && ics_simd_has((ics_simd_path)p)) {
      *out = (ics_simd_path)p;
      return ICS_OK;
    }
  if (msg && msg_size) {
    int known = 0;
    for (int p = 0; p < ICS_SIMD_PATHS_; p++) known |= !strcmp(v, names[p]);
    int n = snprintf(msg, msg_size, "ICS_SIMD=%.40s: %s (this processor has: auto", v,
                     known ? "this processor or build lacks that path" : "no such path");
    for (int p = 0; p < ICS_SIMD_PATHS_ && n >= 0 && (size_t)n < msg_size; p++)
      if (ics_simd_has((ics_simd_path)p)) n += snprintf(msg + n, msg_size - (size_t)n, ", %s", names[p]);
    if (n >= 0 && (size_t)n < msg_size) snprintf(msg + n, msg_size - (size_t)n, ")");
  }
  return ICS_ERR_UNSUPPORTED;
}
