/* bench_sat.c — `icshadow bench sat2d|sat3d`: summed-area-table build time per precision mode
 * against this machine's memory-bandwidth floor, measured in the same run by memcpy of the same
 * number of bytes (min over repetitions, interleaved with the SAT builds), plus each mode's
 * box-sum error on data where float fails (1000 + uniform noise in [-1, 1)).
 * `sat2d --chirp-csv FILE` writes the data of Ament et al. 2014 Fig. 4 (paper_figs/ament_fig4.py).
 * Method and results: docs/sat.md. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "icshadow.h"

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t rng_next(uint64_t *s) { /* splitmix64 */
  uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
static double rng_unit(uint64_t *s) { return (double)(rng_next(s) >> 11) * 0x1p-53; }

static void help(FILE *f, int dims) {
  if (dims == 2)
    fprintf(f,
            "usage: icshadow bench sat2d [--size N | --width W --height H] [--modes LIST]\n"
            "                            [--reps R] [--boxes B] [--chirp-csv FILE]\n\n");
  else
    fprintf(f, "usage: icshadow bench sat3d [--size N | --width W --height H --depth D]\n"
               "                            [--modes LIST] [--reps R] [--boxes B]\n\n");
  fprintf(f,
          "Builds a %dD summed-area table of 1000 + uniform noise in [-1, 1) (data where float\n"
          "fails) in each precision mode and prints one CSV line per mode (header first):\n"
          "  time_s        min over R rebuilds of the table (no allocation in the loop)\n"
          "  bytes         bytes touched: input floats read + table written\n"
          "  memcpy_s      min over R memcpy of the same number of bytes (read + write), run\n"
          "                interleaved with the builds: the memory-bandwidth floor\n"
          "  floor_ratio   memcpy_s / time_s (1 = at the floor; goal >= 0.5)\n"
          "  max_rel_err   max |box sum - exact| / |exact| over B random boxes (edge 1..64,\n"
          "                anywhere in the table, exact sums in double) and the whole table\n"
          "  max_bound_frac  max error / documented bound (icshadow/sat.h), <= 1 expected\n\n"
          "  --size N      %s (default %d)\n"
          "  --modes LIST  comma-separated: float,float-offset,compensated,double (default all)\n"
          "  --reps R      repetitions, 1..100 (default %d)\n"
          "  --boxes B     random boxes for the error, 0..100000 (default 256)\n",
          dims, dims == 2 ? "N x N cells" : "N x N x N cells", dims == 2 ? 4096 : 512,
          dims == 2 ? 5 : 3);
  if (dims == 2)
    fprintf(f, "  --chirp-csv FILE  instead of the benchmark: write the chirp-occluder data of\n"
               "                Ament et al. 2014 Fig. 4 (box vs Gaussian filtering) as CSV\n");
  fprintf(f, "Tables larger than 8 GiB in total are refused.\n");
}

static int usage_error(int dims, const char *msg, const char *arg) {
  if (arg)
    fprintf(stderr, "icshadow bench sat%dd: %s '%s'\n", dims, msg, arg);
  else
    fprintf(stderr, "icshadow bench sat%dd: %s\n", dims, msg);
  fprintf(stderr, "(icshadow bench sat%dd --help for usage)\n", dims);
  return 2;
}

/* ---- Ament Fig. 4: chirp occluder ------------------------------------------------------ */
/* A 2D cut (x across, y up toward a directional light straight above) through the paper's
 * 177 x 27 x 64 set-up, refined to W = 708 columns (4 per voxel): the occluder is the slab
 * y in [24, 40) of H = 64 rows with extinction sigma(x) = s0 (1 + cos(2 pi phase(x))) / 2,
 * phase'(x) from 1/96 to 1/6 cycles per column (linear chirp). The receiver is the bottom row.
 * tau(x) = column sum (unfiltered single scattering), box = SAT box sum over [x - 18, x + 18]
 * (9 voxels = 37 columns) x all rows divided by the width, Gaussian = brute-force convolution
 * of tau with the Gaussian of the same variance (sigma = 37 / sqrt(12) columns), +-4 sigma. */
static int chirp_csv(const char *path) {
  const int W = 708, H = 64, y0 = 24, y1 = 40, half = 18;
  const double s0 = 0.25, f0 = 1.0 / 96, f1 = 1.0 / 6;
  float *img = calloc((size_t)W * H, sizeof *img);
  double *tau = malloc((size_t)W * sizeof *tau), *sig = malloc((size_t)W * sizeof *sig);
  if (!img || !tau || !sig) {
    free(img), free(tau), free(sig);
    fprintf(stderr, "icshadow bench sat2d: out of memory\n");
    return 1;
  }
  for (int x = 0; x < W; x++) {
    double xc = x + 0.5, ph = f0 * xc + (f1 - f0) * xc * xc / (2.0 * W);
    sig[x] = s0 * 0.5 * (1.0 + cos(2 * 3.14159265358979323846 * ph));
    for (int y = y0; y < y1; y++) img[(size_t)y * W + x] = (float)sig[x];
  }
  ics_sat2d *sat = NULL;
  ics_status st = ics_sat2d_build(&sat, img, W, H, W, ICS_SAT_DOUBLE);
  if (st != ICS_OK) {
    free(img), free(tau), free(sig);
    fprintf(stderr, "icshadow bench sat2d: %s\n", ics_status_str(st));
    return 1;
  }
  for (int x = 0; x < W; x++) {
    double s = 0;
    for (int y = 0; y < H; y++) s += img[(size_t)y * W + x];
    tau[x] = s;
  }
  cli_output out;
  if (cli_output_open(&out, path)) {
    ics_sat2d_free(sat);
    free(img), free(tau), free(sig);
    return 1;
  }
  const double gs = (2 * half + 1) / sqrt(12.0);
  const int gr = (int)ceil(4 * gs);
  fprintf(out.fp, "x,sigma,tau,T_none,tau_box,T_box,tau_gauss,T_gauss\n");
  for (int x = 0; x < W; x++) {
    double box = 0, g = 0, gw = 0;
    ics_sat2d_box_sum_clamped(sat, x - half, 0, x + half + 1, H, &box);
    box /= 2 * half + 1; /* outside the grid counts as no extinction */
    for (int k = -gr; k <= gr; k++) {
      double wgt = exp(-0.5 * k * k / (gs * gs));
      gw += wgt;
      if (x + k >= 0 && x + k < W) g += wgt * tau[x + k];
    }
    g /= gw;
    fprintf(out.fp, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", (x + 0.5) / 4.0, sig[x],
            tau[x], exp(-tau[x]), box, exp(-box), g, exp(-g));
  }
  ics_sat2d_free(sat);
  free(img), free(tau), free(sig);
  return cli_output_commit(&out) ? 1 : 0;
}

/* ---- benchmark --------------------------------------------------------------------------- */
typedef struct {
  int dims;
  size_t n[3];
  int modes[ICS_SAT_PRECISION_COUNT], nmodes;
  int reps, boxes;
} config;

static int parse_size(int dims, const char *opt, const char *val, size_t *out) {
  int v;
  if (cli_parse_int(val, 1, 1L << 30, &v)) {
    char msg[96];
    snprintf(msg, sizeof msg, "%s must be an integer in 1..1073741824, got", opt);
    return usage_error(dims, msg, val);
  }
  *out = (size_t)v;
  return 0;
}

static int parse_modes(config *c, const char *list) {
  c->nmodes = 0;
  const char *p = list;
  while (1) {
    const char *e = strchr(p, ',');
    size_t len = e ? (size_t)(e - p) : strlen(p);
    char name[32];
    ics_sat_precision m;
    if (len == 0 || len >= sizeof name) return usage_error(c->dims, "bad --modes list", list);
    memcpy(name, p, len);
    name[len] = 0;
    if (ics_sat_precision_parse(name, &m) != ICS_OK)
      return usage_error(c->dims, "unknown precision mode", name);
    for (int i = 0; i < c->nmodes; i++)
      if (c->modes[i] == (int)m) return usage_error(c->dims, "mode given twice", name);
    c->modes[c->nmodes++] = (int)m;
    if (!e) break;
    p = e + 1;
  }
  return 0;
}

/* The exact sum (double) and the sum of |a - m| over [lo, hi) (for the bound). */
static void brute(const float *data, const size_t n[3], const long lo[3], const long hi[3],
                  double m, double *sum, double *abs_sum) {
  double s = 0, a = 0;
  for (long z = lo[2]; z < hi[2]; z++)
    for (long y = lo[1]; y < hi[1]; y++) {
      const float *row = data + ((size_t)z * n[1] + (size_t)y) * n[0];
      for (long x = lo[0]; x < hi[0]; x++) {
        s += row[x];
        a += fabs((double)row[x] - m);
      }
    }
  *sum = s;
  *abs_sum = a;
}

static ics_status build_any(const config *c, const float *data, ics_sat_precision m, void **sat) {
  if (c->dims == 2)
    return ics_sat2d_build((ics_sat2d **)sat, data, c->n[0], c->n[1], c->n[0], m);
  return ics_sat3d_build((ics_sat3d **)sat, data, c->n[0], c->n[1], c->n[2], m);
}
static ics_status rebuild_any(const config *c, const float *data, void *sat) {
  if (c->dims == 2) return ics_sat2d_rebuild(sat, data, c->n[0]);
  return ics_sat3d_rebuild(sat, data);
}
static void free_any(const config *c, void *sat) {
  if (c->dims == 2)
    ics_sat2d_free(sat);
  else
    ics_sat3d_free(sat);
}
static double offset_any(const config *c, void *sat) {
  return c->dims == 2 ? ics_sat2d_offset(sat) : ics_sat3d_offset(sat);
}
static ics_status box_any(const config *c, void *sat, const long lo[3], const long hi[3],
                          double *s) {
  if (c->dims == 2) return ics_sat2d_box_sum(sat, lo[0], lo[1], hi[0], hi[1], s);
  return ics_sat3d_box_sum(sat, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], s);
}

static int run_bench(const config *c) {
  size_t cells = c->n[0] * c->n[1] * c->n[2];
  float *data = malloc(cells * sizeof(float));
  size_t max_out = 0;
  for (int i = 0; i < c->nmodes; i++) {
    size_t b = ics_sat_cell_bytes((ics_sat_precision)c->modes[i]);
    if (b > max_out) max_out = b;
  }
  size_t copy_max = (cells * 4 + cells * max_out) / 2;
  char *src = malloc(copy_max), *dst = malloc(copy_max);
  if (!data || !src || !dst) {
    free(data), free(src), free(dst);
    fprintf(stderr, "icshadow bench sat%dd: out of memory\n", c->dims);
    return 1;
  }
  uint64_t seed = 12345;
  for (size_t i = 0; i < cells; i++) data[i] = (float)(1000.0 + (2.0 * rng_unit(&seed) - 1.0));
  memset(src, 1, copy_max);
  memset(dst, 0, copy_max);
  printf("kind,mode,width,height,depth,reps,time_s,first_build_s,bytes,memcpy_s,floor_ratio,"
         "gbytes_per_s,max_rel_err,max_bound_frac,boxes\n");
  fflush(stdout);
  int rc = 0;
  for (int mi = 0; mi < c->nmodes; mi++) {
    ics_sat_precision m = (ics_sat_precision)c->modes[mi];
    void *sat = NULL;
    double t0 = now_s();
    ics_status st = build_any(c, data, m, &sat);
    double first = now_s() - t0;
    if (st != ICS_OK) {
      fprintf(stderr, "icshadow bench sat%dd: %s: %s\n", c->dims, ics_sat_precision_name(m),
              ics_status_str(st));
      rc = 1;
      continue;
    }
    size_t bytes = cells * 4 + cells * ics_sat_cell_bytes(m);
    size_t copy = bytes / 2;
    double best = INFINITY, best_copy = INFINITY;
    for (int r = 0; r < c->reps; r++) {
      t0 = now_s();
      memcpy(dst, src, copy);
      double tc = now_s() - t0;
      if (tc < best_copy) best_copy = tc;
      t0 = now_s();
      st = rebuild_any(c, data, sat);
      double tb = now_s() - t0;
      if (st != ICS_OK) break;
      if (tb < best) best = tb;
    }
    if (st != ICS_OK) {
      fprintf(stderr, "icshadow bench sat%dd: rebuild: %s\n", c->dims, ics_status_str(st));
      free_any(c, sat);
      rc = 1;
      continue;
    }
    /* error on random boxes (and the whole table) */
    double off = offset_any(c, sat), max_rel = 0, max_frac = 0;
    double factor = ics_sat_error_factor(m, c->dims);
    uint64_t bs = 777;
    for (int b = 0; b <= c->boxes; b++) {
      long lo[3] = {0, 0, 0}, hi[3];
      for (int a = 0; a < 3; a++) {
        long n = (long)c->n[a];
        if (b == c->boxes) { /* whole table */
          hi[a] = n;
          continue;
        }
        long e = 1 + (long)(rng_unit(&bs) * 64);
        if (e > n) e = n;
        lo[a] = (long)(rng_unit(&bs) * (double)(n - e + 1));
        if (lo[a] > n - e) lo[a] = n - e;
        hi[a] = lo[a] + e;
      }
      if (b == c->boxes && cells > ((size_t)1 << 26)) break; /* too slow to brute-force */
      double got, exact, abs_box;
      if (box_any(c, sat, lo, hi, &got) != ICS_OK) continue;
      brute(data, c->n, lo, hi, off, &exact, &abs_box);
      /* P = sum |a - m| over the prefix box [0, hi): estimated as |mean - m| * cells plus the
       * noise (|a - m| <= |1000 - m| + 1 for this data), exact enough for a bound check. */
      double prefix_cells = (double)hi[0] * (double)hi[1] * (double)hi[2];
      double P = (fabs(1000.0 - off) + 1.0) * prefix_cells;
      double nsum = (double)hi[0] + (double)hi[1] + (c->dims == 3 ? (double)hi[2] : 0.0);
      double bound = factor * (nsum + (c->dims == 3 ? 8 : 4)) * P;
      double err = fabs(got - exact);
      if (err / fabs(exact) > max_rel) max_rel = err / fabs(exact);
      if (err / bound > max_frac) max_frac = err / bound;
    }
    printf("sat%dd,%s,%zu,%zu,%zu,%d,%.17g,%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%d\n", c->dims,
           ics_sat_precision_name(m), c->n[0], c->n[1], c->n[2], c->reps, best, first, bytes,
           best_copy, best_copy / best, (double)bytes / best * 1e-9, max_rel, max_frac, c->boxes);
    fflush(stdout);
    free_any(c, sat);
  }
  free(data), free(src), free(dst);
  return rc;
}

static int bench_sat(int argc, char **argv, int dims) {
  if (cli_wants_help(argc, argv)) {
    help(stdout, dims);
    return 0;
  }
  config c;
  memset(&c, 0, sizeof c);
  c.dims = dims;
  size_t def = dims == 2 ? 4096 : 512;
  c.n[0] = c.n[1] = def;
  c.n[2] = dims == 2 ? 1 : def;
  c.reps = dims == 2 ? 5 : 3;
  c.boxes = 256;
  for (int i = 0; i < ICS_SAT_PRECISION_COUNT; i++) c.modes[i] = i;
  c.nmodes = ICS_SAT_PRECISION_COUNT;
  const char *chirp = NULL;
  int have_size = 0, have_dim = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    int is_opt = !strcmp(a, "--size") || !strcmp(a, "--width") || !strcmp(a, "--height") ||
                 !strcmp(a, "--depth") || !strcmp(a, "--modes") || !strcmp(a, "--reps") ||
                 !strcmp(a, "--boxes") || !strcmp(a, "--chirp-csv");
    if (!is_opt) return usage_error(dims, "unknown argument", a);
    if (i + 1 >= argc) return usage_error(dims, "missing value after", a);
    const char *v = argv[++i];
    int r = 0;
    if (!strcmp(a, "--size")) {
      size_t s;
      if ((r = parse_size(dims, a, v, &s))) return r;
      c.n[0] = c.n[1] = s;
      c.n[2] = dims == 3 ? s : 1;
      have_size = 1;
    } else if (!strcmp(a, "--width")) {
      if ((r = parse_size(dims, a, v, &c.n[0]))) return r;
      have_dim = 1;
    } else if (!strcmp(a, "--height")) {
      if ((r = parse_size(dims, a, v, &c.n[1]))) return r;
      have_dim = 1;
    } else if (!strcmp(a, "--depth")) {
      if (dims == 2) return usage_error(dims, "--depth is for sat3d, got", a);
      if ((r = parse_size(dims, a, v, &c.n[2]))) return r;
      have_dim = 1;
    } else if (!strcmp(a, "--modes")) {
      if ((r = parse_modes(&c, v))) return r;
    } else if (!strcmp(a, "--reps")) {
      if (cli_parse_int(v, 1, 100, &c.reps))
        return usage_error(dims, "--reps must be an integer in 1..100, got", v);
    } else if (!strcmp(a, "--boxes")) {
      if (cli_parse_int(v, 0, 100000, &c.boxes))
        return usage_error(dims, "--boxes must be an integer in 0..100000, got", v);
    } else {
      if (dims == 3) return usage_error(dims, "--chirp-csv is for sat2d, got", a);
      chirp = v;
    }
  }
  if (have_size && have_dim) return usage_error(dims, "give either --size or --width/--height", NULL);
  if (chirp) return chirp_csv(chirp);
  /* input + largest table + the two memcpy buffers */
  double cells = (double)c.n[0] * (double)c.n[1] * (double)c.n[2];
  size_t max_out = 0;
  for (int i = 0; i < c.nmodes; i++) {
    size_t b = ics_sat_cell_bytes((ics_sat_precision)c.modes[i]);
    if (b > max_out) max_out = b;
  }
  double total = cells * 4 + cells * (double)max_out + cells * (4.0 + (double)max_out);
  if (cells > 2147483648.0 || total > 8.0 * 1073741824.0) {
    fprintf(stderr,
            "icshadow bench sat%dd: %zu x %zu x %zu cells would allocate %.1f GiB (input, table "
            "and memcpy buffers); the limit is 8 GiB and 2^31 cells\n",
            dims, c.n[0], c.n[1], c.n[2], total / 1073741824.0);
    return 2;
  }
  return run_bench(&c);
}

int bench_sat2d(int argc, char **argv) { return bench_sat(argc, argv, 2); }
int bench_sat3d(int argc, char **argv) { return bench_sat(argc, argv, 3); }
