/* cmd_lut.c — `icshadow lut`: write a lookup-table header (C, GLSL, OpenCL, or the library's
 * own lut_data.c) for ratioToab and abToVarx, stamped with the command and the measured error;
 * or `--report`: error against evaluation time for a range of table sizes, as CSV.
 * The tables are built from the exact functions (ellipse.c), never from the library's own
 * checked-in tables, so this command can always regenerate them. Method: docs/lut.md. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_stats.h"
#include "commands.h"
#include "icshadow.h"

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow lut --size N --lang c|glsl|opencl|c-data [-o FILE]\n"
          "       icshadow lut --report [--sizes N,N,...] [--progress]\n\n"
          "Lookup tables for ratioToab (t from rat = vary/varx) and abToVarx (V_x(t)) of\n"
          "Patel et al. 2013, Sec. 3.4, built from libicshadow's exact functions.\n\n"
          "  --size N    entries per table, %d..%d\n"
          "  --lang L    c       self-contained C header (double; static inline ics_tab_*)\n"
          "              glsl    GLSL header (float; no #version line)\n"
          "              opencl  OpenCL C 1.2 header (float)\n"
          "              c-data  libicshadow/src/lut_data.c, the library's own tables\n"
          "  -o FILE     output file (default: stdout); written atomically\n"
          "  --report    CSV: for each size, max relative error of each table (double and\n"
          "              float evaluation) against the exact functions, and the evaluation\n"
          "              time per call in ns (double C evaluators; the exact functions too);\n"
          "              each size on its own grid, the one its header's stamp is measured on\n"
          "              (grid_points), so a size reports the same numbers in any --sizes list\n"
          "  --sizes L   sizes for --report (default 8,16,32,...,4096)\n"
          "  --progress  progress on stderr (default: only when stderr is a terminal)\n\n"
          "The header is stamped with the command (without -o) and the maximum relative error\n"
          "measured on a dense grid (%d points per table interval, ends of the domain included).\n",
          ICS_LUT_MIN_SIZE, ICS_LUT_MAX_SIZE, ICS_LUT_STAMP_PER_INTERVAL);
}

static const char CMD[] = "lut";

static const struct {
  const char *name;
  ics_lut_lang lang;
} langs[] = {
    {"c", ICS_LUT_LANG_C},
    {"glsl", ICS_LUT_LANG_GLSL},
    {"opencl", ICS_LUT_LANG_OPENCL},
    {"c-data", ICS_LUT_LANG_C_DATA},
};

typedef struct tables {
  int n;
  double *s, *g;
  ics_lut_tables view;
} tables;

/* the n-entry tables and their stamp errors (ics_lut_build_measured) */
static ics_status tables_build(tables *T, int n, ics_lut_error *ed, ics_lut_error *ef) {
  T->n = n;
  T->s = malloc((size_t)n * sizeof *T->s);
  T->g = malloc((size_t)n * sizeof *T->g);
  if (!T->s || !T->g) return ICS_ERR_NOMEM;
  T->view.n = n;
  T->view.s = T->s;
  T->view.g = T->g;
  return ics_lut_build_measured(n, T->s, T->g, ed, ef);
}

static void tables_free(tables *T) {
  free(T->s);
  free(T->g);
  T->s = T->g = NULL;
}

static int write_header(int n, const char *lang_name, ics_lut_lang lang, const char *path) {
  char command[128];
  snprintf(command, sizeof command, "icshadow lut --size %d --lang %s", n, lang_name);
  tables T = {0};
  ics_lut_error ed, ef;
  ics_status st = tables_build(&T, n, &ed, &ef);
  if (st != ICS_OK) {
    cli_failure(CMD, "cannot build the tables: %s", ics_status_str(st));
    tables_free(&T);
    return 1;
  }
  if (!isfinite(ed.ratio) || !isfinite(ed.vx) || !isfinite(ed.radii)) {
    /* An exact function returned NaN/inf somewhere on the grid: say so, but still write. */
    cli_warning(CMD, "non-finite measured error (exact function failure?)");
  }
  cli_output out;
  if (cli_output_open(&out, CMD, path) != 0) {
    tables_free(&T);
    return 1;
  }
  errno = 0;
  st = ics_lut_write(out.fp, lang, &T.view, command, &ed, &ef);
  int write_errno = errno;
  tables_free(&T);
  if (st != ICS_OK) {
    if (st == ICS_ERR_IO && write_errno) /* the failed write's own reason (ENOSPC, EFBIG, ...) */
      cli_failure(CMD, "cannot write %s: %s", path, strerror(write_errno));
    else
      cli_failure(CMD, "writing failed: %s", ics_status_str(st));
    cli_output_abort(&out);
    return 1;
  }
  return cli_output_commit(&out) == 0 ? 0 : 1;
}

/* ---- --report ------------------------------------------------------------------------------ */

enum { NSAMPLES = 4096 };
static volatile double sink;

/* ns per call of f over the sample, repeated until at least ~20 ms have passed. */
/* ns per call of f over the samples: a warm-up pass, then TIME_REPS repetitions of >= 4 ms */
#define TIME_REPS 7
static cli_spread time_fn(double (*f)(const ics_lut_tables *, double), const ics_lut_tables *L,
                          const double *x) {
  double ns[TIME_REPS], acc = 0;
  for (int i = 0; i < NSAMPLES; i++) acc += f(L, x[i]); /* warm-up: caches, branch history */
  for (int rep = 0; rep < TIME_REPS; rep++) {
    long calls = 0;
    double t0 = cli_now_s(), t1;
    do {
      for (int i = 0; i < NSAMPLES; i++) acc += f(L, x[i]);
      calls += NSAMPLES;
      t1 = cli_now_s();
    } while (t1 - t0 < 4e-3);
    ns[rep] = 1e9 * (t1 - t0) / calls;
  }
  sink = acc;
  return cli_spread_of(ns, TIME_REPS);
}

static double exact_ratio(const ics_lut_tables *L, double x) {
  (void)L;
  return ics_ellipse_ratio_to_t(x);
}
static double exact_vx(const ics_lut_tables *L, double x) {
  (void)L;
  return ics_ellipse_vx(x);
}

static double order(double e_prev, double e, int n_prev, int n) {
  return log(e_prev / e) / log((double)(n - 1) / (n_prev - 1));
}

static int parse_sizes(const char *s, int *sizes, int cap, int *count) {
  *count = 0;
  char buf[512];
  if (strlen(s) >= sizeof buf) return -1;
  strcpy(buf, s);
  /* split by hand: strtok would merge empty fields ("4,,8"), which are refused */
  for (char *tok = buf, *next; tok; tok = next) {
    next = strchr(tok, ',');
    if (next) *next++ = 0;
    if (!*tok || *count >= cap) return -1;
    if (cli_parse_int(tok, ICS_LUT_MIN_SIZE, ICS_LUT_MAX_SIZE, &sizes[*count]) != 0) return -1;
    if (*count && sizes[*count] <= sizes[*count - 1]) return -1;
    (*count)++;
  }
  return *count ? 0 : -1;
}

static int report(const int *sizes, int nsizes, int progress) {
  ics_status st = ICS_OK;
  /* Timing samples: rat log-uniform over [1e-6, 1e6]; t uniform over [0, 1]. */
  double xr[NSAMPLES], xt[NSAMPLES];
  unsigned long long state = 0x9E3779B97F4A7C15ull;
  for (int i = 0; i < NSAMPLES; i++) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    double u = (double)(state >> 11) / 9007199254740992.0;
    xr[i] = pow(10.0, -6.0 + 12.0 * u);
    xt[i] = (i + 0.5) / NSAMPLES;
  }
  printf("method,size,ratio_max_rel_err,vx_max_rel_err,radii_max_rel_err,"
         "ratio_float_max_rel_err,vx_float_max_rel_err,radii_float_max_rel_err,"
         "ratio_order,vx_order,ratio_ns_per_call,vx_ns_per_call,grid_points,ratio_ns_min,"
         "ratio_ns_max,vx_ns_min,vx_ns_max\n");
  double prev_r = 0, prev_v = 0;
  int prev_n = 0, status = 0, busy = 0;
  for (int k = 0; k < nsizes; k++) {
    int n = sizes[k];
    if (progress) fprintf(stderr, "icshadow lut: size %d (exact values on its grid, then the tables)\n", n);
    tables T = {0};
    ics_lut_error ed, ef;
    st = tables_build(&T, n, &ed, &ef);
    if (st != ICS_OK) {
      cli_failure(CMD, "size %d: %s", n, ics_status_str(st));
      tables_free(&T);
      status = 1;
      break;
    }
    cli_spread tr = time_fn(ics_lut_tables_ratio_to_t, &T.view, xr);
    cli_spread tv = time_fn(ics_lut_tables_vx, &T.view, xt);
    busy |= cli_spread_busy(tr) || cli_spread_busy(tv);
    printf("lut,%d,%.3e,%.3e,%.3e,%.3e,%.3e,%.3e,", n, ed.ratio, ed.vx, ed.radii, ef.ratio,
           ef.vx, ef.radii);
    if (prev_n)
      printf("%.3f,%.3f,", order(prev_r, ed.ratio, prev_n, n), order(prev_v, ed.vx, prev_n, n));
    else
      printf(",,");
    printf("%.3g,%.3g,%ld,%.3g,%.3g,%.3g,%.3g\n", tr.median, tv.median, ed.points, tr.min, tr.max,
           tv.min, tv.max);
    fflush(stdout);
    prev_r = ed.ratio;
    prev_v = ed.vx;
    prev_n = n;
    tables_free(&T);
  }
  if (!status) {
    cli_spread tr = time_fn(exact_ratio, NULL, xr), tv = time_fn(exact_vx, NULL, xt);
    busy |= cli_spread_busy(tr) || cli_spread_busy(tv);
    printf("exact,,,,,,,,,,%.3g,%.3g,,%.3g,%.3g,%.3g,%.3g\n", tr.median, tv.median, tr.min, tr.max,
           tv.min, tv.max);
  }
  if (busy) cli_warn_busy(CMD, "*_ns_min vs *_ns_max");
  return cli_stdout_failed(CMD) ? 1 : status;
}

int cmd_lut(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  int size = 0, do_report = 0, progress = isatty(2);
  const char *lang_arg = NULL, *path = NULL, *sizes_arg = NULL;
  const cli_option opts[] = {
      {"--size", .kind = CLI_INT, .dest = &size, .lo = ICS_LUT_MIN_SIZE, .hi = ICS_LUT_MAX_SIZE},
      {"--lang", .kind = CLI_STRING, .dest = &lang_arg},
      {"--output", .alias = "-o", .kind = CLI_FILE, .dest = &path},
      {"--sizes", .kind = CLI_STRING, .dest = &sizes_arg},
      {"--report", .kind = CLI_FLAG, .dest = &do_report},
      {"--progress", .kind = CLI_FLAG, .dest = &progress},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (do_report) {
    if (size || lang_arg || path)
      return cli_error(CMD, "--report takes no --size, --lang or -o (it writes CSV to stdout)");
    int sizes[32], nsizes = 0;
    if (sizes_arg) {
      if (parse_sizes(sizes_arg, sizes, 32, &nsizes) != 0)
        return cli_error(CMD, "--sizes: expected increasing integers in %d..%d, comma-separated "
                         "(at most 32), got '%s'", ICS_LUT_MIN_SIZE, ICS_LUT_MAX_SIZE, sizes_arg);
    } else {
      for (int n = 8; n <= 4096; n *= 2) sizes[nsizes++] = n;
    }
    return report(sizes, nsizes, progress);
  }
  if (sizes_arg) return cli_error(CMD, "--sizes goes with --report");
  if (!size) return cli_error(CMD, "missing --size N");
  if (!lang_arg) return cli_error(CMD, "missing --lang c|glsl|opencl|c-data");
  for (size_t k = 0; k < sizeof langs / sizeof langs[0]; k++)
    if (!strcmp(lang_arg, langs[k].name))
      return write_header(size, langs[k].name, langs[k].lang, path);
  return cli_error(CMD, "unknown language '%s' (c, glsl, opencl or c-data)", lang_arg);
}
