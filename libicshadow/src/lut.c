/* lut.c — lookup tables for ratioToab and abToVarx: builder, evaluators, error measurement and
 * header writers (C, GLSL, OpenCL, and the library's own lut_data.c).
 *
 * Method (details and measured errors: docs/lut.md, icshadow/lut.h):
 *   ratio table s(w) = t / w at w_i = i / (2 (n - 1)), w = q / (1 + q), q = sqrt(rat) <= 1;
 *     rat > 1 goes through the symmetry ratioToab(1/rat) = 1 - ratioToab(rat): the table then
 *     gives a = 1 - t, and b = 1 - a >= 1/2. So the small radius is always w * s(w), with the
 *     relative error of s, and the large one is 1 - (small) with no cancellation.
 *   varx table g(t) = V_x(t) / (1 - t)^2 = var_x(t / (1 - t)) on t in [0, 1/2], nodes uniform
 *     in u = sqrt(t (t + 2 eps)), eps = 1/10; g(t) = 1 - g(1 - t) for t > 1/2 (var_x(B) and
 *     var_x(1/B) are E[cos^2] and E[sin^2] under the arc-length measure of one ellipse).
 *     V_x(t) = (1 - t)^2 g(t) has the relative error of g, also as V_x -> 0 at t -> 1.
 *   Both: linear interpolation, error ~ h^2 max|f''| / 8 relative to f, f = s or g bounded
 *     away from 0 (s in [1/sqrt 2, 1], g in [1/3, 1/2]). s and g have x^2 log x terms at 0
 *     (the elliptic integrals' logarithm): for s it costs a log n factor (observed order 1.8-1.9
 *     at n = 16..4096), for g the u variable absorbs it (order 2.00).
 * Special values: s(0) = 1/sqrt(2) is a limit (0/0): V_x(0) = var_x(0) = 1/3 (segment
 *   [-1, 1]) and var_x(b) -> 2/3 as b -> inf (two segments with density |cos|:
 *   int |cos|^3 / int |cos| = 2/3), so rat = V_y/V_x ~ 2 t^2 and t ~ sqrt(rat / 2) as rat -> 0.
 *   s(1/2) = 1 and g(1/2) = 1/2 are the circle. tests/test_lut.c checks all against ellipse.c.
 * The builder calls only the exact functions (ellipse.c), never the tables: no bootstrap loop.
 * Float mirror: ics_lut_float_* evaluate, operation for operation, the GLSL / OpenCL code the
 *   writers emit (checked bit for bit against PoCL in tests/test_lut_opencl.c).
 * Domain checks: NaN or rat < 0, t outside [0, 1] -> NaN. No errno. */
#include "icshadow/lut.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/ellipse.h"
#include "lut_data.h"
#include "lut_tap_text.h"

#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF /* the float mirror must round like the GPU code it mirrors */
#endif

/* ---- builder ---------------------------------------------------------------------------- */

/* varx table variable: u(t) = sqrt(t (t + 2 eps)), t in [0, 1/2], eps = G_EPS; nodes uniform in u.
 * u ~ sqrt(2 eps t) for t << eps (quadratic node spacing where g has its t^2 log t term) and
 * u ~ t + eps beyond (uniform). eps = 1/10 minimises the max error over eps in
 * {0, 0.001, ..., 0.2} (docs/lut.md); eps = 0 would be uniform t. */
#define G_EPS 0.1
#define G_UMAX_SQ 0.35 /* u(1/2)^2 = 1/2 (1/2 + 2 eps) */
static double g_scale(int n) { return (double)(n - 1) / sqrt(G_UMAX_SQ); }
static double g_node(int i, int n) {
  if (i == n - 1) return 0.5;
  double u = sqrt(G_UMAX_SQ) * i / (n - 1);
  return u * u / (sqrt(u * u + G_EPS * G_EPS) + G_EPS); /* sqrt(u^2 + eps^2) - eps */
}

ics_status ics_lut_build(int n, double *s, double *g) {
  if (!s || !g) return ICS_ERR_INVALID_ARG;
  if (n < ICS_LUT_MIN_SIZE || n > ICS_LUT_MAX_SIZE) return ICS_ERR_RANGE;
  for (int i = 0; i < n; i++) {
    double x = 0.5 * i / (n - 1); /* node: w for s, t for g; both in [0, 1/2] */
    if (i == 0) {
      s[i] = sqrt(0.5); /* limit of t / w as w -> 0, see the header comment */
    } else if (i == n - 1) {
      s[i] = 1.0; /* rat = 1 <=> t = 1/2 (the circle): keeps ratioToab(1) = 1/2 exact */
    } else {
      double q = x / (1.0 - x);
      s[i] = ics_ellipse_ratio_to_t(q * q) / x;
    }
    double t = g_node(i, n), a = 1.0 - t;
    /* g(0) = V_x(0) = 1/3; g(1/2) = V_x(1/2) / (1/4) = 1/2 exactly (the circle, and
     * g(t) + g(1 - t) = 1), set so that the two halves meet exactly at t = 1/2 */
    g[i] = i == n - 1 ? 0.5 : ics_ellipse_vx(t) / (a * a);
    if (!isfinite(s[i]) || !isfinite(g[i])) return ICS_ERR_RANGE;
  }
  return ICS_OK;
}

/* ---- double evaluators ---------------------------------------------------------------- */

static double interp(const double *y, int n, double x) {
  int i = (int)x;
  if (i > n - 2) i = n - 2;
  double f = x - (double)i;
  return y[i] + f * (y[i + 1] - y[i]);
}

/* g(t) for the unit radii a = 1 - t, b = t: the table covers t <= 1/2, and
 * g(t) = 1 - g(1 - t) the rest (with 1 - t = a as given, not recomputed). */
static double g_of(const ics_lut_tables *L, double a, double b) {
  double x = b <= 0.5 ? b : a;
  double v = interp(L->g, L->n, sqrt(x * (x + 2 * G_EPS)) * g_scale(L->n));
  return b <= 0.5 ? v : 1.0 - v;
}

void ics_lut_tables_ratio_to_ab(const ics_lut_tables *L, double rat, double *a, double *b) {
  if (!(rat >= 0)) {
    *a = *b = NAN;
    return;
  }
  int inv = rat > 1;
  double q = inv ? 1.0 / sqrt(rat) : sqrt(rat);
  double w = q / (1.0 + q);
  double u = w * interp(L->s, L->n, w * (double)(2 * (L->n - 1)));
  double v = 1.0 - u;
  *a = inv ? u : v;
  *b = inv ? v : u;
}

double ics_lut_tables_ratio_to_t(const ics_lut_tables *L, double rat) {
  double a, b;
  ics_lut_tables_ratio_to_ab(L, rat, &a, &b);
  return b;
}

double ics_lut_tables_vx_ab(const ics_lut_tables *L, double a, double b) {
  if (!(b >= 0 && b <= 1) || !(a >= 0 && a <= 1)) return NAN;
  return a * a * g_of(L, a, b);
}

double ics_lut_tables_vx(const ics_lut_tables *L, double t) {
  if (!(t >= 0 && t <= 1)) return NAN;
  return ics_lut_tables_vx_ab(L, 1.0 - t, t);
}

void ics_lut_tables_ellipse_radii(const ics_lut_tables *L, double varx, double vary, double *a,
                                  double *b) {
  if (!(varx >= 0 && vary >= 0) || isinf(varx) || isinf(vary)) {
    *a = *b = NAN;
    return;
  }
  if (varx == 0 && vary == 0) {
    *a = *b = 0;
    return;
  }
  double au, bu;
  ics_lut_tables_ratio_to_ab(L, vary / varx, &au, &bu);
  *a = sqrt(varx / g_of(L, au, bu)); /* g(t) */
  *b = sqrt(vary / g_of(L, bu, au)); /* g(1 - t) */
}

/* ---- float mirror of the GLSL / OpenCL code (keep in step with write_glsl / write_opencl) -- */

static float interpf(const float *y, int n, float x) {
  int i = (int)x;
  if (i > n - 2) i = n - 2;
  float f = x - (float)i;
  return y[i] + f * (y[i + 1] - y[i]);
}

static float g_off(int n, const float *gf, float a, float b) {
  float x = b <= 0.5f ? b : a;
  float v = interpf(gf, n, sqrtf(x * (x + (float)(2 * G_EPS))) * (float)g_scale(n));
  return b <= 0.5f ? v : 1.0f - v;
}

void ics_lut_float_ratio_to_ab(int n, const float *sf, float rat, float *a, float *b) {
  if (!(rat >= 0.0f)) {
    *a = *b = NAN;
    return;
  }
  int inv = rat > 1.0f;
  float q = inv ? 1.0f / sqrtf(rat) : sqrtf(rat);
  float w = q / (1.0f + q);
  float u = w * interpf(sf, n, w * (float)(2 * (n - 1)));
  float v = 1.0f - u;
  *a = inv ? u : v;
  *b = inv ? v : u;
}

float ics_lut_float_vx(int n, const float *gf, float t) {
  if (!(t >= 0.0f && t <= 1.0f)) return NAN;
  float a = 1.0f - t;
  return a * a * g_off(n, gf, a, t);
}

void ics_lut_float_ellipse_radii(int n, const float *sf, const float *gf, float varx, float vary,
                                 float *a, float *b) {
  if (varx == 0.0f && vary == 0.0f) {
    *a = *b = 0.0f;
    return;
  }
  float au, bu;
  ics_lut_float_ratio_to_ab(n, sf, vary / varx, &au, &bu);
  *a = sqrtf(varx / g_off(n, gf, au, bu));
  *b = sqrtf(vary / g_off(n, gf, bu, au));
}

/* ---- the library's own tables --------------------------------------------------------- */

static const ics_lut_tables *builtin(void) { return &ics_lut_data_tables; }
const ics_lut_tables *ics_lut_builtin(void) { return builtin(); }
double ics_lut_ratio_to_t(double rat) { return ics_lut_tables_ratio_to_t(builtin(), rat); }
void ics_lut_ratio_to_ab(double rat, double *a, double *b) {
  ics_lut_tables_ratio_to_ab(builtin(), rat, a, b);
}
double ics_lut_vx(double t) { return ics_lut_tables_vx(builtin(), t); }
double ics_lut_vx_ab(double a, double b) { return ics_lut_tables_vx_ab(builtin(), a, b); }
void ics_lut_ellipse_radii(double varx, double vary, double *a, double *b) {
  ics_lut_tables_ellipse_radii(builtin(), varx, vary, a, b);
}
void ics_lut_builtin_stamp(double *ratio_err, double *vx_err, double *radii_err, long *points) {
  if (ratio_err) *ratio_err = ics_lut_data_ratio.max_rel_err;
  if (vx_err) *vx_err = ics_lut_data_vx.max_rel_err;
  if (radii_err) *radii_err = ics_lut_data_radii_max_rel_err;
  if (points) *points = ics_lut_data_ratio.grid_points;
}

/* ---- measurement grid ------------------------------------------------------------------- */

typedef struct ratio_point {
  double rat;        /* float-representable unless !float_ok */
  int float_ok;      /* rat is a float in the normal range (or 0, +inf) */
  double a, b;       /* exact unit radii a = 1 - t, b = t */
  double ka, kb;     /* exact kernel radii for (varx, vary) = (1, rat); NaN: not a radii point */
} ratio_point;

typedef struct vx_point {
  double t;
  int float_ok;
  double vx;
} vx_point;

struct ics_lut_grid {
  long nr, nv;
  ratio_point *r;
  vx_point *v;
};

static void exact_ratio_point(ratio_point *p) {
  double rat = p->rat;
  /* Exact unit radii, each from the side where it is the small one (symmetry). */
  if (rat <= 1) {
    p->b = ics_ellipse_ratio_to_t(rat);
    p->a = 1.0 - p->b;
  } else {
    p->a = isinf(rat) ? 0.0 : ics_ellipse_ratio_to_t(1.0 / rat);
    p->b = 1.0 - p->a;
  }
  /* Kernel radii for varx = 1, vary = rat: sc = varx / V_x(t) = vary / V_y(t),
   * V_y(t) = V_x(1 - t) = V_x(a); use the form whose V argument is <= 1/2. */
  if (!(rat <= DBL_MAX / 4)) { /* outside ellipse_radii's domain (vary / g must not overflow) */
    p->ka = p->kb = NAN;
  } else if (rat <= 1) {
    double sc = 1.0 / ics_ellipse_vx(p->b);
    p->ka = p->a * sqrt(sc);
    p->kb = p->b * sqrt(sc);
  } else {
    double sc = rat / ics_ellipse_vx(p->a);
    p->ka = p->a * sqrt(sc);
    p->kb = p->b * sqrt(sc);
  }
}

static int add_ratio(ics_lut_grid *G, long cap, double rat, int float_ok) {
  if (G->nr >= cap) return -1;
  if (float_ok) {
    float f = (float)rat;
    if (!(f == 0.0f || isinf(f) || fabsf(f) >= FLT_MIN)) float_ok = 0;
    else rat = f;
  }
  ratio_point *p = &G->r[G->nr++];
  p->rat = rat;
  p->float_ok = float_ok;
  exact_ratio_point(p);
  return 0;
}

static int add_vx(ics_lut_grid *G, long cap, double t, int float_ok) {
  if (G->nv >= cap) return -1;
  if (float_ok) t = (float)t;
  vx_point *p = &G->v[G->nv++];
  p->t = t;
  p->float_ok = float_ok;
  p->vx = ics_ellipse_vx(t);
  return 0;
}

ics_status ics_lut_grid_create(ics_lut_grid **out, int n, int per_interval) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (n < ICS_LUT_MIN_SIZE || n > ICS_LUT_MAX_SIZE || per_interval < 2 || per_interval > 1024)
    return ICS_ERR_RANGE;
  const double phase = 0.3819660112501051; /* (3 - sqrt 5)/2: no point falls on a node */
  long mr = (long)per_interval * 2 * (n - 1); /* w over [0, 1]: 2 (n - 1) table intervals */
  long mv = (long)per_interval * (n - 1);
  long capr = mr + 2 * 8 * 37 + 1 + 16, capv = mv + 2 * 15 + 8;
  ics_lut_grid *G = calloc(1, sizeof *G);
  if (!G) return ICS_ERR_NOMEM;
  G->r = malloc((size_t)capr * sizeof *G->r);
  G->v = malloc((size_t)capv * sizeof *G->v);
  if (!G->r || !G->v) {
    ics_lut_grid_destroy(G);
    return ICS_ERR_NOMEM;
  }
  int bad = 0;
  for (long j = 0; j < mr; j++) {
    double w = (j + phase) / mr, q = w / (1.0 - w);
    bad |= add_ratio(G, capr, q * q, 1);
  }
  for (int k = -8 * 37; k <= 8 * 37; k++) bad |= add_ratio(G, capr, pow(10.0, k / 8.0), 1);
  bad |= add_ratio(G, capr, 0.0, 1);
  bad |= add_ratio(G, capr, INFINITY, 1);
  bad |= add_ratio(G, capr, FLT_MIN, 1);
  bad |= add_ratio(G, capr, FLT_MAX, 1);
  /* double-only extremes */
  bad |= add_ratio(G, capr, DBL_MIN, 0);
  bad |= add_ratio(G, capr, DBL_MAX, 0);
  bad |= add_ratio(G, capr, 1e-300, 0);
  bad |= add_ratio(G, capr, 1e300, 0);
  for (long j = 0; j < mv; j++) bad |= add_vx(G, capv, (j + phase) / mv, 1);
  for (int k = 1; k <= 15; k++) {
    bad |= add_vx(G, capv, pow(10.0, -k), 1);
    bad |= add_vx(G, capv, 1.0 - pow(10.0, -k), k <= 7); /* 1 - 1e-8 is 1 in float */
  }
  bad |= add_vx(G, capv, 0.0, 1);
  bad |= add_vx(G, capv, 1.0, 1);
  bad |= add_vx(G, capv, 1e-300, 0);
  bad |= add_vx(G, capv, 1.0 - DBL_EPSILON / 2, 0);
  if (bad) {
    ics_lut_grid_destroy(G);
    return ICS_ERR_RANGE; /* capacity arithmetic above is wrong: cannot happen */
  }
  *out = G;
  return ICS_OK;
}

void ics_lut_grid_destroy(ics_lut_grid *grid) {
  if (!grid) return;
  free(grid->r);
  free(grid->v);
  free(grid);
}

long ics_lut_grid_points(const ics_lut_grid *grid) { return grid ? grid->nr + grid->nv : 0; }

/* Relative error; an exact zero must be matched exactly; NaN anywhere counts as infinite. */
static double relerr(double x, double ref) {
  if (isnan(x) || isnan(ref)) return INFINITY;
  if (ref == 0 || isinf(ref) || isinf(x)) return x == ref ? 0.0 : INFINITY;
  return fabs(x - ref) / fabs(ref);
}

static void worst(double e, double at, double *max, double *max_at) {
  if (e > *max || (isinf(e) && !isinf(*max))) {
    *max = e;
    *max_at = at;
  }
}

ics_status ics_lut_measure(const ics_lut_grid *G, const ics_lut_tables *L, int use_float,
                           ics_lut_error *err) {
  if (!G || !L || !L->s || !L->g || !err) return ICS_ERR_INVALID_ARG;
  if (L->n < ICS_LUT_MIN_SIZE || L->n > ICS_LUT_MAX_SIZE) return ICS_ERR_RANGE;
  float *sf = NULL, *gf = NULL;
  if (use_float) {
    sf = malloc((size_t)L->n * sizeof *sf);
    gf = malloc((size_t)L->n * sizeof *gf);
    if (!sf || !gf) {
      free(sf);
      free(gf);
      return ICS_ERR_NOMEM;
    }
    for (int i = 0; i < L->n; i++) {
      sf[i] = (float)L->s[i];
      gf[i] = (float)L->g[i];
    }
  }
  memset(err, 0, sizeof *err);
  for (long j = 0; j < G->nr; j++) {
    const ratio_point *p = &G->r[j];
    if (use_float && !p->float_ok) continue;
    double a, b, ka = NAN, kb = NAN;
    err->points++;
    /* float radii: vary / g(1 - t) <= 3 vary must not overflow (documented domain) */
    int radii = !isnan(p->ka) && !(use_float && p->rat > FLT_MAX / 4);
    if (use_float) {
      float fa, fb, fka, fkb;
      ics_lut_float_ratio_to_ab(L->n, sf, (float)p->rat, &fa, &fb);
      a = fa;
      b = fb;
      if (radii) {
        ics_lut_float_ellipse_radii(L->n, sf, gf, 1.0f, (float)p->rat, &fka, &fkb);
        ka = fka;
        kb = fkb;
      }
    } else {
      ics_lut_tables_ratio_to_ab(L, p->rat, &a, &b);
      if (radii) ics_lut_tables_ellipse_radii(L, 1.0, p->rat, &ka, &kb);
    }
    worst(fmax(relerr(a, p->a), relerr(b, p->b)), p->rat, &err->ratio, &err->ratio_at);
    if (radii)
      worst(fmax(relerr(ka, p->ka), relerr(kb, p->kb)), p->rat, &err->radii, &err->radii_at);
  }
  for (long j = 0; j < G->nv; j++) {
    const vx_point *p = &G->v[j];
    if (use_float && !p->float_ok) continue;
    double v = use_float ? (double)ics_lut_float_vx(L->n, gf, (float)p->t)
                         : ics_lut_tables_vx(L, p->t);
    worst(relerr(v, p->vx), p->t, &err->vx, &err->vx_at);
    err->points++;
  }
  free(sf);
  free(gf);
  return ICS_OK;
}

/* ---- header writers --------------------------------------------------------------------- */

static const char *lang_name(ics_lut_lang lang) {
  switch (lang) {
  case ICS_LUT_LANG_C: return "C";
  case ICS_LUT_LANG_GLSL: return "GLSL";
  case ICS_LUT_LANG_OPENCL: return "OpenCL C";
  case ICS_LUT_LANG_C_DATA: return "C (libicshadow's own lut_data.c)";
  }
  return "?";
}

static void write_stamp(FILE *f, ics_lut_lang lang, const char *file, const ics_lut_tables *L,
                        const char *command, const ics_lut_error *ed, const ics_lut_error *ef) {
  int gpu = lang == ICS_LUT_LANG_GLSL || lang == ICS_LUT_LANG_OPENCL;
  const ics_lut_error *e = gpu ? ef : ed;
  long points = e->points;
  const char *dash = gpu ? "-" : "\u2014"; /* shader compilers get plain ASCII */
  fprintf(f,
          "/* %s %s lookup tables for ratioToab and abToVarx (Patel et al. 2013, Sec. 3.4), %s.\n"
          " * generated %s do not edit.\n"
          " * Command: %s\n"
          " * (the output path is not part of the stamp: it does not change the contents)\n"
          " * The project's copies are regenerated by scripts/gen_luts.sh; method: docs/lut.md.\n"
          " *\n"
          " * Two tables of %d entries, nodes uniform in their variables, linear interpolation:\n"
          " *   s(w) = t / w on w = q / (1 + q) in [0, 1/2], q = sqrt(rat): t = ratioToab(rat) for\n"
          " *          rat <= 1; for rat > 1 the same with 1/rat gives a = 1 - t (symmetry).\n"
          " *   g(t) = V_x(t) / (1 - t)^2 on t in [0, 1/2], nodes uniform in u = sqrt(t (t + 1/5)),\n"
          " *          and g(t) = 1 - g(1 - t) for t > 1/2: abToVarx(t) = V_x(t) = (1 - t)^2 g(t).\n"
          " * Kernel radii for variances (varx, vary): a = sqrt(varx / g(t)), b = sqrt(vary / "
          "g(1 - t)).\n"
          " *\n"
          " * Maximum relative error against the exact functions (libicshadow ellipse.c), measured\n"
          " * on %ld grid points (rat from 0 to +inf, t from 0 to 1, ends included)%s:\n"
          " *   ratio_to_ab (a = 1 - t and b = t): %.3g (at rat = %.6g)\n"
          " *   vx (abToVarx):                     %.3g (at t = %.6g)\n"
          " *   ellipse_radii (a and b):           %.3g (at vary/varx = %.6g)\n",
          file, dash, lang_name(lang), dash, command, L->n, points,
          gpu ? ",\n * evaluating THIS code in float (float-rounded tables, IEEE single arithmetic"
                " with\n * correctly rounded sqrt and division; a device with less accurate sqrt or"
                " division\n * adds its own few ulps, ~1e-7 each)"
              : ", double evaluation",
          e->ratio, e->ratio_at, e->vx, e->vx_at, e->radii, e->radii_at);
  if (gpu)
    fprintf(f,
            " * Table error alone (double evaluation): ratio %.3g, vx %.3g, radii %.3g.\n"
            " * Bound for float evaluation anywhere: table error + %.2g (float rounding).\n",
            ed->ratio, ed->vx, ed->radii, ICS_LUT_FLOAT_EXTRA);
  fprintf(f, " */\n");
}

static int write_c_array(FILE *f, const char *decl, const double *y, int n) {
  fprintf(f, "%s = {\n", decl);
  for (int i = 0; i < n; i++)
    fprintf(f, "%s%a,%s", (i % 4) ? " " : "    ", y[i], (i % 4 == 3 || i == n - 1) ? "\n" : "");
  return fprintf(f, "};\n") < 0 ? -1 : 0;
}

static void write_c_data(FILE *f, const ics_lut_tables *L, const char *command,
                         const ics_lut_error *ed, const ics_lut_error *ef) {
  write_stamp(f, ICS_LUT_LANG_C_DATA, "lut_data.c", L, command, ed, ef);
  fprintf(f, "#include \"lut_data.h\"\n\n");
  write_c_array(f, "static const double ratio_y[]", L->s, L->n);
  fprintf(f, "\n");
  write_c_array(f, "static const double vx_y[]", L->g, L->n);
  fprintf(f,
          "\nconst ics_lut_data_table ics_lut_data_ratio = {%d, %a, %ld, ratio_y};\n"
          "const ics_lut_data_table ics_lut_data_vx = {%d, %a, %ld, vx_y};\n"
          "const ics_lut_tables ics_lut_data_tables = {%d, ratio_y, vx_y};\n"
          "const double ics_lut_data_radii_max_rel_err = %a;\n"
          "const char ics_lut_data_command[] = \"%s\";\n",
          L->n, ed->ratio, ed->points, L->n, ed->vx, ed->points, L->n, ed->radii, command);
}

static void write_c(FILE *f, const ics_lut_tables *L, const char *command, const ics_lut_error *ed,
                    const ics_lut_error *ef) {
  write_stamp(f, ICS_LUT_LANG_C, "icshadow_lut.h", L, command, ed, ef);
  fprintf(f,
          "/* Self-contained C99 header (double). Functions: ics_tab_ratio_to_ab, ics_tab_ratio_to_t,\n"
          " * ics_tab_vx, ics_tab_vx_ab, ics_tab_ellipse_radii, ics_tab_ellipse_tap (tap k of n);\n"
          " * NaN outside the domain. */\n"
          "#ifndef ICSHADOW_LUT_GENERATED_H\n#define ICSHADOW_LUT_GENERATED_H\n\n"
          "#include <math.h>\n\n#define ICS_TAB_N %d\n"
          "#define ICS_TAB_RATIO_MAX_REL_ERR %.3g\n#define ICS_TAB_VX_MAX_REL_ERR %.3g\n"
          "#define ICS_TAB_RADII_MAX_REL_ERR %.3g\n\n",
          L->n, ed->ratio, ed->vx, ed->radii);
  write_c_array(f, "static const double ics_tab_s[ICS_TAB_N]", L->s, L->n);
  fprintf(f, "\n");
  write_c_array(f, "static const double ics_tab_g[ICS_TAB_N]", L->g, L->n);
  fprintf(f,
          "\nstatic inline double ics_tab_interp(const double *y, double x) {\n"
          "  int i = (int)x;\n"
          "  if (i > ICS_TAB_N - 2) i = ICS_TAB_N - 2;\n"
          "  double f = x - (double)i;\n"
          "  return y[i] + f * (y[i + 1] - y[i]);\n"
          "}\n\n"
          "/* g(t) = V_x(t) / (1 - t)^2 for a = 1 - t, b = t; table on u = sqrt(t (t + %a)),\n"
          " * t <= 1/2, and g(t) = 1 - g(1 - t). */\n"
          "static inline double ics_tab_g_ab(double a, double b) {\n"
          "  double x = b <= 0.5 ? b : a;\n"
          "  double v = ics_tab_interp(ics_tab_g, sqrt(x * (x + %a)) * %a);\n"
          "  return b <= 0.5 ? v : 1.0 - v;\n"
          "}\n\n"
          "/* ratioToab: unit radii a = 1 - t, b = t for rat = vary / varx in [0, +inf]. */\n"
          "static inline void ics_tab_ratio_to_ab(double rat, double *a, double *b) {\n"
          "  if (!(rat >= 0)) {\n    *a = *b = NAN;\n    return;\n  }\n"
          "  int inv = rat > 1;\n"
          "  double q = inv ? 1.0 / sqrt(rat) : sqrt(rat);\n"
          "  double w = q / (1.0 + q);\n"
          "  double u = w * ics_tab_interp(ics_tab_s, w * %.1f);\n"
          "  double v = 1.0 - u;\n"
          "  *a = inv ? u : v;\n  *b = inv ? v : u;\n"
          "}\n\n"
          "static inline double ics_tab_ratio_to_t(double rat) {\n"
          "  double a, b;\n  ics_tab_ratio_to_ab(rat, &a, &b);\n  return b;\n}\n\n"
          "/* abToVarx with a = 1 - t and b = t given separately (keeps V_x's relative precision\n"
          " * when a is small). */\n"
          "static inline double ics_tab_vx_ab(double a, double b) {\n"
          "  if (!(b >= 0 && b <= 1) || !(a >= 0 && a <= 1)) return NAN;\n"
          "  return a * a * ics_tab_g_ab(a, b);\n"
          "}\n\n"
          "/* abToVarx: V_x(t), t in [0, 1]. */\n"
          "static inline double ics_tab_vx(double t) {\n"
          "  if (!(t >= 0 && t <= 1)) return NAN;\n"
          "  return ics_tab_vx_ab(1.0 - t, t);\n"
          "}\n\n"
          "/* Radii of the elliptical kernel for variances varx, vary >= 0 (finite). */\n"
          "static inline void ics_tab_ellipse_radii(double varx, double vary, double *a, "
          "double *b) {\n"
          "  if (!(varx >= 0 && vary >= 0) || isinf(varx) || isinf(vary)) {\n"
          "    *a = *b = NAN;\n    return;\n  }\n"
          "  if (varx == 0 && vary == 0) {\n    *a = *b = 0;\n    return;\n  }\n"
          "  double au, bu;\n"
          "  ics_tab_ratio_to_ab(vary / varx, &au, &bu);\n"
          "  *a = sqrt(varx / ics_tab_g_ab(au, bu));\n"
          "  *b = sqrt(vary / ics_tab_g_ab(bu, au));\n"
          "}\n",
          2 * G_EPS, 2 * G_EPS, g_scale(L->n), 2.0 * (L->n - 1));
  ics_lut_write_tap_c(f);
  fprintf(f, "\n#endif\n");
}

static void write_float_array(FILE *f, ics_lut_lang lang, const char *name, const double *y,
                              int n) {
  if (lang == ICS_LUT_LANG_GLSL)
    fprintf(f, "const float %s[%d] = float[%d](\n", name, n, n);
  else
    fprintf(f, "__constant float %s[%d] = {\n", name, n);
  for (int i = 0; i < n; i++) {
    float v = (float)y[i];
    const char *sep = i == n - 1 ? "" : ",";
    const char *lead = (i % 4) ? " " : "    ";
    const char *end = (i % 4 == 3 || i == n - 1) ? "\n" : "";
    if (lang == ICS_LUT_LANG_GLSL) /* GLSL has no hex floats: 9 digits round-trip a float */
      fprintf(f, "%s%.8e%s%s", lead, (double)v, sep, end);
    else
      fprintf(f, "%s%af%s%s", lead, (double)v, sep, end);
  }
  fprintf(f, lang == ICS_LUT_LANG_GLSL ? ");\n" : "};\n");
}

/* The GLSL and OpenCL evaluators share one text; T(glsl, opencl) picks the spelling. Keep in
 * step with the float mirror above (ics_lut_float_*), which measures this code. */
static void write_gpu_functions(FILE *f, ics_lut_lang lang, const ics_lut_tables *L) {
  int gl = lang == ICS_LUT_LANG_GLSL;
#define T(glsl, opencl) (gl ? (glsl) : (opencl))
  const char *fn = T("", "static inline "), *v2 = T("vec2", "float2");
  const char *pragma = T("", "#pragma OPENCL FP_CONTRACT OFF\n");
  const char *nan = T("uintBitsToFloat(0x7fc00000u)", "NAN");
  char eps2[40], gscale[40], sscale[40];
  float fe = (float)(2 * G_EPS), fg = (float)g_scale(L->n), fs = (float)(2 * (L->n - 1));
  /* GLSL has no hex floats: 9 significant digits round-trip a float exactly */
  snprintf(eps2, sizeof eps2, gl ? "%.8e" : "%af", (double)fe);
  snprintf(gscale, sizeof gscale, gl ? "%.8e" : "%af", (double)fg);
  snprintf(sscale, sizeof sscale, gl ? "%.8e" : "%af", (double)fs);
  for (int k = 0; k < 2; k++) {
    const char *tab = k ? "g" : "s";
    fprintf(f,
            "\n%sfloat ics_tab_interp_%s(float x) {\n%s"
            "  int i = min(%s, ICS_TAB_N - 2);\n"
            "  float f = x - %s;\n"
            "  return ics_tab_%s[i] + f * (ics_tab_%s[i + 1] - ics_tab_%s[i]);\n"
            "}\n",
            fn, tab, pragma, T("int(x)", "(int)x"), T("float(i)", "(float)i"), tab, tab, tab);
  }
  fprintf(f,
          "\n/* g(t) = V_x(t) / (1 - t)^2 for ab = (1 - t, t): table on u = sqrt(t (t + 2 eps)),\n"
          " * t <= 1/2, and g(t) = 1 - g(1 - t). */\n"
          "%sfloat ics_tab_g_ab(%s ab) {\n%s"
          "  float x = ab.y <= 0.5%s ? ab.y : ab.x;\n"
          "  float v = ics_tab_interp_g(sqrt(x * (x + %s)) * %s);\n"
          "  return ab.y <= 0.5%s ? v : 1.0%s - v;\n"
          "}\n",
          fn, v2, pragma, T("", "f"), eps2, gscale, T("", "f"), T("", "f"));
  fprintf(f,
          "\n/* ratioToab: unit radii (a, b) = (1 - t, t) for rat = vary / varx in [0, +inf]. */\n"
          "%s%s ics_tab_ratio_to_ab(float rat) {\n%s"
          "  if (!(rat >= 0.0%s)) return %s(%s, %s);\n"
          "  bool inv = rat > 1.0%s;\n"
          "  float q = inv ? 1.0%s / sqrt(rat) : sqrt(rat);\n"
          "  float w = q / (1.0%s + q);\n"
          "  float u = w * ics_tab_interp_s(w * %s);\n"
          "  float v = 1.0%s - u;\n"
          "  return inv ? %s(u, v) : %s(v, u);\n"
          "}\n",
          fn, v2, pragma, T("", "f"), T("vec2", "(float2)"), nan, nan, T("", "f"), T("", "f"),
          T("", "f"), sscale, T("", "f"), T("vec2", "(float2)"), T("vec2", "(float2)"));
  fprintf(f,
          "\n%sfloat ics_tab_ratio_to_t(float rat) { return ics_tab_ratio_to_ab(rat).y; }\n"
          "\n/* abToVarx from ab = (1 - t, t) (keeps V_x's relative precision as t -> 1). */\n"
          "%sfloat ics_tab_vx_ab(%s ab) {\n%s"
          "  return ab.x * ab.x * ics_tab_g_ab(ab);\n"
          "}\n"
          "\n/* abToVarx: V_x(t), t in [0, 1]. */\n"
          "%sfloat ics_tab_vx(float t) {\n"
          "  if (!(t >= 0.0%s && t <= 1.0%s)) return %s;\n"
          "  return ics_tab_vx_ab(%s(1.0%s - t, t));\n"
          "}\n",
          fn, fn, v2, pragma, fn, T("", "f"), T("", "f"), nan, T("vec2", "(float2)"), T("", "f"));
  fprintf(f,
          "\n/* Kernel radii (a, b) for variances varx, vary in [0, FLT_MAX / 4]. */\n"
          "%s%s ics_tab_ellipse_radii(float varx, float vary) {\n%s"
          "  if (varx == 0.0%s && vary == 0.0%s) return %s(0.0%s, 0.0%s);\n"
          "  %s ab = ics_tab_ratio_to_ab(vary / varx);\n"
          "  return %s(sqrt(varx / ics_tab_g_ab(ab)), sqrt(vary / ics_tab_g_ab(ab.yx)));\n"
          "}\n",
          fn, v2, pragma, T("", "f"), T("", "f"), T("vec2", "(float2)"), T("", "f"), T("", "f"),
          v2, T("vec2", "(float2)"));
  ics_lut_write_tap_gpu(f, gl);
  fprintf(f, "\n#endif\n");
#undef T
}

static void write_glsl(FILE *f, const ics_lut_tables *L, const char *command,
                       const ics_lut_error *ed, const ics_lut_error *ef) {
  write_stamp(f, ICS_LUT_LANG_GLSL, "icshadow_lut.glsl", L, command, ed, ef);
  fprintf(f,
          "/* GLSL: include (or concatenate) after #version 330 or later (uintBitsToFloat gives NaN).\n"
          " * Functions: ics_tab_ratio_to_ab(rat) -> vec2(a, b) = (1 - t, t); ics_tab_ratio_to_t;\n"
          " * ics_tab_vx(t); ics_tab_vx_ab(vec2(1 - t, t)); ics_tab_ellipse_radii(varx, vary)\n"
          " * -> vec2(a, b); ics_tab_ellipse_tap(varx, vary, angle_deg, n, k, u) -> vec2 (tap k of n). */\n"
          "#ifndef ICSHADOW_LUT_GLSL\n#define ICSHADOW_LUT_GLSL\n\n"
          "const int ICS_TAB_N = %d;\n",
          L->n);
  write_float_array(f, ICS_LUT_LANG_GLSL, "ics_tab_s", L->s, L->n);
  write_float_array(f, ICS_LUT_LANG_GLSL, "ics_tab_g", L->g, L->n);
  write_gpu_functions(f, ICS_LUT_LANG_GLSL, L);
}

static void write_opencl(FILE *f, const ics_lut_tables *L, const char *command,
                         const ics_lut_error *ed, const ics_lut_error *ef) {
  write_stamp(f, ICS_LUT_LANG_OPENCL, "icshadow_lut.cl", L, command, ed, ef);
  fprintf(f,
          "/* OpenCL C 1.2: include in a program source (or concatenate before the kernels).\n"
          " * Functions: ics_tab_ratio_to_ab(rat) -> (float2)(a, b) = (1 - t, t);\n"
          " * ics_tab_ratio_to_t; ics_tab_vx(t); ics_tab_vx_ab((float2)(1 - t, t));\n"
          " * ics_tab_ellipse_radii(varx, vary) -> (float2)(a, b);\n"
          " * ics_tab_ellipse_tap(varx, vary, angle_deg, n, k, u) -> (float2) (tap k of n).\n"
          " * FP_CONTRACT is off inside these functions so they round like the measured code. */\n"
          "#ifndef ICSHADOW_LUT_CL\n#define ICSHADOW_LUT_CL\n\n"
          "#define ICS_TAB_N %d\n",
          L->n);
  write_float_array(f, ICS_LUT_LANG_OPENCL, "ics_tab_s", L->s, L->n);
  write_float_array(f, ICS_LUT_LANG_OPENCL, "ics_tab_g", L->g, L->n);
  write_gpu_functions(f, ICS_LUT_LANG_OPENCL, L);
}

ics_status ics_lut_build_measured(int n, double *s, double *g, ics_lut_error *err_double,
                                  ics_lut_error *err_float) {
  ics_lut_grid *grid = NULL;
  ics_lut_tables L = {n, s, g};
  ics_status st = ics_lut_build(n, s, g);
  if (st == ICS_OK) st = ics_lut_grid_create(&grid, n, ICS_LUT_STAMP_PER_INTERVAL);
  if (st == ICS_OK) st = ics_lut_measure(grid, &L, 0, err_double);
  if (st == ICS_OK) st = ics_lut_measure(grid, &L, 1, err_float);
  ics_lut_grid_destroy(grid);
  return st;
}

ics_status ics_lut_write(FILE *f, ics_lut_lang lang, const ics_lut_tables *L, const char *command,
                         const ics_lut_error *ed, const ics_lut_error *ef) {
  if (!f || !L || !L->s || !L->g || !command || !ed || !ef) return ICS_ERR_INVALID_ARG;
  if (L->n < ICS_LUT_MIN_SIZE || L->n > ICS_LUT_MAX_SIZE) return ICS_ERR_RANGE;
  /* Stamped text goes into comments and one C string: refuse what would break either. */
  for (const char *c = command; *c; c++)
    if (*c == '\n' || *c == '"' || *c == '\\' || (*c == '*' && c[1] == '/'))
      return ICS_ERR_INVALID_ARG;
  switch (lang) {
  case ICS_LUT_LANG_C: write_c(f, L, command, ed, ef); break;
  case ICS_LUT_LANG_GLSL: write_glsl(f, L, command, ed, ef); break;
  case ICS_LUT_LANG_OPENCL: write_opencl(f, L, command, ed, ef); break;
  case ICS_LUT_LANG_C_DATA: write_c_data(f, L, command, ed, ef); break;
  default: return ICS_ERR_INVALID_ARG;
  }
  return ferror(f) ? ICS_ERR_IO : ICS_OK;
}
