/* test_sat_cl.c — summed-area tables built on an OpenCL device (icshadow/cl.h, libicshadow_cl/src/sat.cl)
 * equal the core's tables (icshadow/sat.h) bit for bit: every entry of 2D and 3D tables in the
 * four precision modes, on sizes that reach every path of the passes (widths not a multiple of
 * the 4-cell and 2-cell blocks, one row, one column, one slice), on data near 1000 (a ramp: the
 * float modes' worst case) and on signed data over six decades. Then bad arguments. On x86-64
 * the CPU builder is the SSE2 one whose order sat.cl follows; elsewhere the test says so and
 * checks that both tables lie within twice the documented error bound of each other. Exit 77 (skipped) without an OpenCL device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "icshadow/cl.h"
#include "testutil.h"

#if defined(__SSE2__)
#define SAME_ORDER 1
#else
#define SAME_ORDER 0
#endif

static void fill(float *a, size_t n, int kind) {
  for (size_t i = 0; i < n; i++) {
    double u = (double)(test_rng_u64() >> 11) * 0x1p-53;
    a[i] = kind == 0 ? (float)(1000.0 + (2 * u - 1)) : (float)((2 * u - 1) * pow(10.0, 6 * u - 3));
  }
}

/* one table: the device's entries against the CPU's (through ics_sat*_at) */
static void check(ics_cl *cl, size_t w, size_t h, size_t d, ics_sat_precision mode, int kind) {
  size_t n = w * h * d;
  float *data = malloc(n * sizeof *data), *lo = malloc(n * sizeof *lo);
  void *table = malloc(n * sizeof(double));
  if (!data || !lo || !table) {
    fprintf(stderr, "out of memory\n");
    exit(2);
  }
  fill(data, n, kind);
  ics_sat2d *s2 = NULL;
  ics_sat3d *s3 = NULL;
  ics_status st = d == 1 ? ics_sat2d_create(&s2, data, w, h, w, mode)
                         : ics_sat3d_create(&s3, data, w, h, d, mode);
  if (st != ICS_OK) {
    fprintf(stderr, "CPU table: %s\n", ics_status_str(st));
    exit(2);
  }
  double off = d == 1 ? ics_sat2d_offset(s2) : ics_sat3d_offset(s3);
  char msg[1024];
  double ms;
  st = ics_cl_sat_build(cl, data, w, h, d, mode, (float)off, table, lo, &ms, msg, sizeof msg);
  CHECK(st == ICS_OK, "%zux%zux%zu %s: %s", w, h, d, ics_sat_precision_name(mode), msg);
  size_t differ = 0;
  double worst = 0, scale = 0;
  for (size_t z = 0; z < d && st == ICS_OK; z++)
    for (size_t y = 0; y < h; y++)
      for (size_t x = 0; x < w; x++) {
        size_t i = (z * h + y) * w + x;
        double dev = mode == ICS_SAT_DOUBLE        ? ((double *)table)[i]
                     : mode == ICS_SAT_COMPENSATED ? (double)((float *)table)[i] + (double)lo[i]
                                                   : (double)((float *)table)[i];
        dev += off * (double)(x + 1) * (double)(y + 1) * (double)(z + 1);
        double cpu = d == 1 ? ics_sat2d_at(s2, x, y) : ics_sat3d_at(s3, x, y, z);
        if (dev != cpu) differ++;
        if (fabs(dev - cpu) > worst) worst = fabs(dev - cpu);
        if (fabs(cpu) > scale) scale = fabs(cpu);
      }
  printf("%5zu x %4zu x %3zu %-12s %-6s: %zu of %zu entries differ (max %.3g), %.3f ms on the device\n",
         w, h, d, ics_sat_precision_name(mode), kind ? "signed" : "1000", differ, n, worst, ms);
  if (SAME_ORDER)
    CHECK(differ == 0, "%zux%zux%zu %s: %zu entries differ", w, h, d, ics_sat_precision_name(mode),
          differ);
  else /* another order of the same sums: both within the bound of icshadow/sat.h, so within
        * twice it of each other (P <= the largest |entry| summed over the mode's offset) */
    CHECK(worst <= 2 * ics_sat_error_factor(mode, d == 1 ? 2 : 3) * (double)(w + h + d + 8) *
                       (scale + fabs(off) * (double)n),
          "%zux%zux%zu %s: entries differ by %.3g", w, h, d, ics_sat_precision_name(mode), worst);
  ics_sat2d_destroy(s2);
  ics_sat3d_destroy(s3);
  free(data), free(lo), free(table);
}

int main(void) {
  ics_cl *cl = NULL;
  char msg[2048];
  ics_status st = ics_cl_create(&cl, msg, sizeof msg);
  if (st != ICS_OK) {
    printf("SKIPPED: no OpenCL device for the primitives: %s\n", msg);
    return 77;
  }
  printf("device: %s%s\n", ics_cl_device(cl),
         SAME_ORDER ? "" : " (not x86-64: the CPU builder's order differs, bit equality not checked)");
  static const size_t sizes[][3] = {{64, 48, 1}, {67, 33, 1}, {1, 17, 1}, {19, 1, 1}, {513, 9, 1},
                                    {20, 16, 12}, {7, 5, 3}, {5, 1, 4}, {1, 1, 9}};
  for (size_t si = 0; si < sizeof sizes / sizeof *sizes; si++)
    for (int m = 0; m < ICS_SAT_PRECISION_COUNT; m++)
      for (int kind = 0; kind < 2; kind++)
        check(cl, sizes[si][0], sizes[si][1], sizes[si][2], (ics_sat_precision)m, kind);
  float one = 1, out[2];
  CHECK(ics_cl_sat_build(cl, &one, 0, 1, 1, ICS_SAT_FLOAT, 0, out, NULL, NULL, msg, sizeof msg) ==
            ICS_ERR_SIZE, "an empty volume");
  CHECK(ics_cl_sat_build(cl, &one, 1, 1, 1, ICS_SAT_COMPENSATED, 0, out, NULL, NULL, msg,
                         sizeof msg) == ICS_ERR_INVALID_ARG, "compensated without lo");
  CHECK(ics_cl_sat_build(cl, &one, 1, 1, 1, (ics_sat_precision)9, 0, out, NULL, NULL, msg,
                         sizeof msg) == ICS_ERR_INVALID_ARG, "an unknown mode");
  CHECK(ics_cl_sat_build(cl, &one, (size_t)1 << 20, (size_t)1 << 12, 1, ICS_SAT_FLOAT, 0, out,
                         NULL, NULL, msg, sizeof msg) == ICS_ERR_SIZE, "2^32 cells: %s", msg);
  ics_cl_destroy(cl);
  return test_summary("test_sat_cl");
}
