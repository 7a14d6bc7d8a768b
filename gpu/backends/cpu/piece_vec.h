/* piece_vec.h — a row's single-volume pieces (piece_batch.h), W at once, written once over GCC/
 * Clang vector extensions of doubles and compiled per instruction set (piece_sse2.c,
 * piece_avx2.c, piece_avx512.c, piece_neon.c define ICS_DVEC_W and ICS_PIECE_ISA). Each lane
 * repeats backend_cpu.c's single_volume_piece (its helpers arriving_light, piece_light,
 * light_colour, piece_composite, piece_attenuate, moment_add) in its order, float operations as
 * double ones rounded to float (the same result: with more than twice a float's bits plus two, a
 * double's rounding before the float's never changes a sum, difference, product or quotient;
 * Figueroa 1995), with vec_math.h's exp, expm1 and log. The buffers are read and written as
 * vectors where the W pieces are consecutive pixels (most of a row), else lane by lane, as the
 * view is. Compiled without contraction, so every path gives the same bits. */
#include "piece_batch.h"

#if !defined(ICS_DVEC_W) || !defined(ICS_PIECE_ISA)
#error "define ICS_DVEC_W and ICS_PIECE_ISA before including piece_vec.h"
#endif
#include "vec_math.h"

#define PV_CAT_(a, b) a##b
#define PV_CAT(a, b) PV_CAT_(a, b)

typedef float vf __attribute__((vector_size(4 * W)));

/* each lane rounded to float */
static inline vd to_float(vd x) {
  return __builtin_convertvector(__builtin_convertvector(x, vf), vd);
}
static inline vd gather(const float *base, vl idx) {
  vd v;
  for (int k = 0; k < W; k++) v[k] = base[idx[k]];
  return v;
}

/* the pieces' places in the light buffers: their indices, how many lanes are pieces, and
 * whether those are W consecutive pixels (a row's usual case: loaded and stored as a vector) */
typedef struct {
  vl q;
  int m, run;
} places;

static inline vd load_at(const float *base, const places *at) {
  if (!at->run) return gather(base, at->q);
  vf v;
  memcpy(&v, base + at->q[0], sizeof v);
  return __builtin_convertvector(v, vd);
}
/* v rounded to float at the pieces' places (its first m lanes) */
static inline void store_at(float *base, const places *at, vd v) {
  if (at->run) {
    vf f = __builtin_convertvector(v, vf);
    memcpy(base + at->q[0], &f, sizeof f);
    return;
  }
  for (int k = 0; k < at->m; k++) base[at->q[k]] = (float)v[k];
}
static inline vl gather_index(const int64_t *p, int i, int n) {
  vl v;
  for (int k = 0; k < W; k++) v[k] = p[i + k < n ? i + k : n - 1];
  return v;
}
static inline vd gather_value(const double *p, int i, int n) {
  vd v;
  for (int k = 0; k < W; k++) v[k] = p[i + k < n ? i + k : n - 1];
  return v;
}

/* light l's first-set light at the pieces (q: their buffer indices), channel c: render.model
 * blocker blends it with the sharp set's (arriving_light) */
static void arriving(const ics_piece_params *pp, int l, const places *at, vd out[3]) {
  int nch = pp->nch, nl = pp->nlights;
  for (int c = 0; c < nch; c++) out[c] = load_at(pp->dst[l] + (size_t)c * pp->plane, at);
  if (!pp->blend) return;
  vd occ = splat(0);
  for (int c = 0; c < nch; c++) occ += to_float(1 - out[c]);
  occ /= nch;
  vl some = occ > 1e-4; /* no blocker elsewhere: the sets agree */
  if (!any(some)) return;
  vd mom = load_at(pp->dst[(pp->sharp_set + 1) * nl + l], at);
  vd zb = pp->z0 + mom / blend(some, occ, splat(1)) * pp->K * pp->e, d = pp->z_light - zb;
  vl lo = d <= pp->d_sharp, hi = d >= pp->d1; /* (neither where d is NaN: t NaN, as in C) */
  vd t = vlog(blend(lo | hi, splat(1), d / pp->d_sharp)) / pp->blend_span;
  t = blend(lo, splat(0), blend(hi, splat(1), t));
  for (int c = 0; c < nch; c++) {
    vd sh = load_at(pp->dst[pp->sharp_set * nl + l] + (size_t)c * pp->plane, at);
    out[c] = blend(some, to_float(sh + t * to_float(out[c] - sh)), out[c]);
  }
}

/* the light on the pieces per colour channel (piece_light's own term, or light_colour) */
static void light(const ics_piece_params *pp, const places *at, vd sig, vd dl, const vd keep[3],
                  vd L[3]) {
  vd a = sig * dl, plain = -vexpm1(-a * pp->dz) / a, bc[3];
  for (int c = 0; c < pp->nch; c++) bc[c] = sig * keep[c];
  L[0] = L[1] = L[2] = splat(0);
  for (int l = 0; l < pp->nlights; l++) {
    vd F[3];
    arriving(pp, l, at, F);
    for (int c = 0; c < 3; c++) {
      int ch = pp->nch == 3 ? c : 0;
      if (pp->own) {
        vd b = bc[ch] * pp->lpath[l];
        L[c] += pp->lcw[l][c] * F[ch] * (-vexpm1(-(a + b) * pp->dz) / (a + b)) / plain;
      } else {
        L[c] += pp->lcw[l][c] * F[ch];
      }
    }
  }
}

/* the pieces' colour composited under their view pixels (lit: in view, not yet opaque) */
static void composite(const ics_piece_params *pp, vl view, vl lit, vd sig, vd dl,
                      const vd col[3], const vd L[3], int m) {
  vl px = (view * 4) & lit; /* (a lane not lit reads pixel 0 and writes nothing) */
  vd alpha = 1 - vexp(-sig * pp->dz * dl), a3 = gather(pp->img + 3, px);
  vd wgt = to_float(1 - a3) * alpha;
  for (int k = 0; k < m; k++) {
    if (!lit[k]) continue;
    float *C = pp->img + px[k];
    for (int c = 0; c < 3; c++) C[c] += (float)(wgt[k] * ((sig[k] * col[c][k]) / sig[k]) * L[c][k]);
    C[3] += (float)wgt[k];
  }
}

/* render.model blocker: light l's first set's mean over its channels at the pieces */
static vd first_mean(const ics_piece_params *pp, int l, const places *at) {
  vd v = splat(0);
  for (int c = 0; c < pp->nch; c++) v += load_at(pp->dst[l] + (size_t)c * pp->plane, at);
  return v / pp->nch;
}

/* every buffer the pieces occlude, attenuated (piece_attenuate) */
static void attenuate(const ics_piece_params *pp, const places *at, vd sig, const vd keep[3]) {
  int nl = pp->nlights;
  for (int l = 0; l < nl; l++) {
    vd pass[3];
    for (int c = 0; c < pp->nch; c++) pass[c] = vexp(-sig * pp->dz * pp->lpath[l] * keep[c]);
    vd v0 = pp->moment ? first_mean(pp, l, at) : splat(0);
    for (int b = l; b < pp->nb; b += nl)
      if (pp->attenuates[b])
        for (int c = 0; c < pp->nch; c++) {
          float *base = pp->dst[b] + (size_t)c * pp->plane;
          store_at(base, at, load_at(base, at) * to_float(pass[c]));
        }
    if (!pp->moment) continue;
    vd gain = to_float((v0 - first_mean(pp, l, at)) * (pp->z_moment - pp->z0) / (pp->K * pp->e));
    for (int b = l; b < pp->nb; b += nl)
      if (pp->is_moment[b]) store_at(pp->dst[b], at, load_at(pp->dst[b], at) + gain);
  }
}

void PV_CAT(ics_piece_batch_, ICS_PIECE_ISA)(const ics_piece_params *pp, const ics_piece_row *r) {
  for (int i = 0; i < r->n; i += W) {
    places at = {gather_index(r->q, i, r->n), r->n - i < W ? r->n - i : W, 0};
    at.run = at.m == W && at.q[W - 1] - at.q[0] == W - 1; /* (the indices only increase) */
    vl view = gather_index(r->view, i, r->n); /* lanes beyond repeat the last piece, not stored */
    vd sig = gather_value(r->sig, i, r->n), dl = gather_value(r->dl, i, r->n), col[3], keep[3];
    for (int c = 0; c < 3; c++)
      col[c] = gather_value(r->col[c], i, r->n), keep[c] = gather_value(r->keep[c], i, r->n);
    vl in = view >= 0;
    vd a3 = gather(pp->img + 3, (view * 4) & in);
    vl lit = in & (a3 < 1);
    if (any(lit)) {
      vd L[3];
      light(pp, &at, sig, dl, keep, L);
      composite(pp, view, lit, sig, dl, col, L, at.m);
    }
    attenuate(pp, &at, sig, keep);
  }
}

void PV_CAT(ics_vec_math_, ICS_PIECE_ISA)(int fn, const double *x, int n, double *out) {
  for (int i = 0; i < n; i += W) {
    vd v = gather_value(x, i, n), y = fn == 0 ? vexp(v) : fn == 1 ? vexpm1(v) : vlog(v);
    for (int k = 0; k < W && i + k < n; k++) out[i + k] = y[k];
  }
}

#undef W
