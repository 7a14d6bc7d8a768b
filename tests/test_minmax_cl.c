/* test_minmax_cl.c — 1D min-max mipmaps on an OpenCL device (icshadow/cl.h, libicshadow_cl/src/minmax.cl)
 * against the core's (icshadow/minmax.h): every node of the trees equal, and for random rays
 * (flat and sloped, level with a sample's height, gamma_end anywhere in [0, d], rows with steps,
 * plateaus and +-inf) the integrated sums equal bit for bit and the lit-run counts equal; then
 * the refusals. Row
 * lengths 1, 5, 64, 100 and 1000 (padded and exact powers of two). Exit 77 (skipped) without an
 * OpenCL device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "icshadow/cl.h"
#include "testutil.h"

#define NTERMS 3

static double unit(void) { return (double)(test_rng_u64() >> 11) * 0x1p-53; }

static void check(ics_cl *cl, size_t rows, size_t d) {
  size_t stride = d + 3, nrays = 4000;
  float *v = malloc(sizeof *v * rows * stride);
  double *terms = malloc(sizeof *terms * NTERMS * d), *pre = malloc(sizeof *pre * NTERMS * (d + 1));
  double *out_cpu = malloc(sizeof(double) * NTERMS * nrays), *out_cl = malloc(sizeof(double) * NTERMS * nrays);
  size_t *rr = malloc(sizeof *rr * nrays), *ns = malloc(sizeof *ns * nrays), *seg = malloc(sizeof *seg * (d + 2));
  ics_minmax_ray *rays = malloc(sizeof *rays * nrays);
  if (!v || !terms || !pre || !out_cpu || !out_cl || !rr || !ns || !seg || !rays) exit(2);
  for (size_t r = 0; r < rows; r++) { /* steps of random height with plateaus, some infinities */
    float h = (float)unit();
    for (size_t g = 0; g < stride; g++) {
      if (unit() < 0.2) h = (float)unit();
      double u = unit();
      v[r * stride + g] = u < 0.01 ? INFINITY : u < 0.02 ? -INFINITY : h;
    }
  }
  for (size_t i = 0; i < NTERMS * d; i++) terms[i] = 2 * unit() - 1;
  if (ics_minmax_prefix(terms, NTERMS, d, d, pre, d + 1) != ICS_OK) exit(2);
  ics_minmax *t = NULL;
  ics_cl_minmax *tc = NULL;
  char msg[1024];
  double ms_build = 0, ms_trav = 0;
  CHECK(ics_minmax_create(&t, v, rows, d, stride) == ICS_OK, "CPU tree");
  ics_status st = ics_cl_minmax_create(cl, v, rows, d, stride, &tc, &ms_build, msg, sizeof msg);
  CHECK(st == ICS_OK, "%zu x %zu: %s", rows, d, msg);
  if (st != ICS_OK || !t) exit(1);
  size_t P = ics_minmax_leaves(t), ndiff = 0;
  float *nodes = malloc(sizeof *nodes * rows * 4 * P);
  if (!nodes) exit(2);
  CHECK(ics_cl_minmax_nodes(tc, nodes) == ICS_OK, "nodes read back");
  for (size_t r = 0; r < rows; r++)
    for (size_t k = 1; k < 2 * P; k++) {
      float lo, hi;
      ics_minmax_node(t, r, k, &lo, &hi);
      const float *n = nodes + 2 * (r * 2 * P + k);
      if (memcmp(&lo, &n[0], sizeof lo) || memcmp(&hi, &n[1], sizeof hi)) ndiff++;
    }
  for (size_t q = 0; q < nrays; q++) {
    rr[q] = (size_t)(unit() * (double)rows);
    rays[q].beta0 = unit();
    rays[q].slope = q % 3 == 0 ? 0 : (2 * unit() - 1) / (double)d;
    rays[q].gamma_end = q % 7 == 0 ? d : (size_t)(unit() * (double)(d + 1));
    /* every fifth: level with one of the row's heights (ties: equality is shadow) */
    float h = v[rr[q] * stride + (size_t)(unit() * (double)d)];
    if (q % 5 == 1 && isfinite(h)) rays[q].beta0 = h, rays[q].slope = 0;
  }
  st = ics_cl_minmax_integrate(tc, rr, rays, nrays, pre, NTERMS, d + 1, out_cl, ns, &ms_trav, msg,
                               sizeof msg);
  CHECK(st == ICS_OK, "integrate: %s", msg);
  size_t sdiff = 0, cdiff = 0;
  for (size_t q = 0; q < nrays && st == ICS_OK; q++) {
    size_t nseg = 0;
    ics_minmax_integrate(t, rr[q], &rays[q], pre, NTERMS, d + 1, out_cpu + q * NTERMS);
    ics_minmax_segments(t, rr[q], &rays[q], seg, d / 2 + 1, &nseg, NULL);
    for (int i = 0; i < NTERMS; i++)
      if (memcmp(&out_cpu[q * NTERMS + i], &out_cl[q * NTERMS + i], sizeof(double))) sdiff++;
    if (nseg != ns[q]) cdiff++;
  }
  printf("%4zu rows x %4zu samples (P %4zu): %zu of %zu nodes differ; %zu rays: %zu sums and %zu "
         "run counts differ; device %.3f ms build, %.3f ms traversal\n",
         rows, d, P, ndiff, rows * (2 * P - 1), nrays, sdiff, cdiff, ms_build, ms_trav);
  CHECK(ndiff == 0 && sdiff == 0 && cdiff == 0, "%zu x %zu: nodes %zu, sums %zu, counts %zu differ",
        rows, d, ndiff, sdiff, cdiff);
  /* refusals, before anything runs */
  size_t bad_row = rows;
  ics_minmax_ray bad = {0.5, 0, d + 1}, nan_ray = {NAN, 0, 1};
  CHECK(ics_cl_minmax_integrate(tc, &bad_row, &rays[0], 1, pre, NTERMS, d + 1, out_cl, NULL, NULL,
                                NULL, 0) == ICS_ERR_RANGE, "a row out of range");
  CHECK(ics_cl_minmax_integrate(tc, &rr[0], &bad, 1, pre, NTERMS, d + 1, out_cl, NULL, NULL, NULL,
                                0) == ICS_ERR_RANGE, "gamma_end > d");
  CHECK(ics_cl_minmax_integrate(tc, &rr[0], &nan_ray, 1, pre, NTERMS, d + 1, out_cl, NULL, NULL,
                                NULL, 0) == ICS_ERR_NAN, "a NaN ray");
  CHECK(ics_cl_minmax_integrate(tc, &rr[0], &rays[0], 1, pre, NTERMS, d, out_cl, NULL, NULL, NULL,
                                0) == ICS_ERR_INVALID_ARG, "ld < d + 1");
  ics_minmax_destroy(t);
  ics_cl_minmax_destroy(tc);
  free(v), free(terms), free(pre), free(out_cpu), free(out_cl), free(rr), free(ns), free(seg);
  free(rays), free(nodes);
}

int main(void) {
  ics_cl *cl = NULL;
  char msg[2048];
  if (ics_cl_create(&cl, msg, sizeof msg) != ICS_OK) {
    printf("SKIPPED: no OpenCL device for the primitives: %s\n", msg);
    return 77;
  }
  printf("device: %s\n", ics_cl_device(cl));
  static const size_t sizes[][2] = {{7, 1}, {13, 5}, {37, 64}, {41, 100}, {9, 1000}};
  for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) check(cl, sizes[i][0], sizes[i][1]);
  ics_cl_minmax *tc = NULL;
  float one = 1;
  CHECK(ics_cl_minmax_create(cl, &one, 0, 1, 1, &tc, NULL, msg, sizeof msg) == ICS_ERR_SIZE && !tc,
        "no rows");
  CHECK(ics_cl_minmax_create(cl, &one, 1, 2, 1, &tc, NULL, msg, sizeof msg) == ICS_ERR_INVALID_ARG,
        "stride < d");
  const float with_nan[4] = {0.5f, NAN, 0.25f, 1};
  CHECK(ics_cl_minmax_create(cl, with_nan, 1, 4, 4, &tc, NULL, msg, sizeof msg) == ICS_ERR_NAN && !tc,
        "a NaN sample (the CPU refuses it too)");
  ics_cl_destroy(cl);
  return test_summary("test_minmax_cl");
}
