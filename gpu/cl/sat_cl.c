/* sat_cl.c — icshadow/cl.h: the OpenCL context of the primitives and the summed-area tables
 * built on it (gpu/cl/sat.cl; method: docs/sat.md "On OpenCL"). The data are uploaded, the rows,
 * columns and (3D) slices passes run in one in-order queue, the table is read back. Without
 * OpenCL (ICS_HAVE_OPENCL unset) every function returns ICS_ERR_UNSUPPORTED. */
#define _POSIX_C_SOURCE 200809L
#include "icshadow/cl.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef ICS_HAVE_OPENCL
ics_status ics_cl_create(ics_cl **out, char *msg, size_t msg_size) {
  if (out) *out = NULL;
  if (msg) snprintf(msg, msg_size, "libicshadow_render was built without OpenCL");
  return ICS_ERR_UNSUPPORTED;
}
void ics_cl_destroy(ics_cl *cl) { (void)cl; }
const char *ics_cl_device(const ics_cl *cl) {
  (void)cl;
  return "";
}
ics_status ics_cl_sat_build(ics_cl *cl, const float *data, size_t w, size_t h, size_t d,
                            ics_sat_precision mode, float offset, void *table, float *lo,
                            double *ms_device, char *msg, size_t msg_size) {
  (void)cl, (void)data, (void)w, (void)h, (void)d, (void)mode, (void)offset, (void)table, (void)lo;
  (void)ms_device;
  if (msg) snprintf(msg, msg_size, "libicshadow_render was built without OpenCL");
  return ICS_ERR_UNSUPPORTED;
}
#else
#include "cl_device.h"
#include "sat_cl_source.h" /* ics_sat_cl_source: gpu/cl/sat.cl (cmake/embed_text.cmake) */

/* per accumulation type (f32: float and float offset, f64: double, ff: compensated): rows,
 * columns, slices */
static const char *const SAT_KERNELS[9] = {"sat_rows_f32", "sat_cols_f32", "sat_slices_f32",
                                           "sat_rows_f64", "sat_cols_f64", "sat_slices_f64",
                                           "sat_rows_ff",  "sat_cols_ff",  "sat_slices_ff"};

struct ics_cl {
  ics_cl_dev d;
  cl_program sat;
  cl_kernel k[9];
};

void ics_cl_destroy(ics_cl *cl) {
  if (!cl) return;
  for (int i = 0; i < 9; i++)
    if (cl->k[i]) clReleaseKernel(cl->k[i]);
  if (cl->sat) clReleaseProgram(cl->sat);
  ics_cl_dev_close(&cl->d);
  free(cl);
}

ics_status ics_cl_create(ics_cl **out, char *msg, size_t msg_size) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  ics_cl *cl = calloc(1, sizeof *cl);
  if (!cl) return ICS_ERR_NOMEM;
  ics_status st = ics_cl_dev_open(&cl->d, msg, msg_size);
  if (st == ICS_OK)
    st = ics_cl_build(&cl->d, ics_sat_cl_source, "sat.cl", 9, SAT_KERNELS, &cl->sat, cl->k, msg,
                      msg_size);
  if (st != ICS_OK) {
    ics_cl_destroy(cl);
    return st;
  }
  *out = cl;
  return ICS_OK;
}

const char *ics_cl_device(const ics_cl *cl) { return cl ? cl->d.name : ""; }

/* the run of one build: the first failed call and its code */
typedef struct {
  cl_int err;
  const char *call;
} run_t;

static void arg(run_t *r, cl_kernel k, cl_uint i, size_t size, const void *v) {
  if (r->err != CL_SUCCESS) return;
  cl_int e = clSetKernelArg(k, i, size, v);
  if (e != CL_SUCCESS) r->err = e, r->call = "clSetKernelArg";
}

static void launch(run_t *r, cl_command_queue q, cl_kernel k, cl_uint dims, const size_t *g,
                   cl_event *ev, int *nev) {
  if (r->err != CL_SUCCESS) return;
  cl_int e = clEnqueueNDRangeKernel(q, k, dims, NULL, g, NULL, 0, NULL, &ev[*nev]);
  if (e != CL_SUCCESS) r->err = e, r->call = "clEnqueueNDRangeKernel";
  else (*nev)++;
}

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
      w * h * d > ((size_t)1 << 31)) {
    if (msg) snprintf(msg, msg_size, "%zux%zux%zu cells: expected 1 .. 2^31", w, h, d);
    return ICS_ERR_SIZE;
  }
  size_t n = w * h * d, cell = mode == ICS_SAT_DOUBLE ? sizeof(double) : sizeof(float);
  if (n * cell > cl->d.max_alloc || n * sizeof(float) > cl->d.max_alloc) {
    if (msg) snprintf(msg, msg_size, "a %zu-byte table is over the device's largest allocation "
                      "(%llu bytes, %s)", n * cell, (unsigned long long)cl->d.max_alloc, cl->d.name);
    return ICS_ERR_SIZE;
  }
  int kind = mode == ICS_SAT_DOUBLE ? 1 : mode == ICS_SAT_COMPENSATED ? 2 : 0;
  cl_kernel *k = cl->k + 3 * kind;
  run_t r = {CL_SUCCESS, NULL};
  cl_int e;
  cl_mem in = clCreateBuffer(cl->d.ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(float),
                             (void *)data, &e);
  if (e != CL_SUCCESS) r.err = e, r.call = "clCreateBuffer(data)";
  cl_mem t = NULL, tl = NULL;
  if (r.err == CL_SUCCESS) {
    t = clCreateBuffer(cl->d.ctx, CL_MEM_READ_WRITE, n * cell, NULL, &e);
    if (e != CL_SUCCESS) r.err = e, r.call = "clCreateBuffer(table)";
  }
  if (r.err == CL_SUCCESS && kind == 2) {
    tl = clCreateBuffer(cl->d.ctx, CL_MEM_READ_WRITE, n * sizeof(float), NULL, &e);
    if (e != CL_SUCCESS) r.err = e, r.call = "clCreateBuffer(table)";
  }
  cl_int W = (cl_int)w, H = (cl_int)h, D = (cl_int)d, rows = (cl_int)(h * d), slice = (cl_int)(w * h);
  cl_float m = mode == ICS_SAT_FLOAT_OFFSET ? offset : 0.0f;
  size_t g_rows[1] = {h * d}, g_cols[2] = {w, d}, g_slices[1] = {w * h};
  cl_event ev[3];
  int nev = 0, a = 0;
  /* rows: (in, out[, lo], w, rows[, m]) */
  arg(&r, k[0], (cl_uint)a++, sizeof in, &in);
  arg(&r, k[0], (cl_uint)a++, sizeof t, &t);
  if (kind == 2) arg(&r, k[0], (cl_uint)a++, sizeof tl, &tl);
  arg(&r, k[0], (cl_uint)a++, sizeof W, &W);
  arg(&r, k[0], (cl_uint)a++, sizeof rows, &rows);
  if (kind == 0) arg(&r, k[0], (cl_uint)a++, sizeof m, &m);
  launch(&r, cl->d.q, k[0], 1, g_rows, ev, &nev);
  if (h > 1) { /* columns: (t[, lo], w, h, d) */
    a = 0;
    arg(&r, k[1], (cl_uint)a++, sizeof t, &t);
    if (kind == 2) arg(&r, k[1], (cl_uint)a++, sizeof tl, &tl);
    arg(&r, k[1], (cl_uint)a++, sizeof W, &W);
    arg(&r, k[1], (cl_uint)a++, sizeof H, &H);
    arg(&r, k[1], (cl_uint)a++, sizeof D, &D);
    launch(&r, cl->d.q, k[1], 2, g_cols, ev, &nev);
  }
  if (d > 1) { /* slices: (t[, lo], w h, d) */
    a = 0;
    arg(&r, k[2], (cl_uint)a++, sizeof t, &t);
    if (kind == 2) arg(&r, k[2], (cl_uint)a++, sizeof tl, &tl);
    arg(&r, k[2], (cl_uint)a++, sizeof slice, &slice);
    arg(&r, k[2], (cl_uint)a++, sizeof D, &D);
    launch(&r, cl->d.q, k[2], 1, g_slices, ev, &nev);
  }
  if (r.err == CL_SUCCESS) {
    e = clEnqueueReadBuffer(cl->d.q, t, CL_TRUE, 0, n * cell, table, 0, NULL, NULL);
    if (e == CL_SUCCESS && kind == 2)
      e = clEnqueueReadBuffer(cl->d.q, tl, CL_TRUE, 0, n * sizeof(float), lo, 0, NULL, NULL);
    if (e != CL_SUCCESS) r.err = e, r.call = "clEnqueueReadBuffer(table)";
  }
  if (nev) clWaitForEvents((cl_uint)nev, ev);
  for (int i = 0; i < nev; i++) {
    if (ms_device && r.err == CL_SUCCESS) *ms_device += ics_cl_event_ms(ev[i]);
    clReleaseEvent(ev[i]);
  }
  if (in) clReleaseMemObject(in);
  if (t) clReleaseMemObject(t);
  if (tl) clReleaseMemObject(tl);
  if (r.err != CL_SUCCESS) {
    if (msg) snprintf(msg, msg_size, "%s on %s: %s", r.call, cl->d.name, ics_cl_err_name(r.err));
    return ics_cl_status(r.err);
  }
  return ICS_OK;
}
#endif
