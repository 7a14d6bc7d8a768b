/* bench_sat.c — `icshadow bench sat2d|sat3d`: summed-area-table build time per precision mode
 * against this machine's memory-bandwidth floor, measured in the same run by memcpy of the same
 * number of bytes (min over repetitions, interleaved with the SAT builds), plus each mode's
 * box-sum error on data where float fails (1000 + uniform noise in [-1, 1)).
 * `sat2d --chirp-csv FILE` writes the data of Ament et al. 2014 Fig. 4 (paper_figs/ament_fig4.py).
 * Method and results: docs/sat.md. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_stats.h"
#include "commands.h"
#include "icshadow.h"
#include "icshadow/cl.h"

/* the subcommand, for messages */
static const char *sat_cmd(int dims) { return dims == 2 ? "bench sat2d" : "bench sat3d"; }

static void help(FILE *f, int dims) {
  if (dims == 2)
    fprintf(f,
            "usage: icshadow bench sat2d [--size N | --width W --height H] [--modes LIST]\n"
            "                            [--reps R] [--boxes B] [--chirp-csv FILE]\n\n");
  else
    fprintf(f, "usage: icshadow bench sat3d [--size N | --width W --height H --depth D]\n"
               "                            [--modes LIST] [--reps R] [--boxes B]\n"
               "       icshadow bench sat3d --lights\n\n");
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
          "                (when it has at most 2^26 cells)\n"
          "  max_bound_frac  max error / documented bound (icshadow/sat.h), <= 1 expected;\n"
          "                P = sum of |a - m| over the prefix box, computed exactly (double)\n"
          "  time_median_s, time_max_s  median and max of the R rebuilds (a spread over 30 %%\n"
          "                prints a busy-machine warning)\n\n"
          "  --size N      %s (default %d)\n"
          "  --modes LIST  comma-separated: float,float-offset,compensated,double (default all)\n"
          "  --reps R      repetitions, 1..100 (default %d)\n"
          "  --boxes B     random boxes for the error, 0..100000 (default 256)\n"
          "  --backend L   cpu (default), cl (the table built on the OpenCL device of\n"
          "                icshadow/cl.h) or cpu,cl: side by side per mode; a cl row has kind\n"
          "                sat%dd-cl, time_s the device time of the passes (transfers not\n"
          "                counted: first_build_s has one whole call), its error from its table\n"
          CLI_CL_DEVICE_HELP,
          dims, dims == 2 ? "N x N cells" : "N x N x N cells", dims == 2 ? 4096 : 512,
          dims == 2 ? 9 : 5, dims);
  if (dims == 2)
    fprintf(f, "  --chirp-csv FILE  instead of the benchmark: write the chirp-occluder data of\n"
               "                Ament et al. 2014 Fig. 4 (box vs Gaussian filtering) as CSV\n");
  if (dims == 3)
    fprintf(f, "  --lights      instead: CSAT (directional light, h = 1 and 0.5 voxel) and SSAT\n"
               "                (point light) filtered optical depth on a 64^3 volume against\n"
               "                brute-force shadow-ray marching of the same quantity: error and\n"
               "                time per query side by side (CSV)\n");
  fprintf(f, "Tables larger than 8 GiB in total are refused.\n");
}

/* Flush stdout; on a write error (full disk, closed pipe, /dev/full) say so on stderr and
 * return 0, so the command exits 1 instead of pretending the CSV was written. */
static int stdout_ok(int dims) { return !cli_stdout_failed(sat_cmd(dims)); }

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
    return cli_failure(sat_cmd(2), "out of memory");
  }
  for (int x = 0; x < W; x++) {
    double xc = x + 0.5, ph = f0 * xc + (f1 - f0) * xc * xc / (2.0 * W);
    sig[x] = s0 * 0.5 * (1.0 + cos(2 * ICS_PI * ph));
    for (int y = y0; y < y1; y++) img[(size_t)y * W + x] = (float)sig[x];
  }
  ics_sat2d *sat = NULL;
  ics_status st = ics_sat2d_create(&sat, img, W, H, W, ICS_SAT_DOUBLE);
  if (st != ICS_OK) {
    free(img), free(tau), free(sig);
    return cli_failure(sat_cmd(2), "%s", ics_status_str(st));
  }
  for (int x = 0; x < W; x++) {
    double s = 0;
    for (int y = 0; y < H; y++) s += img[(size_t)y * W + x];
    tau[x] = s;
  }
  cli_output out;
  if (cli_output_open(&out, sat_cmd(2), path)) {
    ics_sat2d_destroy(sat);
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
  ics_sat2d_destroy(sat);
  free(img), free(tau), free(sig);
  if (out.fp == stdout && !stdout_ok(2)) { /* cli_output_commit would fail without a message */
    cli_output_abort(&out);
    return 1;
  }
  return cli_output_commit(&out) ? 1 : 0;
}

/* ---- CSAT / SSAT against brute-force shadow-ray marching (--lights) --------------------- */
/* A 64^3 volume of compactly supported blobs; 200 random points; for each filter half-width U
 * the filtered optical depth from the light-aligned table (one constant-time lookup) and from
 * brute-force marching of the same filtered optical depth (patch rays every 0.5 voxel, step
 * 0.25 voxel, trilinear sigma_t): error and time per query side by side. */
static float *lights_volume(long n) {
  static const double b[4][4] = {
      {32, 30, 36, 14}, {18, 44, 20, 8}, {46, 18, 24, 10}, {30, 34, 12, 6}};
  float *v = malloc(sizeof(float) * (size_t)(n * n * n));
  if (!v) return NULL;
  for (long z = 0; z < n; z++)
    for (long y = 0; y < n; y++)
      for (long x = 0; x < n; x++) {
        double s = 0;
        for (int k = 0; k < 4; k++) {
          double dx = x + 0.5 - b[k][0], dy = y + 0.5 - b[k][1], dz = z + 0.5 - b[k][2];
          double q = 1 - (dx * dx + dy * dy + dz * dz) / (b[k][3] * b[k][3]);
          if (q > 0) s += 0.1 * q * q;
        }
        v[(z * n + y) * n + x] = (float)s;
      }
  return v;
}

static int bench_lights(void) {
  const long N = 64;
  const int NP = 200;
  float *data = lights_volume(N);
  if (!data) return 1;
  ics_volume vol = {data, N, N, N};
  double pts[200][3];
  uint64_t seed = 99;
  for (int i = 0; i < NP; i++)
    for (int a = 0; a < 3; a++) pts[i][a] = 4 + cli_splitmix_unit(&seed) * (N - 8);
  printf("method,table,mode,U,build_s,ns_per_query,bf_ns_per_query,speedup,max_abs_err,"
         "mean_abs_err,mean_tau\n");
  if (!stdout_ok(3)) { /* fail before the brute force runs */
    free(data);
    return 1;
  }
  const double l[3] = {1, 2, 3}, Us[4] = {0, 2, 4, 8};
  const double hs[2] = {1.0, 0.5};
  const ics_sat_precision ms[2] = {ICS_SAT_FLOAT, ICS_SAT_DOUBLE};
  double tau_ref[4][200], bf_ns[4];
  int have_ref = 0;
  for (int hi = 0; hi < 2; hi++)
    for (int mi = 0; mi < 2; mi++) {
      ics_csat *c = NULL;
      double t0 = cli_now_s();
      ics_status st = ics_csat_create(&c, &vol, l, hs[hi], ms[mi]);
      double tb = cli_now_s() - t0;
      if (st != ICS_OK) {
        free(data);
        return cli_failure(sat_cmd(3), "CSAT: %s", ics_status_str(st));
      }
      double ru[3], rv[3], rw[3];
      ics_csat_frame(c, ru, rv, rw, NULL);
      if (!have_ref) { /* brute force once per U (the reference does not depend on the table) */
        for (int ui = 0; ui < 4; ui++) {
          int np = Us[ui] > 0 ? (int)ceil(2 * Us[ui] / 0.5) : 1;
          t0 = cli_now_s();
          for (int i = 0; i < NP; i++)
            ics_volume_tau_directional(&vol, ru, rv, rw, pts[i], Us[ui], np, 0.25,
                                       &tau_ref[ui][i]);
          bf_ns[ui] = (cli_now_s() - t0) / NP * 1e9;
        }
        have_ref = 1;
      }
      for (int ui = 0; ui < 4; ui++) {
        double tq = INFINITY, tau[200];
        for (int rep = 0; rep < 5; rep++) {
          t0 = cli_now_s();
          for (int i = 0; i < NP; i++) ics_csat_tau(c, ICS_CSAT_PLUS_W, pts[i], Us[ui], &tau[i]);
          double t = cli_now_s() - t0;
          if (t < tq) tq = t;
        }
        double emax = 0, esum = 0, tsum = 0;
        for (int i = 0; i < NP; i++) {
          double e = fabs(tau[i] - tau_ref[ui][i]);
          if (e > emax) emax = e;
          esum += e, tsum += tau_ref[ui][i];
        }
        char name[32];
        snprintf(name, sizeof name, "h=%g", hs[hi]);
        double ns = tq / NP * 1e9;
        printf("csat,%s,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", name,
               ics_sat_precision_name(ms[mi]), Us[ui], tb, ns, bf_ns[ui], bf_ns[ui] / ns, emax,
               esum / NP, tsum / NP);
      }
      ics_csat_destroy(c);
    }
  /* SSAT: a point light outside the volume */
  const double lp[3] = {-16, 30, 36}, Uss[3] = {2, 4, 8};
  const size_t grids[2][3] = {{128, 64, 64}, {256, 128, 128}};
  double sref[3][200], sbf_ns[3];
  int nvalid = 0;
  double spts[200][3];
  for (int i = 0; i < NP; i++) {
    double d2 = 0;
    for (int a = 0; a < 3; a++) d2 += (pts[i][a] - lp[a]) * (pts[i][a] - lp[a]);
    if (d2 > 36) memcpy(spts[nvalid++], pts[i], sizeof spts[0]);
  }
  for (int ui = 0; ui < 3; ui++) {
    double t0 = cli_now_s();
    for (int i = 0; i < nvalid; i++) {
      int np = (int)ceil(2 * Uss[ui] / 0.5);
      ics_volume_tau_point(&vol, lp, spts[i], Uss[ui], np, 0.25, &sref[ui][i]);
    }
    sbf_ns[ui] = (cli_now_s() - t0) / nvalid * 1e9;
  }
  for (int gi = 0; gi < 2; gi++)
    for (int mi = 0; mi < 2; mi++) {
      ics_ssat *s = NULL;
      double t0 = cli_now_s();
      ics_status st =
          ics_ssat_create(&s, &vol, lp, grids[gi][0], grids[gi][1], grids[gi][2], ms[mi]);
      double tb = cli_now_s() - t0;
      if (st != ICS_OK) {
        free(data);
        return cli_failure(sat_cmd(3), "SSAT: %s", ics_status_str(st));
      }
      for (int ui = 0; ui < 3; ui++) {
        double tq = INFINITY, tau[200];
        for (int rep = 0; rep < 5; rep++) {
          t0 = cli_now_s();
          for (int i = 0; i < nvalid; i++) ics_ssat_tau(s, spts[i], Uss[ui], &tau[i]);
          double t = cli_now_s() - t0;
          if (t < tq) tq = t;
        }
        double emax = 0, esum = 0, tsum = 0;
        for (int i = 0; i < nvalid; i++) {
          double e = fabs(tau[i] - sref[ui][i]);
          if (e > emax) emax = e;
          esum += e, tsum += sref[ui][i];
        }
        char name[48];
        snprintf(name, sizeof name, "%zux%zux%zu", grids[gi][0], grids[gi][1], grids[gi][2]);
        double ns = tq / nvalid * 1e9;
        printf("ssat,%s,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", name,
               ics_sat_precision_name(ms[mi]), Uss[ui], tb, ns, sbf_ns[ui], sbf_ns[ui] / ns, emax,
               esum / nvalid, tsum / nvalid);
      }
      ics_ssat_destroy(s);
    }
  free(data);
  return stdout_ok(3) ? 0 : 1;
}

/* ---- benchmark --------------------------------------------------------------------------- */
typedef struct {
  int dims;
  size_t n[3];
  int modes[ICS_SAT_PRECISION_COUNT], nmodes;
  int reps, boxes;
  int cpu, cl; /* --backend */
} config;

/* --modes: distinct precision mode names, comma-separated */
static int parse_modes(const char *cmd, const char *opt, const char *list, void *dest) {
  (void)opt;
  config *c = dest;
  c->nmodes = 0;
  const char *p = list;
  while (1) {
    const char *e = strchr(p, ',');
    size_t len = e ? (size_t)(e - p) : strlen(p);
    char name[32];
    ics_sat_precision m;
    if (len == 0 || len >= sizeof name) return cli_error(cmd, "bad --modes list '%s'", list);
    memcpy(name, p, len);
    name[len] = 0;
    if (ics_sat_precision_parse(name, &m) != ICS_OK)
      return cli_error(cmd, "unknown precision mode '%s'", name);
    for (int i = 0; i < c->nmodes; i++)
      if (c->modes[i] == (int)m) return cli_error(cmd, "mode given twice '%s'", name);
    c->modes[c->nmodes++] = (int)m;
    if (!e) break;
    p = e + 1;
  }
  return 0;
}

/* P of the error bound for every prefix box: pre[(z * h + y) * w + x] = sum of |a - m| over
 * [0, x] x [0, y] x [0, z], in double, by three plain prefix passes (independent of sat.c). */
static void abs_prefix(const float *data, const size_t n[3], double m, double *pre) {
  size_t w = n[0], h = n[1], d = n[2];
  for (size_t r = 0; r < h * d; r++) {
    double acc = 0;
    for (size_t x = 0; x < w; x++) pre[r * w + x] = acc += fabs((double)data[r * w + x] - m);
  }
  for (size_t z = 0; z < d; z++)
    for (size_t y = 1; y < h; y++)
      for (size_t x = 0; x < w; x++) pre[(z * h + y) * w + x] += pre[(z * h + y - 1) * w + x];
  for (size_t z = 1; z < d; z++)
    for (size_t i = 0; i < h * w; i++) pre[z * h * w + i] += pre[(z - 1) * h * w + i];
}

/* The exact sum (double) and the sum of |a - m| over [lo, hi). */
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
    return ics_sat2d_create((ics_sat2d **)sat, data, c->n[0], c->n[1], c->n[0], m);
  return ics_sat3d_create((ics_sat3d **)sat, data, c->n[0], c->n[1], c->n[2], m);
}
static ics_status rebuild_any(const config *c, const float *data, void *sat) {
  if (c->dims == 2) return ics_sat2d_rebuild(sat, data, c->n[0]);
  return ics_sat3d_rebuild(sat, data);
}
static void free_any(const config *c, void *sat) {
  if (c->dims == 2)
    ics_sat2d_destroy(sat);
  else
    ics_sat3d_destroy(sat);
}
static double offset_any(const config *c, void *sat) {
  return c->dims == 2 ? ics_sat2d_offset(sat) : ics_sat3d_offset(sat);
}
static ics_status box_any(const config *c, void *sat, const long lo[3], const long hi[3],
                          double *s) {
  if (c->dims == 2) return ics_sat2d_box_sum(sat, lo[0], lo[1], hi[0], hi[1], s);
  return ics_sat3d_box_sum(sat, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], s);
}

/* A table's box sum: the CPU table, or the entries of a table read back from the device. */
typedef struct {
  const config *c;
  void *sat;          /* CPU */
  const void *table;  /* device: floats or doubles */
  const float *lo;    /* device, compensated */
  ics_sat_precision mode;
  double off;
} table_ref;

static double raw_entry(const table_ref *t, long x, long y, long z) {
  if (x < 0 || y < 0 || z < 0) return 0.0;
  size_t i = ((size_t)z * t->c->n[1] + (size_t)y) * t->c->n[0] + (size_t)x;
  if (t->mode == ICS_SAT_DOUBLE) return ((const double *)t->table)[i];
  double v = ((const float *)t->table)[i];
  return t->mode == ICS_SAT_COMPENSATED ? v + (double)t->lo[i] : v;
}

static ics_status box_ref(const table_ref *t, const long lo[3], const long hi[3], double *s) {
  if (t->sat) return box_any(t->c, t->sat, lo, hi, s);
  double v = 0;
  for (int k = 0; k < 8; k++) {
    long x = k & 1 ? lo[0] - 1 : hi[0] - 1, y = k & 2 ? lo[1] - 1 : hi[1] - 1,
         z = k & 4 ? lo[2] - 1 : hi[2] - 1;
    double sign = ((k & 1) ^ (k >> 1 & 1) ^ (k >> 2 & 1)) ? -1.0 : 1.0;
    if (t->c->dims == 2 && (k & 4)) continue; /* no z corners in 2D (z0 - 1 < 0 anyway) */
    v += sign * raw_entry(t, x, y, z);
  }
  *s = v + t->off * (double)(hi[0] - lo[0]) * (double)(hi[1] - lo[1]) * (double)(hi[2] - lo[2]);
  return ICS_OK;
}

/* max relative error and max error / bound over the random boxes and the whole table */
static void measure_error(const table_ref *t, const float *data, double *pre, double *max_rel,
                          double *max_frac) {
  const config *c = t->c;
  double factor = ics_sat_error_factor(t->mode, c->dims);
  size_t cells = c->n[0] * c->n[1] * c->n[2];
  *max_rel = *max_frac = 0;
  abs_prefix(data, c->n, t->off, pre);
  uint64_t bs = 777;
  for (int b = 0; b <= c->boxes; b++) {
    long lo[3] = {0, 0, 0}, hi[3];
    for (int a = 0; a < 3; a++) {
      long n = (long)c->n[a];
      if (b == c->boxes) { /* whole table */
        hi[a] = n;
        continue;
      }
      long e = 1 + (long)(cli_splitmix_unit(&bs) * 64);
      if (e > n) e = n;
      lo[a] = (long)(cli_splitmix_unit(&bs) * (double)(n - e + 1));
      if (lo[a] > n - e) lo[a] = n - e;
      hi[a] = lo[a] + e;
    }
    if (b == c->boxes && cells > ((size_t)1 << 26)) break; /* too slow to brute-force */
    double got, exact, abs_box;
    if (box_ref(t, lo, hi, &got) != ICS_OK) continue;
    brute(data, c->n, lo, hi, t->off, &exact, &abs_box);
    /* P = sum |a - m| over the prefix box [0, hi), exact up to double rounding */
    double P = pre[((size_t)(hi[2] - 1) * c->n[1] + (size_t)(hi[1] - 1)) * c->n[0] +
                   (size_t)(hi[0] - 1)];
    double nsum = (double)hi[0] + (double)hi[1] + (c->dims == 3 ? (double)hi[2] : 0.0);
    double bound = factor * (nsum + (c->dims == 3 ? 8 : 4)) * P;
    double err = fabs(got - exact);
    if (err / fabs(exact) > *max_rel) *max_rel = err / fabs(exact);
    if (err / bound > *max_frac) *max_frac = err / bound;
  }
}

/* The table of mode m built on the device: the first call (whole, wall clock), then R builds
 * (device time of the passes) interleaved with the memcpy floor, its error, one CSV row. */
static int cl_row(const config *c, ics_cl *cl, ics_sat_precision m, float off, const float *data,
                  void *table, float *lo, const char *src, char *dst, size_t copy, size_t bytes,
                  double *pre, int *busy) {
  char msg[1024];
  double ms, t0 = cli_now_s();
  ics_status st = ics_cl_sat_build(cl, data, c->n[0], c->n[1], c->n[2], m, off, table, lo, &ms,
                                   msg, sizeof msg);
  double first = cli_now_s() - t0, best_copy = INFINITY, tb[100];
  int nb = 0;
  for (int r = 0; r < c->reps && st == ICS_OK; r++) {
    t0 = cli_now_s();
    memcpy(dst, src, copy);
    double tc = cli_now_s() - t0;
    if (tc < best_copy) best_copy = tc;
    st = ics_cl_sat_build(cl, data, c->n[0], c->n[1], c->n[2], m, off, table, lo, &ms, msg,
                          sizeof msg);
    if (st == ICS_OK) tb[nb++] = 1e-3 * ms;
  }
  if (st != ICS_OK)
    return cli_status_error(sat_cmd(c->dims), st, "--backend cl, %s: %s", ics_sat_precision_name(m), msg);
  cli_spread sp = cli_spread_of(tb, nb);
  double best = sp.min;
  if (cli_spread_busy(sp)) *busy = 1;
  double max_rel, max_frac;
  table_ref tr = {c, NULL, table, lo, m, m == ICS_SAT_FLOAT_OFFSET ? (double)off : 0.0};
  measure_error(&tr, data, pre, &max_rel, &max_frac);
  printf("sat%dd-cl,%s,%zu,%zu,%zu,%d,%.17g,%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%.17g\n",
         c->dims, ics_sat_precision_name(m), c->n[0], c->n[1], c->n[2], c->reps, best, first, bytes,
         best_copy, best_copy / best, (double)bytes / best * 1e-9, max_rel, max_frac, c->boxes,
         sp.median, sp.max);
  return 0;
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
  double *pre = malloc(cells * sizeof(double)); /* P of the bound, per prefix box */
  if (!data || !src || !dst || !pre) {
    free(data), free(src), free(dst), free(pre);
    return cli_failure(sat_cmd(c->dims), "out of memory");
  }
  uint64_t seed = 12345;
  for (size_t i = 0; i < cells; i++)
    data[i] = (float)(1000.0 + (2.0 * cli_splitmix_unit(&seed) - 1.0));
  memset(src, 1, copy_max);
  memset(dst, 0, copy_max);
  ics_cl *cl = NULL;
  void *cltab = NULL;
  float *cllo = NULL;
  if (c->cl) {
    char msg[2048];
    if (ics_cl_create(&cl, msg, sizeof msg) != ICS_OK) {
      free(data), free(src), free(dst), free(pre);
      return cli_error(sat_cmd(c->dims), "--backend cl: %s", msg);
    }
    cltab = malloc(cells * sizeof(double));
    cllo = malloc(cells * sizeof(float));
    if (!cltab || !cllo) {
      ics_cl_destroy(cl), free(cltab), free(cllo);
      free(data), free(src), free(dst), free(pre);
      return cli_failure(sat_cmd(c->dims), "out of memory");
    }
  }
  printf("kind,mode,width,height,depth,reps,time_s,first_build_s,bytes,memcpy_s,floor_ratio,"
         "gbytes_per_s,max_rel_err,max_bound_frac,boxes,time_median_s,time_max_s\n");
  int header_ok = stdout_ok(c->dims), rc = header_ok ? 0 : 1, busy = 0;
  for (int mi = 0; mi < c->nmodes && header_ok; mi++) {
    ics_sat_precision m = (ics_sat_precision)c->modes[mi];
    void *sat = NULL;
    double t0 = cli_now_s();
    ics_status st = build_any(c, data, m, &sat);
    double first = cli_now_s() - t0;
    if (st != ICS_OK) {
      cli_failure(sat_cmd(c->dims), "%s: %s", ics_sat_precision_name(m), ics_status_str(st));
      rc = 1;
      continue;
    }
    size_t bytes = cells * 4 + cells * ics_sat_cell_bytes(m);
    size_t copy = bytes / 2;
    double best_copy = INFINITY, tb[100];
    int nb = 0;
    for (int r = 0; r < (c->cpu ? c->reps : 0); r++) {
      t0 = cli_now_s();
      memcpy(dst, src, copy);
      double tc = cli_now_s() - t0;
      if (tc < best_copy) best_copy = tc;
      t0 = cli_now_s();
      st = rebuild_any(c, data, sat);
      if (st != ICS_OK) break;
      tb[nb++] = cli_now_s() - t0;
    }
    if (st != ICS_OK) {
      cli_failure(sat_cmd(c->dims), "rebuild: %s", ics_status_str(st));
      free_any(c, sat);
      rc = 1;
      continue;
    }
    /* error on random boxes (and the whole table) */
    double off = offset_any(c, sat), max_rel, max_frac;
    if (c->cpu) {
      table_ref tr = {c, sat, NULL, NULL, m, off};
      measure_error(&tr, data, pre, &max_rel, &max_frac);
      cli_spread sp = cli_spread_of(tb, nb);
      double best = sp.min;
      if (cli_spread_busy(sp)) busy = 1;
      printf("sat%dd,%s,%zu,%zu,%zu,%d,%.17g,%.17g,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%.17g\n",
             c->dims, ics_sat_precision_name(m), c->n[0], c->n[1], c->n[2], c->reps, best, first,
             bytes, best_copy, best_copy / best, (double)bytes / best * 1e-9, max_rel, max_frac,
             c->boxes, sp.median, sp.max);
    }
    if (c->cl && cl_row(c, cl, m, (float)off, data, cltab, cllo, src, dst, copy, bytes, pre, &busy)) {
      free_any(c, sat);
      rc = 1;
      break;
    }
    free_any(c, sat);
    if (!stdout_ok(c->dims)) {
      rc = 1;
      break;
    }
  }
  ics_cl_destroy(cl);
  free(cltab), free(cllo);
  free(data), free(src), free(dst), free(pre);
  if (busy) cli_warn_busy(sat_cmd(c->dims), "time_s vs time_max_s");
  return rc;
}

static int bench_sat(int argc, char **argv, int dims) {
  if (cli_wants_help(argc, argv)) {
    help(stdout, dims);
    return stdout_ok(dims) ? 0 : 1;
  }
  config c;
  memset(&c, 0, sizeof c);
  c.dims = dims;
  size_t def = dims == 2 ? 4096 : 512;
  c.n[0] = c.n[1] = def;
  c.n[2] = dims == 2 ? 1 : def;
  c.reps = dims == 2 ? 9 : 5;
  c.boxes = 256;
  for (int i = 0; i < ICS_SAT_PRECISION_COUNT; i++) c.modes[i] = i;
  c.nmodes = ICS_SAT_PRECISION_COUNT;
  const char *cmd = sat_cmd(dims), *chirp = NULL, *backend = "cpu";
  int size = 0, width = 0, height = 0, depth = 0, lights = 0;
  int given_size = 0, given_width = 0, given_height = 0, given_depth = 0, given_chirp = 0;
  const cli_option opts[] = {
      {"--size", .kind = CLI_INT, .dest = &size, .lo = 1, .hi = 1L << 30, .given = &given_size},
      {"--width", .kind = CLI_INT, .dest = &width, .lo = 1, .hi = 1L << 30, .given = &given_width},
      {"--height", .kind = CLI_INT, .dest = &height, .lo = 1, .hi = 1L << 30,
       .given = &given_height},
      {"--depth", .kind = CLI_INT, .dest = &depth, .lo = 1, .hi = 1L << 30, .given = &given_depth},
      {"--modes", .kind = CLI_CALL, .dest = &c, .parse = parse_modes},
      {"--reps", .kind = CLI_INT, .dest = &c.reps, .lo = 1, .hi = 100},
      {"--boxes", .kind = CLI_INT, .dest = &c.boxes, .lo = 0, .hi = 100000},
      {"--chirp-csv", .kind = CLI_FILE, .dest = &chirp, .given = &given_chirp},
      {"--lights", .kind = CLI_FLAG, .dest = &lights},
      {"--backend", .kind = CLI_STRING, .dest = &backend},
      {"--cl-device", .kind = CLI_CALL, .parse = cli_parse_cl_device},
  };
  int rc = cli_parse_options(cmd, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (!strcmp(backend, "cpu")) c.cpu = 1;
  else if (!strcmp(backend, "cl")) c.cl = 1;
  else if (!strcmp(backend, "cpu,cl") || !strcmp(backend, "cl,cpu")) c.cpu = c.cl = 1;
  else return cli_error(cmd, "--backend: expected cpu, cl or cpu,cl, got '%s'", backend);
  if (dims == 2 && lights) return cli_error(cmd, "--lights is for sat3d");
  if (dims == 2 && given_depth) return cli_error(cmd, "--depth is for sat3d");
  if (dims == 3 && given_chirp) return cli_error(cmd, "--chirp-csv is for sat2d");
  if (given_size && (given_width || given_height || given_depth))
    return cli_error(cmd, "give either --size or --width/--height");
  if (given_size) {
    c.n[0] = c.n[1] = (size_t)size;
    c.n[2] = dims == 3 ? (size_t)size : 1;
  }
  if (given_width) c.n[0] = (size_t)width;
  if (given_height) c.n[1] = (size_t)height;
  if (given_depth) c.n[2] = (size_t)depth;
  if (chirp) return chirp_csv(chirp);
  if (lights) return bench_lights();
  /* input + largest table + the two memcpy buffers */
  double cells = (double)c.n[0] * (double)c.n[1] * (double)c.n[2];
  size_t max_out = 0;
  for (int i = 0; i < c.nmodes; i++) {
    size_t b = ics_sat_cell_bytes((ics_sat_precision)c.modes[i]);
    if (b > max_out) max_out = b;
  }
  double total = cells * 4 + cells * (double)max_out + cells * (4.0 + (double)max_out) + cells * 8 +
                 (c.cl ? cells * 12 : 0); /* the device table read back */
  if (cells > 2147483648.0 || total > 8.0 * 1073741824.0)
    return cli_error(cmd, "%zu x %zu x %zu cells would allocate %.1f GiB (input, table, memcpy "
                     "buffers and the bound's prefix sums); the limit is 8 GiB and 2^31 cells",
                     c.n[0], c.n[1], c.n[2], total / 1073741824.0);
  return run_bench(&c);
}

int bench_sat2d(int argc, char **argv) { return bench_sat(argc, argv, 2); }
int bench_sat3d(int argc, char **argv) { return bench_sat(argc, argv, 3); }
