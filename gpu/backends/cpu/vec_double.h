/* vec_double.h — vectors of W doubles (GCC/Clang vector extensions) for the cpu backend's
 * double-precision batches (detail_vec.h, piece_vec.h): the types and the few helpers they
 * share. The including file defines ICS_DVEC_W, the lanes (1 for the portable build, 2 for SSE2
 * and NEON, 4 for AVX2, 8 for AVX-512), and is compiled for its instruction set. */
#ifndef ICS_RENDER_VEC_DOUBLE_H
#define ICS_RENDER_VEC_DOUBLE_H

#include <stdint.h>
#include <string.h>

#ifndef ICS_DVEC_W
#error "define ICS_DVEC_W before including vec_double.h"
#endif

#define W ICS_DVEC_W
typedef double vd __attribute__((vector_size(8 * W)));
typedef int64_t vl __attribute__((vector_size(8 * W)));

static inline vd splat(double v) { return (vd){0} + v; }
/* a where mask (all ones), else b */
static inline vd blend(vl mask, vd a, vd b) { return (vd)(((vl)a & mask) | ((vl)b & ~mask)); }
static inline vd vfabs(vd x) { return (vd)((vl)x & ((vl){0} + INT64_MAX)); }
static inline vd load(const double *p) {
  vd v;
  memcpy(&v, p, sizeof v);
  return v;
}
static inline void store(double *p, vd v) { memcpy(p, &v, sizeof v); }
/* 1 when some lane of mask is set */
static inline int any(vl mask) {
  int64_t a = 0;
  for (int k = 0; k < W; k++) a |= mask[k];
  return a != 0;
}

#endif
