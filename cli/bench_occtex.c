/* bench_occtex.c — `icshadow bench occtex [options]`: occlusion textures (Eisemann & Décoret
 * 2006) against brute-force visibility of a rectangular light, side by side in one run.
 * One CSV row per texture size x slice count x prefilter x combination: build and query times
 * (min over repetitions), error against the brute force, speed-up over it. With --fig3-csv,
 * writes the data of Eisemann Fig. 3 (max vs sum vs product on one receiver plane) instead. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_stats.h"
#include "commands.h"
#include "icshadow.h"

#define MAX_LIST 8
/* Limits checked while parsing (see est_bytes / est_work and --help): estimated peak memory of
 * one configuration, and estimated work in "operations" (about 1-1.7 ns each on the 2-core VM of
 * docs/occtex.md: 2^36 operations take 1-2 minutes). */
#define OT_MAX_GIB 4
#define OT_MAX_BYTES ((double)OT_MAX_GIB * 1073741824.0)
#define OT_MAX_WORK 68719476736.0 /* 2^36 */

static const char CMD[] = "bench occtex";
static cli_progress g_prog; /* set up once the options are parsed */
static int g_progress;    /* --progress given */

/* Peak bytes of one configuration (n x n textures, K slices): the bench's and the object's
 * texture copies, the slicing bitmap, the largest prefilter (N-Buffers: levels of side
 * n + 2^l - 1, l = 0..log2 n, and its padded scratch level) and the receiver arrays. */
static double est_bytes(double n, double K, double ss, double R) {
  double nb = 0, L = 0;
  for (double w = 1; w < n; w *= 2) L++;
  for (double l = 0, p = 1; l <= L; l++, p *= 2) nb += (n + p - 1) * (n + p - 1);
  double scratch = n + 3 * (L > 0 ? pow(2, L - 1) : 1);
  double pre = K * nb * 4 + scratch * scratch * 4, sat = K * n * n * 8, mip = K * n * n * 4 * 4 / 3;
  if (sat > pre) pre = sat;
  if (mip > pre) pre = mip;
  return 2 * K * n * n * 4 + (n * ss) * (n * ss) + pre + R * R * 7 * 8;
}
/* Operations of one configuration, one repetition: slicing (3 times, once per prefilter:
 * K (n ss)^2 sub-samples x 2), the three prefilters (~3 K n^2 (log2 n + 5) for N-Buffers,
 * less for the others) and the 9 query passes (R^2 K lookups, up to 16 taps x 16 reads for the
 * pyramids). */
static double est_work(double n, double K, double ss, double R) {
  double L = 0;
  for (double w = 1; w < n; w *= 2) L++;
  return 3 * K * (n * ss) * (n * ss) * 2 + K * n * n * (3 * (L + 5) + 8) + 3 * R * R * K * (256 + 256 + 16);
}
/* Bytes read + written by a method, counted from its data structures (float 4, double 8):
 * build = slicing (per slice: the (n S)^2-byte sub-sample bitmap cleared, painted and read,
 * the n^2 texture written) + the object's copy (read and write K n^2 floats) + the prefilter:
 * mipmap and N-Buffers read and write every level once (4 K x their total texels, x 2; the
 * N-Buffers also clear and fill a padded scratch level, so x 4 for them), the SAT reads the
 * floats and writes doubles (12 K n^2). query = per receiver its point (24) and result (8),
 * and per slice one lookup: 2 levels x 4 texels x 4 bytes for the pyramids (one tap: the
 * light is square), 4 bilinear corner reads x 4 doubles for the SAT. */
static double bytes_build(ics_occ_prefilter pf, double n, double K, double ss) {
  double b = K * (3 * (n * ss) * (n * ss) + 4 * n * n) + 8 * K * n * n, lev = 0;
  int L = 0;
  for (double w = 1; w < n; w *= 2) L++;
  if (pf == ICS_OCC_SAT) return b + 12 * K * n * n;
  for (int l = 0; l <= L; l++) {
    double w = pf == ICS_OCC_MIPMAP ? n / pow(2, l) : n + pow(2, l) - 1;
    lev += w * w;
  }
  return b + (pf == ICS_OCC_MIPMAP ? 2 : 4) * 4 * K * lev;
}
static double bytes_query(ics_occ_prefilter pf, double K, double R) {
  return R * R * (24 + 8 + K * (pf == ICS_OCC_SAT ? 128 : 32));
}

/* Brute force, one repetition: R^2 receivers x M^2 rays x (at most) every box, plus the cull. */
static double est_brute(double R, double M, double boxes) { return R * R * (M * M * boxes + boxes); }

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow bench occtex [options]\n"
          "Occlusion textures (Eisemann & Decoret 2006): a synthetic scene of boxes between a square\n"
          "light (z = 0) and a receiver plane is cut into K slices; each slice's occlusion texture is\n"
          "prefiltered (mipmap, nbuffers, sat) and looked up with the box of Eq. 4 at every receiver;\n"
          "slices are combined by product (Eq. 5), clamped sum or max. The reference is brute-force\n"
          "visibility (M x M rays to the light per receiver). CSV on stdout, header first, numbers\n"
          "printed with %%.17g:\n"
          "  scene,prefilter,combination,size,slices,build_ms,query_ms,time_ms,build_bytes,\n"
          "  query_bytes,brute_ms,mean_abs_err,max_abs_err,mean_signed_err,speedup,\n"
          "  brute_median_ms,time_median_ms,speedup_median\n"
          "build_ms = slicing + prefilter, query_ms = all receivers, time_ms = both; each the\n"
          "minimum over the repetitions, measured in the same run as brute_ms; speedup =\n"
          "brute_ms / time_ms; the last three: the brute force's median, the median of each\n"
          "repetition's build + query, and their ratio.\n"
          "Errors are occlusion (fraction of the light hidden) minus the brute force's, over all\n"
          "receivers. Bytes read + written, counted from the data structures (float 4, double 8;\n"
          "S = --supersample, R = --receivers):\n"
          "  build_bytes = K (3 (n S)^2 + 12 n^2) (slicing bitmap, texture, object copy) + the\n"
          "    prefilter: mipmap 8 K x its texels (each level read and written once), N-Buffers\n"
          "    16 K x its texels (also the padded scratch level), SAT 12 K n^2 (floats in, doubles out);\n"
          "  query_bytes = R^2 (32 + K x 32 (mipmap, nbuffers: 2 levels x 4 texels) or K x 128\n"
          "    (SAT: 4 corners x 4 doubles)).\n\n"
          "options:\n"
          "  --sizes LIST        texture sides, powers of two in 1..%d (default 128,256)\n"
          "  --slices LIST       slice counts, 1..%d (default 4,8,16)\n"
          "  --scene LIST        scenes from foliage, plates, blocks (default plates,foliage):\n"
          "                      12 thin plates / 150 small cubes / 20 large blocks\n"
          "  --boxes N           boxes in every scene, 1..100000 (default: as above)\n"
          "  --seed N            scene seed, 0..2^31-1 (default 1)\n"
          "  --light W           side of the square light, > 0 and <= 100 (default 0.6)\n"
          "  --receivers R       R x R receivers on the plane z = 2.5, 1..1024 (default 48)\n"
          "  --light-samples M   brute force: M x M rays per receiver, 1..1024 (default 32)\n"
          "  --supersample S     slicing: S x S samples per texel, 1..%d (default 2)\n"
          "  --reps N            repetitions for the timings, 1..100 (default 3)\n"
          "  --fig3-csv FILE     write Fig. 3 data instead: x,y,exact,max,sum,product (occlusion) at\n"
          "                      the R x R receivers, for the first scene, size and slice count\n"
          "                      and --fig3-prefilter\n"
          "  --fig3-prefilter P  mipmap | nbuffers | sat (default sat)\n"
          "  --progress          progress on stderr (default: only when stderr is a terminal)\n"
          "The scene lies in x, y in [-1, 1], z in [1, 2]; the textures cover [-1, 1]^2; receivers\n"
          "cover [-1.2, 1.2]^2.\n"
          "Limits, checked before anything runs (exit 2 naming the options), for every size n x\n"
          "slice count K that will run:\n"
          "  K x n^2 <= 2^%.0f texels (the library's ICS_OCC_MAX_TEXELS);\n"
          "  memory: 8 K n^2 (two texture copies) + (n S)^2 (slicing) + the largest prefilter\n"
          "    (N-Buffers: 4 K sum_l (n + 2^l - 1)^2, about 4 K (log2 n + 5) n^2) bytes <= %d GiB;\n"
          "  work per configuration: reps x (6 K (n S)^2 + K n^2 (3 log2 n + 23) + 1584 R^2 K)\n"
          "    operations <= 2^36 (1-2 minutes here), and for the brute force of one scene\n"
          "    reps x R^2 x (M^2 + 1) x boxes <= 2^36 (S = --supersample, R = --receivers,\n"
          "    M = --light-samples).\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input.\n",
          ICS_OCC_MAX_SIZE, ICS_OCC_MAX_SLICES, ICS_OCC_MAX_SUPERSAMPLE, log2((double)ICS_OCC_MAX_TEXELS),
          OT_MAX_GIB);
}

static const char *const scene_names[] = {"foliage", "plates", "blocks"};

typedef struct {
  int sizes[MAX_LIST], nsizes, slices[MAX_LIST], nslices;
  ics_occ_boxes_kind scenes[3];
  int nscenes;
  int boxes, seed, receivers, m, ss, reps;
  double light;
  const char *fig3;
  ics_occ_prefilter fig3_pf;
} options;

/* comma-separated integers in lo..hi; pow2: powers of two only */
static int int_list(const char *cmd, const char *opt, const char *s, long lo, long hi, int pow2,
                    int *out, int *count) {
  char buf[256];
  if (strlen(s) >= sizeof buf || !*s)
    return cli_error(cmd, "%s: expected a comma-separated list, got '%s'", opt, s);
  strcpy(buf, s);
  *count = 0;
  /* split at every comma: an empty item (",,", "1,,2", "1,") is an error, as in sat's --modes */
  for (char *tok = buf, *comma; tok; tok = comma ? comma + 1 : NULL) {
    comma = strchr(tok, ',');
    if (comma) *comma = '\0';
    if (!*tok) return cli_error(cmd, "%s: empty list item in '%s'", opt, s);
    int v;
    if (*count >= MAX_LIST) return cli_error(cmd, "%s: at most %d values", opt, MAX_LIST);
    if (cli_parse_int(tok, lo, hi, &v) != 0 || (pow2 && (v & (v - 1))))
      return cli_error(cmd, "%s: expected %sintegers in %ld..%ld, got '%s'", opt,
                       pow2 ? "power-of-two " : "", lo, hi, tok);
    out[(*count)++] = v;
  }
  return 0;
}

static int parse_sizes(const char *cmd, const char *opt, const char *s, void *dest) {
  options *o = dest;
  return int_list(cmd, opt, s, 1, ICS_OCC_MAX_SIZE, 1, o->sizes, &o->nsizes);
}

static int parse_slices(const char *cmd, const char *opt, const char *s, void *dest) {
  options *o = dest;
  return int_list(cmd, opt, s, 1, ICS_OCC_MAX_SLICES, 0, o->slices, &o->nslices);
}

/* --scene: comma-separated scene names, each at most once */
static int parse_scenes(const char *cmd, const char *opt, const char *val, void *dest) {
  options *o = dest;
  const char *p = val;
  o->nscenes = 0;
  while (1) {
    size_t len = strcspn(p, ",");
    int which = -1;
    for (int k = 0; k < 3; k++)
      if (len == strlen(scene_names[k]) && !strncmp(p, scene_names[k], len)) which = k;
    for (int k = 0; k < o->nscenes; k++)
      if ((int)o->scenes[k] == which) which = -2;
    if (which < 0)
      return cli_error(cmd, "%s: expected a list of distinct names from foliage, plates, blocks; "
                       "got '%s'", opt, val);
    o->scenes[o->nscenes++] = (ics_occ_boxes_kind)which;
    if (!p[len]) return 0;
    p += len + 1;
  }
}

/* --light: the side of the square light, in (0, 100] */
static int parse_light_side(const char *cmd, const char *opt, const char *val, void *dest) {
  double *w = dest;
  if (cli_parse_double(val, w) != 0) return cli_error(cmd, "%s: not a number: '%s'", opt, val);
  if (isnan(*w) || !(*w > 0) || !(*w <= 100))
    return cli_error(cmd, "%s: expected a size in (0, 100], got '%s'", opt, val);
  return 0;
}

static int parse_prefilter(const char *cmd, const char *opt, const char *val, void *dest) {
  ics_occ_prefilter *pf = dest;
  if (!strcmp(val, "mipmap"))
    *pf = ICS_OCC_MIPMAP;
  else if (!strcmp(val, "nbuffers"))
    *pf = ICS_OCC_NBUFFERS;
  else if (!strcmp(val, "sat"))
    *pf = ICS_OCC_SAT;
  else
    return cli_error(cmd, "%s: unknown prefilter '%s' (mipmap, nbuffers, sat)", opt, val);
  return 0;
}

/* 0, or the exit status after the message */
static int parse(int argc, char **argv, options *o) {
  *o = (options){{128, 256}, 2, {4, 8, 16}, 3, {ICS_OCC_BOXES_PLATES, ICS_OCC_BOXES_FOLIAGE}, 2, 0, 1, 48, 32, 2, 3, 0.6, NULL, ICS_OCC_SAT};
  int given_reps = 0, given_prefilter = 0;
  const cli_option opts[] = {
      {"--sizes", .kind = CLI_CALL, .dest = o, .parse = parse_sizes},
      {"--slices", .kind = CLI_CALL, .dest = o, .parse = parse_slices},
      {"--scene", .kind = CLI_CALL, .dest = o, .parse = parse_scenes},
      {"--boxes", .kind = CLI_INT, .dest = &o->boxes, .lo = 1, .hi = 100000},
      {"--seed", .kind = CLI_INT, .dest = &o->seed, .lo = 0, .hi = 2147483647L},
      {"--light", .kind = CLI_CALL, .dest = &o->light, .parse = parse_light_side},
      {"--receivers", .kind = CLI_INT, .dest = &o->receivers, .lo = 1, .hi = 1024},
      {"--light-samples", .kind = CLI_INT, .dest = &o->m, .lo = 1, .hi = 1024},
      {"--supersample", .kind = CLI_INT, .dest = &o->ss, .lo = 1, .hi = ICS_OCC_MAX_SUPERSAMPLE},
      {"--reps", .kind = CLI_INT, .dest = &o->reps, .lo = 1, .hi = 100, .given = &given_reps},
      {"--fig3-csv", .kind = CLI_FILE, .dest = &o->fig3},
      {"--fig3-prefilter", .kind = CLI_CALL, .dest = &o->fig3_pf, .parse = parse_prefilter,
       .given = &given_prefilter},
      {"--progress", .kind = CLI_FLAG, .dest = &g_progress},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  /* options the chosen mode does not use: warn */
  if (o->fig3) {
    if (given_reps) cli_warning(CMD, "--reps is ignored with --fig3-csv");
    if (o->nsizes > 1 || o->nslices > 1 || o->nscenes > 1)
      cli_warning(CMD, "--fig3-csv uses only the first --scene, --sizes and --slices values (%s, "
                  "%d, %d)", scene_names[o->scenes[0]], o->sizes[0], o->slices[0]);
  } else if (given_prefilter) {
    cli_warning(CMD, "--fig3-prefilter is ignored without --fig3-csv");
  }
  for (int i = 0; i < o->nsizes; i++)
    if ((long)o->sizes[i] * o->ss > 8192)
      return cli_error(CMD, "--sizes x --supersample must stay <= 8192");
  return 0;
}

static int fail(const char *what, ics_status st) {
  return cli_failure(CMD, "%s: %s", what, ics_status_str(st));
}

/* slice + build one prefilter; returns the object, times in ms */
static ics_status build(const options *o, const ics_occ_box *boxes, int nb, int n, int K, ics_occ_prefilter pf,
                        float *tex, ics_occtex **ot, double *ms) {
  const ics_occ_grid g = {-1, -1, 2.0 / n, n};
  double t0 = cli_now_s();
  ics_status st = ics_occtex_slice_boxes(boxes, (size_t)nb, &g, K, 1, 2, o->ss, tex);
  if (!st) st = ics_occtex_create(ot, tex, &g, K, 1, 2);
  if (!st) st = ics_occtex_prefilter(*ot, pf);
  *ms = 1e3 * (cli_now_s() - t0);
  return st;
}

static int scene_boxes(const options *o, ics_occ_boxes_kind k) {
  static const int def[3] = {150, 12, 20}; /* foliage, plates, blocks */
  return o->boxes ? o->boxes : def[k];
}

/* memory and work limits of every configuration that will run (fig3: the first of each): 0, or
 * the exit status after the message */
static int check_limits(const options *o) {
  const int na = o->fig3 ? 1 : o->nsizes, nb = o->fig3 ? 1 : o->nslices, nsc = o->fig3 ? 1 : o->nscenes;
  for (int a = 0; a < na; a++)
    for (int b = 0; b < nb; b++) {
      const int n = o->sizes[a], K = o->slices[b];
      if ((double)K * n * n > (double)ICS_OCC_MAX_TEXELS)
        return cli_error(CMD, "--sizes %d with --slices %d: %d x %d^2 texels exceeds the limit "
                         "2^%.0f (see --help)", n, K, K, n, log2((double)ICS_OCC_MAX_TEXELS));
      double by = est_bytes(n, K, o->ss, o->receivers);
      if (by > OT_MAX_BYTES)
        return cli_error(CMD, "--sizes %d with --slices %d: an estimated %.1f GiB of memory "
                         "(textures and N-Buffers); the limit is %d GiB (see --help)", n, K,
                         by / 1073741824.0, OT_MAX_GIB);
      double wk = est_work(n, K, o->ss, o->receivers);
      if (!o->fig3) wk *= o->reps;
      if (wk > OT_MAX_WORK)
        return cli_error(CMD, "--sizes %d with --slices %d, --supersample %d, --receivers %d and "
                         "--reps %d: an estimated %.3g operations; the work limit is 2^36 = %.3g "
                         "(1-2 minutes here; see --help)", n, K, o->ss, o->receivers,
                         o->fig3 ? 1 : o->reps, wk, OT_MAX_WORK);
    }
  for (int sc = 0; sc < nsc; sc++) {
    int boxes = scene_boxes(o, o->scenes[sc]);
    double wk = est_brute(o->receivers, o->m, boxes) * (o->fig3 ? 1 : o->reps);
    if (wk > OT_MAX_WORK)
      return cli_error(CMD, "brute force: --receivers %d with --light-samples %d, %d boxes (%s) "
                       "and --reps %d: an estimated %.3g operations; the work limit is 2^36 = "
                       "%.3g (1-2 minutes here; see --help)", o->receivers, o->m, boxes,
                       scene_names[o->scenes[sc]], o->fig3 ? 1 : o->reps, wk, OT_MAX_WORK);
  }
  return 0;
}

int bench_occtex(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  options o;
  int rc = parse(argc, argv, &o);
  if (!rc) rc = check_limits(&o);
  if (rc) return rc;
  cli_progress_init(&g_prog, "icshadow bench occtex", g_progress);

  const size_t R = (size_t)o.receivers, nr = R * R;
  int maxb = 0, maxn = 0, maxk = 0;
  for (int i = 0; i < o.nscenes; i++) maxb = scene_boxes(&o, o.scenes[i]) > maxb ? scene_boxes(&o, o.scenes[i]) : maxb;
  for (int i = 0; i < o.nsizes; i++) maxn = o.sizes[i] > maxn ? o.sizes[i] : maxn;
  for (int i = 0; i < o.nslices; i++) maxk = o.slices[i] > maxk ? o.slices[i] : maxk;
  ics_occ_box *boxes = malloc((size_t)maxb * sizeof *boxes);
  double *P = malloc(3 * nr * sizeof *P), *ref = malloc(nr * sizeof *ref), *occ = malloc(3 * nr * sizeof *occ);
  float *tex = malloc((size_t)maxn * maxn * maxk * sizeof *tex);
  int header = 0, busy = 0; /* busy: the brute-force repetitions spread over 30 % */
  ics_status st;
  if (!boxes || !P || !ref || !occ || !tex) {
    rc = fail("allocation", ICS_ERR_NOMEM);
    goto done;
  }
  for (size_t j = 0; j < R; j++)
    for (size_t i = 0; i < R; i++) {
      P[3 * (j * R + i)] = -1.2 + 2.4 * (i + 0.5) / R;
      P[3 * (j * R + i) + 1] = -1.2 + 2.4 * (j + 0.5) / R;
      P[3 * (j * R + i) + 2] = 2.5;
    }
  const ics_occ_light light = {0, 0, o.light, o.light};

  if (o.fig3) { /* first scene, first size, first slice count */
    ics_occtex *ot = NULL;
    double ms;
    const int nb = scene_boxes(&o, o.scenes[0]);
    cli_progress_say(&g_prog, "fig3: slicing, prefilter, shadows and brute force");
    st = ics_occtex_boxes_make(o.scenes[0], nb, (uint64_t)o.seed, boxes);
    if (!st) st = build(&o, boxes, nb, o.sizes[0], o.slices[0], o.fig3_pf, tex, &ot, &ms);
    for (int c = 0; c < 3 && !st; c++) st = ics_occtex_shadow(ot, &light, o.fig3_pf, (ics_occ_combine)c, P, nr, occ + c * nr);
    if (!st) st = ics_occtex_exact(boxes, (size_t)nb, &light, o.m, P, nr, ref);
    ics_occtex_destroy(ot);
    if (st) {
      rc = fail("fig3", st);
      goto done;
    }
    cli_output out;
    if (cli_output_open(&out, CMD, o.fig3) != 0) {
      rc = 1;
      goto done;
    }
    fprintf(out.fp, "x,y,exact,max,sum,product\n");
    for (size_t i = 0; i < nr; i++)
      fprintf(out.fp, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", P[3 * i], P[3 * i + 1], ref[i],
              occ[ICS_OCC_MAX * nr + i], occ[ICS_OCC_SUM * nr + i], occ[ICS_OCC_PRODUCT * nr + i]);
    rc = cli_output_commit(&out) ? 1 : 0;
    goto done;
  }

  enum { NPF = ICS_OCC_PREFILTER_COUNT, NC = ICS_OCC_COMBINE_COUNT };
  static double tb[MAX_LIST][MAX_LIST][NPF], tq[MAX_LIST][MAX_LIST][NPF][NC];
  static double emean[MAX_LIST][MAX_LIST][NPF][NC], emax[MAX_LIST][MAX_LIST][NPF][NC], ebias[MAX_LIST][MAX_LIST][NPF][NC];
  /* every repetition's times (build + query of that repetition; brute force), for the medians */
  static double trep[MAX_LIST][MAX_LIST][NPF][NC][100], brep[100];
  for (int sc = 0; sc < o.nscenes; sc++) {
    const int nb = scene_boxes(&o, o.scenes[sc]);
    if ((st = ics_occtex_boxes_make(o.scenes[sc], nb, (uint64_t)o.seed, boxes))) {
      rc = fail("scene", st);
      goto done;
    }
    double brute = INFINITY, brute_max = 0;
    for (int a = 0; a < MAX_LIST; a++)
      for (int b = 0; b < MAX_LIST; b++)
        for (int p = 0; p < NPF; p++) {
          tb[a][b][p] = INFINITY;
          for (int c = 0; c < NC; c++) tq[a][b][p][c] = INFINITY;
        }
    /* each repetition runs the brute force and every method once: side by side in one run */
    for (int rep = 0; rep < o.reps; rep++) {
      cli_progress_say(&g_prog, "%s: repetition %d/%d: brute force", scene_names[o.scenes[sc]], rep + 1, o.reps);
      double t0 = cli_now_s();
      if ((st = ics_occtex_exact(boxes, (size_t)nb, &light, o.m, P, nr, ref))) {
        rc = fail("brute force", st);
        goto done;
      }
      double t1 = 1e3 * (cli_now_s() - t0);
      brute = t1 < brute ? t1 : brute;
      brute_max = t1 > brute_max ? t1 : brute_max;
      brep[rep] = t1;
      for (int a = 0; a < o.nsizes; a++)
        for (int b = 0; b < o.nslices; b++)
          for (int p = 0; p < NPF; p++) {
            ics_occtex *ot = NULL;
            double ms;
            cli_progress_say(&g_prog, "%s: repetition %d/%d: size %d, %d slices, %s",
                             scene_names[o.scenes[sc]], rep + 1, o.reps, o.sizes[a], o.slices[b],
                             ics_occtex_prefilter_name((ics_occ_prefilter)p));
            st = build(&o, boxes, nb, o.sizes[a], o.slices[b], (ics_occ_prefilter)p, tex, &ot, &ms);
            if (st) {
              ics_occtex_destroy(ot);
              rc = fail("build", st);
              goto done;
            }
            tb[a][b][p] = ms < tb[a][b][p] ? ms : tb[a][b][p];
            for (int c = 0; c < NC; c++) {
              double q0 = cli_now_s();
              st = ics_occtex_shadow(ot, &light, (ics_occ_prefilter)p, (ics_occ_combine)c, P, nr, occ);
              double q = 1e3 * (cli_now_s() - q0);
              if (st) {
                ics_occtex_destroy(ot);
                rc = fail("shadow", st);
                goto done;
              }
              tq[a][b][p][c] = q < tq[a][b][p][c] ? q : tq[a][b][p][c];
              trep[a][b][p][c][rep] = ms + q;
              double sa = 0, mx = 0, sb = 0;
              for (size_t i = 0; i < nr; i++) {
                double e = occ[i] - ref[i];
                sa += fabs(e);
                sb += e;
                mx = fabs(e) > mx ? fabs(e) : mx;
              }
              emean[a][b][p][c] = sa / nr;
              emax[a][b][p][c] = mx;
              ebias[a][b][p][c] = sb / nr;
            }
            ics_occtex_destroy(ot);
          }
    }
    if (o.reps > 1 && cli_spread_busy((cli_spread){brute, brute, brute_max})) busy = 1;
    double brute_median = cli_spread_of(brep, o.reps).median;
    if (!header++)
      printf("scene,prefilter,combination,size,slices,build_ms,query_ms,time_ms,build_bytes,query_bytes,"
             "brute_ms,mean_abs_err,max_abs_err,mean_signed_err,speedup,brute_median_ms,"
             "time_median_ms,speedup_median\n");
    for (int a = 0; a < o.nsizes; a++)
      for (int b = 0; b < o.nslices; b++)
        for (int p = 0; p < NPF; p++)
          for (int c = 0; c < NC; c++) {
            double t = tb[a][b][p] + tq[a][b][p][c];
            double bb = bytes_build((ics_occ_prefilter)p, o.sizes[a], o.slices[b], o.ss);
            double bq = bytes_query((ics_occ_prefilter)p, o.slices[b], (double)R);
            double tmed = cli_spread_of(trep[a][b][p][c], o.reps).median;
            printf("%s,%s,%s,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
                   "%.17g,%.17g,%.17g\n",
                   scene_names[o.scenes[sc]], ics_occtex_prefilter_name((ics_occ_prefilter)p),
                   ics_occtex_combine_name((ics_occ_combine)c), o.sizes[a], o.slices[b],
                   tb[a][b][p], tq[a][b][p][c], t, bb, bq, brute, emean[a][b][p][c],
                   emax[a][b][p][c], ebias[a][b][p][c], brute / t, brute_median, tmed,
                   brute_median / tmed);
          }
  }
  if (cli_stdout_failed(CMD)) rc = 1;
  if (busy) cli_warn_busy(CMD, "brute_ms; the columns are minima");
done:
  cli_progress_done(&g_prog);
  free(boxes);
  free(P);
  free(ref);
  free(occ);
  free(tex);
  return rc;
}
