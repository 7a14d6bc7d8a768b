/* stability_sweep.c — stability sweep of libicshadow's exact functions over their whole domains.
 *
 * For every function of `icshadow eval` (ellipk, ellipe, ellipk_m1, ellipe_m1, varx, vx, vy,
 * ratio, ratio_to_t), plus ics_ellint_ke_m1 (K and E in one call; its error is the larger of the
 * two), and every region of its domain — the extremes (subnormal, near 1, huge, negative) and
 * both sides of every algorithm switch listed in docs/ellint.md ("Switch points") and
 * docs/ellipse.md — it draws deterministic random inputs, measures the maximum error in ulps
 * against the 320-bit MPFR references of tests/ref_mpfr.c, and times the function on the same
 * inputs (ns per call, minimum over repetitions). Writes CSV to stdout:
 *   function,region,lo,hi,samples,max_ulp,worst_input,ns_per_call
 * (lo, hi: the region's bounds; for the switch regions, the smallest and largest input drawn).
 *
 * Switch regions of K and E ("just below / above", EDGE draws): the switch is a comparison of a
 * switch variable v(a) of the argument a with an edge e — v = m1, or x = 1 - m, or m1h = 1 - m
 * rounded, or x' = 1/m1 as ellint.c forms them in double. The sweep finds the two adjacent
 * doubles a on either side of the switch exactly (by evaluating v as the library does), then
 * steps 0 ... 2^22 ulps away from it on the requested side (the offset log-uniform, so the
 * arguments next to the switch are drawn often), staying within |v(a) - e| <= 2^-30 |e|.
 * Edge sets: one edge, or a random one of the 55 piece boundaries x = 2^-j (1 + i/8) in
 * (1/128, 1), or a random one of the 128 interval ends of the inline logarithm's table
 * (bit patterns LOG_OFF + i 2^45 scaled by 2^k, k random in the region's range; for subnormal
 * m1 the ends of the rescaled significand). The switch points come from ellint_data.h
 * (ICS_ELLINT_X0, ICS_ELLINT_S, ICS_ELLINT_LOG_*), so the sweep follows the tables.
 *
 * Each region draws from its own generator, seeded from its function and label, so adding or
 * changing a region does not move the inputs of the others.
 * Usage: stability_sweep [--samples N] [--progress]   (default N = 2000 per region).
 * The documented bounds (0.60 ulp K/E, 0.75 varx/vx/vy, 1.0 ratio/ratio_to_t) are what
 * tests/test_ellint.c and tests/test_ellipse.c assert; this program reports, it does not assert. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <mpfr.h>

#include "ellint_data.h" /* switch points: ICS_ELLINT_X0(_LOG2), ICS_ELLINT_S, ICS_ELLINT_LOG_* */
#include "icshadow.h"
#include "ref_mpfr.h"

typedef enum { F_K, F_E, F_K1, F_E1, F_KE1, F_VARX, F_VX, F_VY, F_RATIO, F_RATIO_TO_T } func_id;

/* ics_ellint_ke_m1 as a function of one argument, for the timing loop (K + E) */
static double ellipke_m1_sum(double m1) {
  double k, e;
  ics_ellint_ke_m1(m1, &k, &e);
  return k + e;
}

static const struct {
  const char *name;
  double (*f)(double);
} funcs[] = {
    [F_K] = {"ellipk", ics_ellint_k},          [F_E] = {"ellipe", ics_ellint_e},
    [F_K1] = {"ellipk_m1", ics_ellint_k_m1},   [F_E1] = {"ellipe_m1", ics_ellint_e_m1},
    [F_KE1] = {"ellipke_m1", ellipke_m1_sum},
    [F_VARX] = {"varx", ics_ellipse_varx},   [F_VX] = {"vx", ics_ellipse_vx},
    [F_VY] = {"vy", ics_ellipse_vy},         [F_RATIO] = {"ratio", ics_ellipse_ratio},
    [F_RATIO_TO_T] = {"ratio_to_t", ics_ellipse_ratio_to_t},
};

/* how inputs are drawn in [lo, hi]: uniform, log-uniform, 1 - log-uniform(lo, hi),
 * -log-uniform(lo, hi), or next to a switch (EDGE, see the header) */
typedef enum { LIN, LOG, ONE_MINUS_LOG, NEG_LOG, EDGE } draw_kind;

/* EDGE regions: which edges, the switch variable, and the side */
typedef enum { ES_NONE, ES_ONE, ES_PIECES, ES_LOGTAB } edge_set;
typedef enum {
  SV_ID,              /* v = a  (m1 entry: x = m1; transformed route: m1h = m1) */
  SV_ID_SUB,          /* v = a 2^128 (exact for subnormal a: the log table's rescaled ends) */
  SV_ONE_MINUS,       /* v = 1 - a in double (m entry: x = 1 - m, or m1h = 1 - m) */
  SV_RECIP,           /* v = 1/a in double (transformed route: x' = q = 1/m1) */
  SV_RECIP_ONE_MINUS, /* v = 1/(1 - a) in double (m entry, transformed route: q) */
} sv_kind;
typedef enum { LO_SIDE, HI_SIDE } side_kind; /* v < e (v <= e if strict) / v >= e (v > e) */

typedef struct {
  func_id f;
  const char *region;
  double lo, hi; /* bounds; ES_ONE: lo = e; ES_LOGTAB: exponent range of the edges */
  draw_kind draw;
  edge_set set;
  sv_kind sv;
  side_kind side;
  int strict; /* the switch is v > e (the high side excludes e) rather than v >= e */
} region;

#define RG(f, name, lo, hi, d) {f, name, lo, hi, d, ES_NONE, SV_ID, LO_SIDE, 0}
#define EDGE1(f, name, sv, e, strict, side) {f, name, e, e, EDGE, ES_ONE, sv, side, strict}
#define EDGES(f, name, set, sv, klo, khi, side) {f, name, klo, khi, EDGE, set, sv, side, 0}

#define X0 ICS_ELLINT_X0 /* log series below x = X0, pieces above (1/128) */

/* K or E through the parameter m; the switch variable is x = 1 - m (m >= 0) or m1h = 1 - m
 * rounded (m < 0), as in ellint.c */
#define M_ENTRY(F)                                                                                 \
  RG(F, "1-m log-uniform [2^-53, 1/128) (log series)", 0x1p-53, X0, ONE_MINUS_LOG),               \
  EDGES(F, "1-m just below a log table interval end (log series)", ES_LOGTAB, SV_ONE_MINUS, -51, -8, LO_SIDE), \
  EDGES(F, "1-m at/just above a log table interval end (log series)", ES_LOGTAB, SV_ONE_MINUS, -51, -8, HI_SIDE), \
  EDGE1(F, "m just above 127/128 (1-m < 1/128: log series)", SV_ONE_MINUS, X0, 0, LO_SIDE),        \
  EDGE1(F, "m at/just below 127/128 (1-m >= 1/128: pieces)", SV_ONE_MINUS, X0, 0, HI_SIDE),        \
  RG(F, "m in [0, 127/128] (pieces)", 0.0, 1 - X0, LIN),                                         \
  EDGES(F, "1-m just below a piece boundary 2^-j(1+i/8)", ES_PIECES, SV_ONE_MINUS, 0, 0, LO_SIDE), \
  EDGES(F, "1-m at/just above a piece boundary 2^-j(1+i/8)", ES_PIECES, SV_ONE_MINUS, 0, 0, HI_SIDE), \
  EDGE1(F, "m just above 31/32 (old log/pieces switch; now a piece boundary)", SV_ONE_MINUS, 0x1p-5, 0, LO_SIDE), \
  EDGE1(F, "m at/just below 31/32 (old log/pieces switch; now a piece boundary)", SV_ONE_MINUS, 0x1p-5, 0, HI_SIDE), \
  RG(F, "m in [0, 2^-30] (at/just above m = 0: direct)", 0.0, 0x1p-30, LIN),                     \
  RG(F, "m in [-2^-30, 0) (just below m = 0: transform below -2^-60)", -0x1p-30, 0.0, LIN),       \
  EDGE1(F, "m at/just below -2^-60 (transform)", SV_ID, -0x1p-60, 1, LO_SIDE),                      \
  EDGE1(F, "m just above -2^-60 (tiny m < 0: direct, x = 1)", SV_ID, -0x1p-60, 1, HI_SIDE),         \
  RG(F, "m in (-2^-60, 0) log-uniform (tiny m < 0: direct)", 0x1p-1074, 0x1p-60, NEG_LOG),          \
  RG(F, "m in (-127, 0) (transform, pieces)", -(1 / X0 - 1), 0.0, LIN),                          \
  EDGES(F, "1/(1-m) just below a piece boundary (transform, pieces)", ES_PIECES, SV_RECIP_ONE_MINUS, 0, 0, LO_SIDE), \
  EDGES(F, "1/(1-m) at/just above a piece boundary (transform, pieces)", ES_PIECES, SV_RECIP_ONE_MINUS, 0, 0, HI_SIDE), \
  EDGE1(F, "m just below -31 (old switch m1 = 32; now a transformed piece boundary)", SV_RECIP_ONE_MINUS, 0x1p-5, 0, LO_SIDE), \
  EDGE1(F, "m at/just above -31 (old switch m1 = 32; now a transformed piece boundary)", SV_RECIP_ONE_MINUS, 0x1p-5, 0, HI_SIDE), \
  EDGE1(F, "m at/just above -127 (1-m <= 128: transform, pieces)", SV_ONE_MINUS, 1 / X0, 1, LO_SIDE), \
  EDGE1(F, "m just below -127 (1-m > 128: transform, log)", SV_ONE_MINUS, 1 / X0, 1, HI_SIDE),    \
  RG(F, "m in [-2^512, -127) (transform, log)", 1 / X0 - 1, 0x1p512, NEG_LOG),                    \
  EDGES(F, "1-m just below a log table interval end (transform, log)", ES_LOGTAB, SV_ONE_MINUS, 8, 1023, LO_SIDE), \
  EDGES(F, "1-m at/just above a log table interval end (transform, log)", ES_LOGTAB, SV_ONE_MINUS, 8, 1023, HI_SIDE), \
  EDGE1(F, "m just above 1-2^64 (x' > 2^-64: polynomials in x')", SV_RECIP_ONE_MINUS, 0x1p-64, 1, HI_SIDE), \
  EDGE1(F, "m at/just below 1-2^64 (x' <= 2^-64: polynomials at 0)", SV_RECIP_ONE_MINUS, 0x1p-64, 1, LO_SIDE), \
  EDGE1(F, "m at/just above -2^512 (1-m <= 2^512: unscaled)", SV_ONE_MINUS, 0x1p512, 1, LO_SIDE),   \
  EDGE1(F, "m just below -2^512 (1-m > 2^512: scaled)", SV_ONE_MINUS, 0x1p512, 1, HI_SIDE),       \
  RG(F, "m < -2^512 (scaled transform)", 0x1p512, DBL_MAX, NEG_LOG)

/* K or E through m1; the switch variable is m1 itself, or x' = 1/m1 (transformed pieces and
 * the polynomial clamp on x') */
#define M1_ENTRY(F)                                                                                \
  RG(F, "m1 subnormal (log series, rescaled)", 0x1p-1074, 0x1p-1022, LOG),                        \
  EDGES(F, "m1 subnormal, just below a log table interval end", ES_LOGTAB, SV_ID_SUB, -1072, -1023, LO_SIDE), \
  EDGES(F, "m1 subnormal, at/just above a log table interval end", ES_LOGTAB, SV_ID_SUB, -1072, -1023, HI_SIDE), \
  EDGE1(F, "m1 just below 2^-1022 (subnormal: rescaled)", SV_ID, 0x1p-1022, 0, LO_SIDE),          \
  EDGE1(F, "m1 at/just above 2^-1022 (normal)", SV_ID, 0x1p-1022, 0, HI_SIDE),                     \
  EDGE1(F, "m1 just below 2^-1019 (outer factor x dropped)", SV_ID, 0x1p-1019, 0, LO_SIDE),       \
  EDGE1(F, "m1 at/just above 2^-1019 (outer factor x kept)", SV_ID, 0x1p-1019, 0, HI_SIDE),       \
  RG(F, "m1 in [2^-1022, 2^-64] (log series, polynomials at 0)", 0x1p-1022, 0x1p-64, LOG),        \
  EDGE1(F, "m1 at/just below 2^-64 (polynomials at 0)", SV_ID, 0x1p-64, 1, LO_SIDE),              \
  EDGE1(F, "m1 just above 2^-64 (polynomials in x)", SV_ID, 0x1p-64, 1, HI_SIDE),                 \
  RG(F, "m1 in (2^-64, 1/128) (log series)", 0x1p-64, X0, LOG),                                   \
  EDGES(F, "m1 just below a log table interval end (log series)", ES_LOGTAB, SV_ID, -1021, -8, LO_SIDE), \
  EDGES(F, "m1 at/just above a log table interval end (log series)", ES_LOGTAB, SV_ID, -1021, -8, HI_SIDE), \
  EDGE1(F, "m1 just below 1/128 (log series)", SV_ID, X0, 0, LO_SIDE),                             \
  EDGE1(F, "m1 at/just above 1/128 (pieces)", SV_ID, X0, 0, HI_SIDE),                              \
  RG(F, "m1 in [1/128, 1] (pieces)", X0, 1.0, LOG),                                               \
  EDGES(F, "m1 just below a piece boundary 2^-j(1+i/8)", ES_PIECES, SV_ID, 0, 0, LO_SIDE),        \
  EDGES(F, "m1 at/just above a piece boundary 2^-j(1+i/8)", ES_PIECES, SV_ID, 0, 0, HI_SIDE),     \
  EDGE1(F, "m1 just below 1/32 (old log/pieces switch; now a piece boundary)", SV_ID, 0x1p-5, 0, LO_SIDE), \
  EDGE1(F, "m1 at/just above 1/32 (old log/pieces switch; now a piece boundary)", SV_ID, 0x1p-5, 0, HI_SIDE), \
  EDGE1(F, "m1 at/just below 1 (m >= 0: direct)", SV_ID, 1.0, 1, LO_SIDE),                         \
  EDGE1(F, "m1 just above 1 (m < 0: transform)", SV_ID, 1.0, 1, HI_SIDE),                          \
  RG(F, "m1 in (1, 128] (transform, pieces)", 1.0, 1 / X0, LOG),                                  \
  EDGES(F, "1/m1 just below a piece boundary (transform, pieces)", ES_PIECES, SV_RECIP, 0, 0, LO_SIDE), \
  EDGES(F, "1/m1 at/just above a piece boundary (transform, pieces)", ES_PIECES, SV_RECIP, 0, 0, HI_SIDE), \
  EDGE1(F, "m1 just above 32 (old switch; now a transformed piece boundary)", SV_RECIP, 0x1p-5, 0, LO_SIDE), \
  EDGE1(F, "m1 at/just below 32 (old switch; now a transformed piece boundary)", SV_RECIP, 0x1p-5, 0, HI_SIDE), \
  EDGE1(F, "m1 at/just below 128 (transform, pieces)", SV_ID, 1 / X0, 1, LO_SIDE),                 \
  EDGE1(F, "m1 just above 128 (transform, log)", SV_ID, 1 / X0, 1, HI_SIDE),                       \
  RG(F, "m1 in (128, 2^512] (transform, log)", 1 / X0, 0x1p512, LOG),                             \
  EDGES(F, "m1 just below a log table interval end (transform, log)", ES_LOGTAB, SV_ID, 8, 1023, LO_SIDE), \
  EDGES(F, "m1 at/just above a log table interval end (transform, log)", ES_LOGTAB, SV_ID, 8, 1023, HI_SIDE), \
  EDGE1(F, "m1 just below 2^64 (x' > 2^-64: polynomials in x')", SV_RECIP, 0x1p-64, 1, HI_SIDE),   \
  EDGE1(F, "m1 at/just above 2^64 (x' <= 2^-64: polynomials at 0)", SV_RECIP, 0x1p-64, 1, LO_SIDE), \
  EDGE1(F, "m1 at/just below 2^512 (unscaled)", SV_ID, 0x1p512, 1, LO_SIDE),                       \
  EDGE1(F, "m1 just above 2^512 (scaled)", SV_ID, 0x1p512, 1, HI_SIDE),                            \
  RG(F, "m1 > 2^512 (scaled transform)", 0x1p512, DBL_MAX, LOG)

static const region regions[] = {
    M_ENTRY(F_K),
    M_ENTRY(F_E),
    M1_ENTRY(F_K1),
    M1_ENTRY(F_E1),
    /* K and E in one call: every route and both sides of the route switches */
    RG(F_KE1, "m1 subnormal (log series, rescaled)", 0x1p-1074, 0x1p-1022, LOG),
    RG(F_KE1, "m1 in [2^-1022, 1/128) (log series)", 0x1p-1022, X0, LOG),
    EDGES(F_KE1, "m1 just below a log table interval end (log series)", ES_LOGTAB, SV_ID, -1021, -8, LO_SIDE),
    EDGES(F_KE1, "m1 at/just above a log table interval end (log series)", ES_LOGTAB, SV_ID, -1021, -8, HI_SIDE),
    EDGE1(F_KE1, "m1 just below 1/128 (log series)", SV_ID, X0, 0, LO_SIDE),
    EDGE1(F_KE1, "m1 at/just above 1/128 (pieces)", SV_ID, X0, 0, HI_SIDE),
    RG(F_KE1, "m1 in [1/128, 1] (pieces)", X0, 1.0, LOG),
    EDGES(F_KE1, "m1 just below a piece boundary 2^-j(1+i/8)", ES_PIECES, SV_ID, 0, 0, LO_SIDE),
    EDGES(F_KE1, "m1 at/just above a piece boundary 2^-j(1+i/8)", ES_PIECES, SV_ID, 0, 0, HI_SIDE),
    EDGE1(F_KE1, "m1 at/just below 1 (m >= 0: direct)", SV_ID, 1.0, 1, LO_SIDE),
    EDGE1(F_KE1, "m1 just above 1 (m < 0: transform)", SV_ID, 1.0, 1, HI_SIDE),
    RG(F_KE1, "m1 in (1, 128] (transform, pieces)", 1.0, 1 / X0, LOG),
    EDGES(F_KE1, "1/m1 just below a piece boundary (transform, pieces)", ES_PIECES, SV_RECIP, 0, 0, LO_SIDE),
    EDGES(F_KE1, "1/m1 at/just above a piece boundary (transform, pieces)", ES_PIECES, SV_RECIP, 0, 0, HI_SIDE),
    EDGE1(F_KE1, "m1 at/just below 128 (transform, pieces)", SV_ID, 1 / X0, 1, LO_SIDE),
    EDGE1(F_KE1, "m1 just above 128 (transform, log)", SV_ID, 1 / X0, 1, HI_SIDE),
    RG(F_KE1, "m1 in (128, 2^512] (transform, log)", 1 / X0, 0x1p512, LOG),
    EDGE1(F_KE1, "m1 at/just below 2^512 (unscaled)", SV_ID, 0x1p512, 1, LO_SIDE),
    EDGE1(F_KE1, "m1 just above 2^512 (scaled)", SV_ID, 0x1p512, 1, HI_SIDE),
    RG(F_KE1, "m1 > 2^512 (scaled transform)", 0x1p512, DBL_MAX, LOG),
    /* ellipse variance functions */
    RG(F_VARX, "b log-uniform [1e-300, 0.0757) (thin, T formula 2)", 1e-300, 0.0757, LOG),
    RG(F_VARX, "b around 0.0757 (p = 1/4 switch)", 0.0757 * (1 - 1e-3), 0.0757 * (1 + 1e-3), LIN),
    RG(F_VARX, "b in [0.0757, 1)", 0.0757, 1.0, LIN),
    RG(F_VARX, "b = 1 - 2^-k (k up to 53)", 0x1p-53, 0.5, ONE_MINUS_LOG),
    RG(F_VARX, "just below b = 1", (1.0) * (1 - 0x1p-30), 1.0, LIN),
    RG(F_VARX, "just above b = 1", 1.0, (1.0) * (1 + 0x1p-30), LIN),
    RG(F_VARX, "b in (1, 2^500)", 1.0, 0x1p500, LOG),
    RG(F_VARX, "b >= 2^500", 0x1p500, DBL_MAX, LOG),
    RG(F_VX, "t log-uniform [1e-300, 2^-480) (scaled square)", 1e-300, 0x1p-480, LOG),
    RG(F_VX, "t in [2^-480, 0.0703) log-uniform", 0x1p-480, 0.0703, LOG),
    RG(F_VX, "t in [0.0703, 1/2)", 0.0703, 0.5, LIN),
    RG(F_VX, "just below / above t = 1/2", 0.5 * (1 - 0x1p-30), 0.5 * (1 + 0x1p-30), LIN),
    RG(F_VX, "t in (1/2, 1)", 0.5, 1.0, LIN),
    RG(F_VX, "t = 1 - log-uniform [2^-53, 1/2)", 0x1p-53, 0.5, ONE_MINUS_LOG),
    RG(F_VY, "t log-uniform [1e-300, 2^-480) (scaled square)", 1e-300, 0x1p-480, LOG),
    RG(F_VY, "just below / above t = 2^-480", 0x1p-480 * (1 - 0x1p-30), 0x1p-480 * (1 + 0x1p-30), LIN),
    RG(F_VY, "t in [2^-480, 1/2) log-uniform", 0x1p-480, 0.5, LOG),
    RG(F_VY, "t in (1/2, 1)", 0.5, 1.0, LIN),
    RG(F_VY, "t = 1 - log-uniform [2^-53, 1/2)", 0x1p-53, 0.5, ONE_MINUS_LOG),
    RG(F_RATIO, "t log-uniform [1e-300, 2^-480)", 1e-300, 0x1p-480, LOG),
    RG(F_RATIO, "t in [2^-480, 1/2) log-uniform", 0x1p-480, 0.5, LOG),
    RG(F_RATIO, "t around 0.0703 (p = 1/4 switch)", 0.0703 * (1 - 1e-3), 0.0703 * (1 + 1e-3), LIN),
    RG(F_RATIO, "just below / above t = 1/2", 0.5 * (1 - 0x1p-30), 0.5 * (1 + 0x1p-30), LIN),
    RG(F_RATIO, "t in (1/2, 1)", 0.5, 1.0, LIN),
    RG(F_RATIO, "t = 1 - log-uniform [2^-53, 1/2)", 0x1p-53, 0.5, ONE_MINUS_LOG),
    RG(F_RATIO_TO_T, "r log-uniform [1e-300, 2^-600) (asymptotic)", 1e-300, 0x1p-600, LOG),
    RG(F_RATIO_TO_T, "just below / above r = 2^-600", 0x1p-600 * (1 - 0x1p-30), 0x1p-600 * (1 + 0x1p-30), LIN),
    RG(F_RATIO_TO_T, "r in [2^-600, 1e-4) log-uniform", 0x1p-600, 1e-4, LOG),
    RG(F_RATIO_TO_T, "r in [1e-4, 1) log-uniform", 1e-4, 1.0, LOG),
    RG(F_RATIO_TO_T, "just below / above r = 1", 1.0 * (1 - 0x1p-30), 1.0 * (1 + 0x1p-30), LIN),
    RG(F_RATIO_TO_T, "r in (1, 1e4] log-uniform", 1.0, 1e4, LOG),
    RG(F_RATIO_TO_T, "r in (1e4, 2^600] log-uniform", 1e4, 0x1p600, LOG),
    RG(F_RATIO_TO_T, "r > 2^600 (asymptotic)", 0x1p600, 1e300, LOG),
};

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static double urand(void) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (double)(rng >> 11) * 0x1p-53;
}

static int irand(int n) { /* 0 .. n-1 */
  int i = (int)(urand() * n);
  return i < n ? i : n - 1;
}

/* a region's own generator: FNV-1a of function and label (never 0, as xorshift needs) */
static void seed_region(const region *r) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const char *p = funcs[r->f].name; *p; p++) h = (h ^ (unsigned char)*p) * 0x100000001b3ull;
  for (const char *p = r->region; *p; p++) h = (h ^ (unsigned char)*p) * 0x100000001b3ull;
  rng = h ? h : 1;
}

static uint64_t as_u64(double x) {
  uint64_t u;
  memcpy(&u, &x, sizeof u);
  return u;
}

static double as_f64(uint64_t u) {
  double x;
  memcpy(&x, &u, sizeof x);
  return x;
}

/* a moved by n ulps towards +inf (a != 0; the switch points are far from 0) */
static double step_ulps(double a, int64_t n) {
  uint64_t u = as_u64(a);
  return as_f64(a > 0 ? u + (uint64_t)n : u - (uint64_t)n);
}

/* the switch variable as ellint.c forms it in double */
static double sv_of(sv_kind k, double a) {
  switch (k) {
  case SV_ID: return a;
  case SV_ID_SUB: return a * 0x1p128;
  case SV_ONE_MINUS: return 1.0 - a;
  case SV_RECIP: return 1.0 / a;
  case SV_RECIP_ONE_MINUS: return 1.0 / (1.0 - a);
  }
  return NAN;
}

static int sv_dir(sv_kind k) { /* +1: v increases with a */
  return k == SV_ONE_MINUS || k == SV_RECIP ? -1 : 1;
}

static double sv_guess(sv_kind k, double e) { /* an argument near v = e */
  switch (k) {
  case SV_ID: return e;
  case SV_ID_SUB: return e * 0x1p-128;
  case SV_ONE_MINUS: return 1.0 - e;
  case SV_RECIP: return 1.0 / e;
  case SV_RECIP_ONE_MINUS: return 1.0 - 1.0 / e;
  }
  return NAN;
}

/* the piece boundaries x = 2^-j (1 + i/2^S) strictly inside (X0, 1) */
#define NBOUND ((-ICS_ELLINT_X0_LOG2) * (1 << ICS_ELLINT_S) - 1)
static double piece_bound(int b) {
  b += 1; /* skip x = X0 itself (a switch of its own) */
  int j = -ICS_ELLINT_X0_LOG2 - b / (1 << ICS_ELLINT_S), i = b % (1 << ICS_ELLINT_S);
  return ldexp(1.0 + (double)i / (1 << ICS_ELLINT_S), -j);
}

static double edge_of(const region *r) {
  switch (r->set) {
  case ES_PIECES: return piece_bound(irand(NBOUND));
  case ES_LOGTAB: {
    uint64_t i = (uint64_t)irand(ICS_ELLINT_LOG_N);
    double z = as_f64(ICS_ELLINT_LOG_OFF + (i << (52 - ICS_ELLINT_LOG_B))); /* [sqrt(1/2), sqrt(2)) */
    int k = (int)r->lo + irand((int)(r->hi - r->lo) + 1);
    return ldexp(z, k + (r->sv == SV_ID_SUB ? 128 : 0));
  }
  case ES_ONE:
  case ES_NONE: break;
  }
  return r->lo;
}

static int high_side(const region *r, double a, double e) {
  double v = sv_of(r->sv, a);
  return r->strict ? v > e : v >= e;
}

/* an argument on the region's side of a switch: see the header */
static double draw_edge(const region *r) {
  double e = edge_of(r);
  int dir = sv_dir(r->sv), n = 0;
  double g = sv_guess(r->sv, e);
  while (high_side(r, g, e) && n++ < 4096) g = step_ulps(g, -dir);
  while (!high_side(r, step_ulps(g, dir), e) && n++ < 4096) g = step_ulps(g, dir);
  if (n >= 4096 || high_side(r, g, e)) {
    fprintf(stderr, "stability_sweep: no switch found for %s \"%s\" at %a\n", funcs[r->f].name,
            r->region, e);
    exit(1);
  }
  /* g: the last argument on the low side; step_ulps(g, dir): the first on the high side */
  int64_t k = (int64_t)exp2(22.0 * urand()) - 1; /* 0 .. 2^22 - 2 ulps further */
  for (;;) {
    double a = r->side == LO_SIDE ? step_ulps(g, -dir * k) : step_ulps(g, dir * (k + 1));
    if (k == 0 || fabs(sv_of(r->sv, a) - e) <= 0x1p-30 * fabs(e)) return a;
    k /= 2;
  }
}

static double draw(const region *r) {
  double u = urand();
  switch (r->draw) {
  case LIN: return r->lo + u * (r->hi - r->lo);
  case LOG: return exp(log(r->lo) + u * (log(r->hi) - log(r->lo)));
  case ONE_MINUS_LOG: return 1.0 - exp(log(r->lo) + u * (log(r->hi) - log(r->lo)));
  case NEG_LOG: return -exp(log(r->lo) + u * (log(r->hi) - log(r->lo)));
  case EDGE: return draw_edge(r);
  }
  return NAN;
}

/* the MPFR reference of function f at the double x */
static void reference(func_id f, double x, double got, mpfr_ptr out) {
  mpfr_t a;
  mpfr_init2(a, REF_PREC + 64);
  mpfr_set_d(a, x, MPFR_RNDN);
  switch (f) {
  case F_K:
  case F_E:
    mpfr_ui_sub(a, 1, a, MPFR_RNDN); /* m1 = 1 - m, exact at this precision */
    /* fall through */
  case F_K1:
  case F_E1:
  case F_KE1: /* K here; main() asks for E through F_E1 */
    if (f == F_K || f == F_K1 || f == F_KE1)
      ref_ellipke_m1(out, NULL, a);
    else
      ref_ellipke_m1(NULL, out, a);
    break;
  case F_VARX: ref_varx(out, a); break;
  case F_VX: ref_vx(out, a); break;
  case F_VY: ref_vy(out, a); break;
  case F_RATIO: ref_ratio(out, a); break;
  case F_RATIO_TO_T: ref_ratio_to_t(out, x, got); break;
  }
  mpfr_clear(a);
}

static double now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e9 + ts.tv_nsec;
}

/* ns per call over xs[0..n): minimum over repetitions of a throughput loop */
static double time_per_call(double (*f)(double), const double *xs, int n) {
  volatile double sink = 0;
  double best = INFINITY;
  for (int rep = 0; rep < 7; rep++) {
    double t0 = now_ns(), acc = 0;
    for (int i = 0; i < n; i++) acc += f(xs[i]);
    double dt = (now_ns() - t0) / n;
    sink += acc;
    if (dt < best) best = dt;
  }
  (void)sink;
  return best;
}

int main(int argc, char **argv) {
  int samples = 2000, progress = isatty(2);
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--samples") && i + 1 < argc) {
      samples = atoi(argv[++i]);
      if (samples < 1 || samples > 10000000) {
        fprintf(stderr, "stability_sweep: --samples must be in 1..10000000\n");
        return 2;
      }
    } else if (!strcmp(argv[i], "--progress")) {
      progress = 1;
    } else {
      fprintf(stderr, "usage: stability_sweep [--samples N] [--progress]\n");
      return !strcmp(argv[i], "--help") || !strcmp(argv[i], "-h") ? 0 : 2;
    }
  }
  double *xs = malloc(sizeof *xs * (size_t)samples);
  if (!xs) {
    fprintf(stderr, "stability_sweep: out of memory\n");
    return 1;
  }
  mpfr_t ref;
  mpfr_init2(ref, REF_PREC + 64);
  const int nreg = (int)(sizeof regions / sizeof regions[0]);
  printf("function,region,lo,hi,samples,max_ulp,worst_input,ns_per_call\n");
  for (int k = 0; k < nreg; k++) {
    const region *r = &regions[k];
    double (*f)(double) = funcs[r->f].f;
    double worst = 0, worst_x = NAN, xmin = INFINITY, xmax = -INFINITY;
    seed_region(r);
    for (int i = 0; i < samples; i++) {
      double x = draw(r);
      xs[i] = x;
      xmin = fmin(xmin, x);
      xmax = fmax(xmax, x);
      double e;
      if (r->f == F_KE1) { /* both results of one call; the larger error counts */
        double gk, ge;
        ics_ellint_ke_m1(x, &gk, &ge);
        reference(F_K1, x, gk, ref);
        e = ref_ulp_error(gk, ref);
        reference(F_E1, x, ge, ref);
        e = fmax(e, ref_ulp_error(ge, ref));
      } else {
        double got = f(x);
        reference(r->f, x, got, ref);
        e = ref_ulp_error(got, ref);
      }
      if (e > worst || isnan(worst_x)) {
        worst = e;
        worst_x = x;
      }
    }
    double ns = time_per_call(f, xs, samples);
    int edge = r->draw == EDGE; /* bounds: the inputs drawn */
    printf("%s,\"%s\",%a,%a,%d,%.4f,%a,%.2f\n", funcs[r->f].name, r->region, edge ? xmin : r->lo,
           edge ? xmax : r->hi, samples, worst, worst_x, ns);
    fflush(stdout);
    if (progress) fprintf(stderr, "\rstability_sweep: %d/%d regions", k + 1, nreg);
  }
  if (progress) fputc('\n', stderr);
  mpfr_clear(ref);
  free(xs);
  return 0;
}
