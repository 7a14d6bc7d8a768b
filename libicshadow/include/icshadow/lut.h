/* icshadow/lut.h — lookup tables for ratioToab and abToVarx (Patel et al. 2013, Sec. 3.4) and
 * their header generator (C, GLSL, OpenCL). Method and measured errors: docs/lut.md.
 *
 * The exact functions are ics_ellipse_ratio_to_t (ratioToab) and ics_ellipse_vx (abToVarx),
 * icshadow/ellipse.h. The tables here never feed back into them: the builder samples the
 * exact functions only, so the checked-in tables can always be regenerated.
 *
 * Tabulation variables (chosen so that small tables keep a small RELATIVE error over the whole
 * domain, rat -> 0 and rat -> +inf included; t = ratioToab(rat), unit radii a = 1 - t, b = t):
 *   ratio table  s(w) = t / w  on  w = q / (1 + q) in [0, 1/2],  q = sqrt(rat), rat in [0, 1];
 *                nodes w_i = i / (2 (n - 1)). t ~ sqrt(rat / 2) as rat -> 0, so s(0) = 1/sqrt(2)
 *                (the limit), s(1/2) = 1 (rat = 1 is the circle). For rat > 1 the symmetry
 *                ratioToab(1/rat) = 1 - ratioToab(rat) gives a = 1 - t from the table, so both
 *                a and b keep their relative precision (the small one is never 1 - x).
 *   varx table   g(t) = V_x(t) / (1 - t)^2 = var_x(t / (1 - t)) on t in [0, 1/2], g in [1/3, 1/2],
 *                g(0) = 1/3, g(1/2) = 1/2; nodes uniform in u = sqrt(t (t + 1/5)) (quadratic
 *                spacing near t = 0, where g has a t^2 log t term; near-uniform beyond). For
 *                t > 1/2: g(t) = 1 - g(1 - t) (var_x(B) + var_x(1/B) = 1: E[cos^2] + E[sin^2] on
 *                one ellipse), from a = 1 - t as given. V_x(t) = (1 - t)^2 g(t) has the relative
 *                error of g, also as V_x(t) -> 0 at t -> 1.
 * Evaluation: linear interpolation between nodes, error O(1/n^2) (measured: docs/lut.md).
 *
 * Accuracy (measured on a dense grid against the exact functions, relative error):
 *   the library's own tables (n = ICS_LUT_BUILTIN_SIZE, lut_data.c, double evaluation):
 *   ratio_to_t / ratio_to_ab (both a and b)  <= ICS_LUT_BUILTIN_RATIO_BOUND
 *   vx / vx_ab                                <= ICS_LUT_BUILTIN_VX_BOUND
 *   ellipse_radii (both radii)                <= ICS_LUT_BUILTIN_RADII_BOUND
 * Each is the stamped (measured) maximum of lut_data.c rounded up to two significant digits;
 * tests/test_lut.c asserts them on an independent, denser sample. Float evaluation (GLSL,
 * OpenCL, ics_lut_float_*) adds at most ICS_LUT_FLOAT_EXTRA.
 * Domain: rat in [0, +inf], t in [0, 1]; NaN or out-of-domain input gives NaN; no errno. */
#ifndef ICSHADOW_LUT_H
#define ICSHADOW_LUT_H

#include <stdio.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_LUT_MIN_SIZE 4
#define ICS_LUT_MAX_SIZE 65536
/* Grid density of the stamped errors: points per table interval (see ics_lut_grid_create). */
#define ICS_LUT_STAMP_PER_INTERVAL 16

#define ICS_LUT_BUILTIN_SIZE 256
#define ICS_LUT_BUILTIN_RATIO_BOUND 2.4e-6 /* stamped 2.35e-6 */
#define ICS_LUT_BUILTIN_VX_BOUND 2.7e-6    /* stamped 2.60e-6 */
#define ICS_LUT_BUILTIN_RADII_BOUND 1.4e-6 /* stamped 1.32e-6 */
/* Float evaluation (the GLSL / OpenCL code, ics_lut_float_*; IEEE single with correctly rounded
 * sqrt and division) adds at most this to a bound: float rounding of the tables (2^-24
 * relative) and of the few operations after the lookup (measured: <= 1.5e-7, docs/lut.md). */
#define ICS_LUT_FLOAT_EXTRA (4 * 1.1920928955078125e-7)

/* A pair of tables of n entries each (caller-owned storage). */
typedef struct ics_lut_tables {
  int n;
  const double *s; /* s(w) = t / w at w_i = i / (2 (n - 1)) */
  const double *g; /* g(t) = V_x(t) / (1 - t)^2 at t_i in [0, 1/2] with u(t_i) = i u(1/2) / (n - 1),
                      u(t) = sqrt(t (t + 1/5)) */
} ics_lut_tables;

/* Fill s[0..n-1] and g[0..n-1] from the exact functions (ellipse.c). n in
 * [ICS_LUT_MIN_SIZE, ICS_LUT_MAX_SIZE], else ICS_ERR_RANGE; ICS_ERR_INVALID_ARG for NULL. */
ICS_API ics_status ics_lut_build(int n, double *s, double *g);

/* Evaluators on given tables (double arithmetic). ratio_to_ab writes the unit radii
 * a = 1 - t and b = t, each with its own relative precision. vx_ab takes a = 1 - t and b = t
 * separately, so V_x keeps its relative precision when a was computed precisely and t -> 1.
 * ellipse_radii: radii a, b of the elliptical kernel for variances (varx, vary), i.e.
 * a = (1 - t) sqrt(sc), b = t sqrt(sc), sc = varx / V_x(t), computed without cancellation as
 * a = sqrt(varx / g(t)), b = sqrt(vary / g(1 - t)); (0, 0) for varx = vary = 0; NaN for
 * negative, NaN or infinite variances. Domain: variances <= DBL_MAX / 4 (FLT_MAX / 4 for the
 * float code): beyond, var / g (g >= 1/3) may overflow to +inf. */
ICS_API double ics_lut_tables_ratio_to_t(const ics_lut_tables *L, double rat);
ICS_API void ics_lut_tables_ratio_to_ab(const ics_lut_tables *L, double rat, double *a, double *b);
ICS_API double ics_lut_tables_vx(const ics_lut_tables *L, double t);
ICS_API double ics_lut_tables_vx_ab(const ics_lut_tables *L, double a, double b);
ICS_API void ics_lut_tables_ellipse_radii(const ics_lut_tables *L, double varx, double vary,
                                          double *a, double *b);

/* The same in float arithmetic on float-rounded tables: a C mirror, operation for operation, of
 * the GLSL and OpenCL evaluators written by ics_lut_write (IEEE single, correctly rounded sqrt and
 * division, no contraction). sf, gf: the tables rounded to float. */
ICS_API void ics_lut_float_ratio_to_ab(int n, const float *sf, float rat, float *a, float *b);
ICS_API float ics_lut_float_vx(int n, const float *gf, float t);
ICS_API void ics_lut_float_ellipse_radii(int n, const float *sf, const float *gf, float varx,
                                         float vary, float *a, float *b);

/* The library's own checked-in tables (lut_data.c, n = ICS_LUT_BUILTIN_SIZE), double evaluation. */
ICS_API const ics_lut_tables *ics_lut_builtin(void);
ICS_API double ics_lut_ratio_to_t(double rat); /* ratioToab */
ICS_API void ics_lut_ratio_to_ab(double rat, double *a, double *b);
ICS_API double ics_lut_vx(double t); /* abToVarx */
ICS_API double ics_lut_vx_ab(double a, double b);
ICS_API void ics_lut_ellipse_radii(double varx, double vary, double *a, double *b);
/* What lut_data.c was stamped with: maximum relative errors (ratio, vx, radii) and the number
 * of grid points they were measured on (double evaluation, on the grid of
 * ics_lut_grid_create(&grid, n, ICS_LUT_STAMP_PER_INTERVAL)). */
ICS_API void ics_lut_builtin_stamp(double *ratio_err, double *vx_err, double *radii_err,
                                   long *points);

/* ---- measurement -------------------------------------------------------------------------
 * A grid of test points with their exact values: the ratio (and radii) points are uniform in w
 * over [0, 1] with `per_interval` points per table interval of a table of `n` entries (offset
 * so no point falls on a node), plus rat = 10^(k/8) for |k| <= 8 * 37, plus 0, +inf, the
 * smallest and largest normal floats; the varx points likewise in t over [0, 1] plus
 * t = 10^-k and 1 - 10^-k (k = 1..15) and t = 0, 1. These points are float-representable, so
 * the same grid measures the float evaluators; a few more are for double evaluation only:
 * rat = DBL_MIN, DBL_MAX, 1e-300, 1e300, t = 1e-300, 1 - 2^-53, and 1 - 10^-k for k > 7.
 * Radii points are (varx, vary) = (1, rat) for finite rat <= DBL_MAX / 4 (float: FLT_MAX / 4).
 * The grid is an opaque object: ics_lut_grid_create makes it (n in [ICS_LUT_MIN_SIZE,
 * ICS_LUT_MAX_SIZE], per_interval in [2, 1024], else ICS_ERR_RANGE; *out NULL on failure),
 * ics_lut_grid_destroy frees it (NULL is fine). */
typedef struct ics_lut_grid ics_lut_grid;
ICS_API ics_status ics_lut_grid_create(ics_lut_grid **out, int n, int per_interval);
ICS_API void ics_lut_grid_destroy(ics_lut_grid *grid);
ICS_API long ics_lut_grid_points(const ics_lut_grid *grid); /* ratio points + varx points */

typedef struct ics_lut_error {
  double ratio;    /* max relative error of a = 1 - t and of b = t from ratio_to_ab */
  double ratio_at; /* rat where it occurs */
  double vx;       /* max relative error of V_x(t) */
  double vx_at;    /* t where it occurs */
  double radii;    /* max relative error of the kernel radii a, b from ellipse_radii */
  double radii_at; /* vary / varx where it occurs */
  long points;     /* grid points used (float: the float-representable ones) */
} ics_lut_error;

/* Measure tables on a grid. use_float: evaluate through the float mirror on float-rounded
 * tables (what a GLSL / OpenCL header computes); else double evaluation. */
ICS_API ics_status ics_lut_measure(const ics_lut_grid *grid, const ics_lut_tables *L, int use_float,
                                   ics_lut_error *err);

/* Builds n-entry tables into s and g (ics_lut_build) and measures them on the stamp grid
 * (ICS_LUT_STAMP_PER_INTERVAL points per interval) in double and in float evaluation: the
 * errors a header written by ics_lut_write is stamped with. */
ICS_API ics_status ics_lut_build_measured(int n, double *s, double *g, ics_lut_error *err_double,
                                          ics_lut_error *err_float);

/* ---- header writers ------------------------------------------------------------------------ */
typedef enum ics_lut_lang {
  ICS_LUT_LANG_C,      /* self-contained C99 header: static tables + static inline functions */
  ICS_LUT_LANG_GLSL,   /* GLSL (no #version line; 3.30+ / 4.50 core): const float arrays */
  ICS_LUT_LANG_OPENCL, /* OpenCL C 1.2: __constant float arrays */
  ICS_LUT_LANG_C_DATA  /* the library's own libicshadow/src/lut_data.c */
} ics_lut_lang;

/* Write a generated header for tables L. `command` is stamped verbatim (no newline, quote,
 * backslash or comment end, else ICS_ERR_INVALID_ARG); err_double and err_float are the
 * measured errors of double and float evaluation (the float one is stamped in the GLSL and
 * OpenCL headers, the double one in the C ones). ICS_ERR_IO if a write fails. */
ICS_API ics_status ics_lut_write(FILE *f, ics_lut_lang lang, const ics_lut_tables *L,
                                 const char *command, const ics_lut_error *err_double,
                                 const ics_lut_error *err_float);

#ifdef __cplusplus
}
#endif
#endif
