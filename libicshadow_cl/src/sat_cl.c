/* sat_cl.c — ics_cl_sat_build (icshadow/cl.h): summed-area tables built on the device
 * (libicshadow_cl/src/sat.cl; method: docs/sat.md "On OpenCL"). The data are uploaded, the rows, columns and
 * (3D) slices passes run in the context's in-order queue, the table is read back. */
#define _POSIX_C_SOURCE 200809L
#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "cl_context.h"

ics_status ics_cl_sat_build(ics_cl *cl, const float *data, size_t w, size_t h, size_t d,
                            ics_sat_precision mode, float offset, void *table, float *lo,
                            double *ms_device, char *msg, size_t msg_size) {
  if (msg && msg_size) msg[0] = 0;
  if (ms_device) *ms_device = 0;
  if (!cl || !data || !table || (mode == ICS_SAT_COMPENSATED && !lo)) return ICS_ERR_INVALID_ARG;
  if (mode != ICS_SAT_FLOAT && mode != ICS_SAT_FLOAT_OFFSET && mode != ICS_SAT_COMPENSATED &&
      mode != ICS_SAT_DOUBLE)
    return ICS_ERR_INVALID_ARG;
  if (!w || !h || !d || w > INT_MAX || h > INT_MAX || d > INT_MAX || w * h > INT_MAX ||
      w * h * d > INT_MAX) { /* the kernels' int counts (rows h d <= cells) */
    if (msg) snprintf(msg, msg_size, "%zux%zux%zu cells: expected 1 .. 2^31 - 1", w, h, d);
    return ICS_ERR_SIZE;
  }
  size_t n = w * h * d, cell = mode == ICS_SAT_DOUBLE ? sizeof(double) : sizeof(float);
  if (n * cell > cl->d.max_alloc) {
    if (msg) snprintf(msg, msg_size, "a %zu-byte table is over the device's largest allocation "
                      "(%llu bytes, %s)", n * cell, (unsigned long long)cl->d.max_alloc, cl->d.name);
    return ICS_ERR_SIZE;
  }
  int kind = mode == ICS_SAT_DOUBLE ? 1 : mode == ICS_SAT_COMPENSATED ? 2 : 0;
  cl_kernel *k = cl->sat_k + 3 * kind;
  ics_cl_run r = {CL_SUCCESS, NULL, 0};
  cl_mem in = ics_cl_run_buffer(&r, cl, CL_MEM_READ_ONLY, n * sizeof(float), data, "clCreateBuffer(data)");
  cl_mem t = ics_cl_run_buffer(&r, cl, CL_MEM_READ_WRITE, n * cell, NULL, "clCreateBuffer(table)");
  cl_mem tl = kind == 2 ? ics_cl_run_buffer(&r, cl, CL_MEM_READ_WRITE, n * sizeof(float), NULL,
                                            "clCreateBuffer(table)")
                        : NULL;
  cl_int W = (cl_int)w, H = (cl_int)h, D = (cl_int)d, rows = (cl_int)(h * d), slice = (cl_int)(w * h);
  cl_float m = mode == ICS_SAT_FLOAT_OFFSET ? offset : 0.0f;
  size_t g_rows[1] = {h * d}, g_cols[2] = {w, d}, g_slices[1] = {w * h};
  cl_event ev[3];
  cl_uint a = 0;
  /* rows: (in, out[, lo], w, rows[, m]) */
  ics_cl_run_arg(&r, k[0], a++, sizeof in, &in);
  ics_cl_run_arg(&r, k[0], a++, sizeof t, &t);
  if (kind == 2) ics_cl_run_arg(&r, k[0], a++, sizeof tl, &tl);
  ics_cl_run_arg(&r, k[0], a++, sizeof W, &W);
  ics_cl_run_arg(&r, k[0], a++, sizeof rows, &rows);
  if (kind == 0) ics_cl_run_arg(&r, k[0], a++, sizeof m, &m);
  ics_cl_run_launch(&r, cl->d.q, k[0], 1, g_rows, &ev[r.nev]);
  if (h > 1) { /* columns: (t[, lo], w, h, d) */
    a = 0;
    ics_cl_run_arg(&r, k[1], a++, sizeof t, &t);
    if (kind == 2) ics_cl_run_arg(&r, k[1], a++, sizeof tl, &tl);
    ics_cl_run_arg(&r, k[1], a++, sizeof W, &W);
    ics_cl_run_arg(&r, k[1], a++, sizeof H, &H);
    ics_cl_run_arg(&r, k[1], a++, sizeof D, &D);
    ics_cl_run_launch(&r, cl->d.q, k[1], 2, g_cols, &ev[r.nev]);
  }
  if (d > 1) { /* slices: (t[, lo], w h, d) */
    a = 0;
    ics_cl_run_arg(&r, k[2], a++, sizeof t, &t);
    if (kind == 2) ics_cl_run_arg(&r, k[2], a++, sizeof tl, &tl);
    ics_cl_run_arg(&r, k[2], a++, sizeof slice, &slice);
    ics_cl_run_arg(&r, k[2], a++, sizeof D, &D);
    ics_cl_run_launch(&r, cl->d.q, k[2], 1, g_slices, &ev[r.nev]);
  }
  if (r.err == CL_SUCCESS) {
    cl_int e = clEnqueueReadBuffer(cl->d.q, t, CL_TRUE, 0, n * cell, table, 0, NULL, NULL);
    if (e == CL_SUCCESS && kind == 2)
      e = clEnqueueReadBuffer(cl->d.q, tl, CL_TRUE, 0, n * sizeof(float), lo, 0, NULL, NULL);
    if (e != CL_SUCCESS) r.err = e, r.call = "clEnqueueReadBuffer(table)";
  }
  ics_status st = ics_cl_run_finish(&r, cl, ev, ms_device, msg, msg_size);
  if (in) clReleaseMemObject(in);
  if (t) clReleaseMemObject(t);
  if (tl) clReleaseMemObject(tl);
  return st;
}
