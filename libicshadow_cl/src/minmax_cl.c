/* minmax_cl.c — ics_cl_minmax_* (icshadow/cl.h): 1D min-max mipmaps built and traversed on the
 * device (libicshadow_cl/src/minmax.cl; method: docs/minmax.md "On OpenCL"). The trees stay on the device;
 * a batch of rays is uploaded with the shared prefix sums, one work-item per ray traverses its
 * row's tree, the sums come back. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cl_context.h"

struct ics_cl_minmax {
  ics_cl *cl;
  size_t rows, d, P;
  cl_mem node; /* rows x 2P (min, max) pairs */
};

void ics_cl_minmax_destroy(ics_cl_minmax *t) {
  if (!t) return;
  if (t->node) clReleaseMemObject(t->node);
  free(t);
}

ics_status ics_cl_minmax_create(ics_cl *cl, const float *values, size_t rows, size_t d,
                                size_t stride, ics_cl_minmax **out, double *ms_device, char *msg,
                                size_t msg_size) {
  if (msg && msg_size) msg[0] = 0;
  if (ms_device) *ms_device = 0;
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!cl || !values) return ICS_ERR_INVALID_ARG;
  if (rows == 0 || d == 0 || rows > ICS_MINMAX_MAX_ROWS || d > ICS_MINMAX_MAX_SAMPLES)
    return ICS_ERR_SIZE;
  if (stride < d) return ICS_ERR_INVALID_ARG;
  /* ics_minmax_create's checks: the last row addressable, no NaN (a NaN node would send the
   * traversal below the leaves) */
  if ((rows - 1) > (SIZE_MAX / sizeof(float) - d) / stride) return ICS_ERR_SIZE;
  for (size_t r = 0; r < rows; r++)
    for (size_t g = 0; g < d; g++)
      if (isnan(values[r * stride + g])) return ICS_ERR_NAN;
  size_t P = 1;
  while (P < d) P <<= 1;
  if (rows * 2 * P > ((size_t)1 << 31)) return ICS_ERR_SIZE;
  size_t in_bytes = ((rows - 1) * stride + d) * sizeof(float), node_bytes = rows * 4 * P * sizeof(float);
  if (node_bytes > cl->d.max_alloc || in_bytes > cl->d.max_alloc) {
    if (msg) snprintf(msg, msg_size, "%zu rows of %zu samples: over the device's largest "
                      "allocation (%llu bytes, %s)", rows, d, (unsigned long long)cl->d.max_alloc,
                      cl->d.name);
    return ICS_ERR_SIZE;
  }
  ics_cl_minmax *t = calloc(1, sizeof *t);
  if (!t) return ICS_ERR_NOMEM;
  t->cl = cl, t->rows = rows, t->d = d, t->P = P;
  ics_cl_run r = {CL_SUCCESS, NULL, 0};
  cl_mem in = ics_cl_run_buffer(&r, cl, CL_MEM_READ_ONLY, in_bytes, values, "clCreateBuffer(values)");
  t->node = ics_cl_run_buffer(&r, cl, CL_MEM_READ_WRITE, node_bytes, NULL, "clCreateBuffer(tree)");
  int levels = 0;
  for (size_t f = P >> 1; f >= 1; f >>= 1) levels++;
  cl_event *ev = malloc(sizeof *ev * (size_t)(levels + 1));
  if (!ev) r.err = CL_OUT_OF_HOST_MEMORY, r.call = "malloc(events)";
  cl_ulong st64 = stride;
  cl_uint dd = (cl_uint)d, PP = (cl_uint)P;
  cl_kernel kl = cl->mm_k[0], kv = cl->mm_k[1];
  ics_cl_run_arg(&r, kl, 0, sizeof in, &in);
  ics_cl_run_arg(&r, kl, 1, sizeof st64, &st64);
  ics_cl_run_arg(&r, kl, 2, sizeof dd, &dd);
  ics_cl_run_arg(&r, kl, 3, sizeof PP, &PP);
  ics_cl_run_arg(&r, kl, 4, sizeof t->node, &t->node);
  size_t g[2] = {P, rows};
  if (ev) ics_cl_run_launch(&r, cl->d.q, kl, 2, g, &ev[r.nev]);
  for (size_t f = P >> 1; f >= 1 && ev; f >>= 1) { /* one pass per level, leaves' parents up */
    cl_uint first = (cl_uint)f;
    ics_cl_run_arg(&r, kv, 0, sizeof t->node, &t->node);
    ics_cl_run_arg(&r, kv, 1, sizeof PP, &PP);
    ics_cl_run_arg(&r, kv, 2, sizeof first, &first);
    size_t gl[2] = {f, rows};
    ics_cl_run_launch(&r, cl->d.q, kv, 2, gl, &ev[r.nev]);
  }
  ics_status st = ev ? ics_cl_run_finish(&r, cl, ev, ms_device, msg, msg_size) : ICS_ERR_NOMEM;
  free(ev);
  if (in) clReleaseMemObject(in);
  if (st != ICS_OK) {
    ics_cl_minmax_destroy(t);
    return st;
  }
  *out = t;
  return ICS_OK;
}

ics_status ics_cl_minmax_nodes(const ics_cl_minmax *t, float *nodes) {
  if (!t || !nodes) return ICS_ERR_INVALID_ARG;
  cl_int e = clEnqueueReadBuffer(t->cl->d.q, t->node, CL_TRUE, 0, t->rows * 4 * t->P * sizeof(float),
                                 nodes, 0, NULL, NULL);
  return e == CL_SUCCESS ? ICS_OK : ics_cl_status(e);
}

ics_status ics_cl_minmax_integrate(ics_cl_minmax *t, const size_t *ray_rows,
                                   const ics_minmax_ray *rays, size_t nrays, const double *prefix,
                                   size_t nterms, size_t ld, double *out, size_t *nseg,
                                   double *ms_device, char *msg, size_t msg_size) {
  if (msg && msg_size) msg[0] = 0;
  if (ms_device) *ms_device = 0;
  if (!t || !ray_rows || !rays || !prefix || !out || nterms == 0 || ld < t->d + 1)
    return ICS_ERR_INVALID_ARG;
  if (nrays == 0) return ICS_OK;
  if (nrays > UINT32_MAX || nterms > UINT32_MAX || nterms * ld > ((size_t)1 << 31)) return ICS_ERR_SIZE;
  for (size_t q = 0; q < nrays; q++) { /* ics_minmax_integrate's checks, before anything runs */
    if (ray_rows[q] >= t->rows) return ICS_ERR_RANGE;
    if (isnan(rays[q].beta0) || isnan(rays[q].slope)) return ICS_ERR_NAN;
    if (isinf(rays[q].beta0) || isinf(rays[q].slope)) return ICS_ERR_INFINITE;
    if (rays[q].gamma_end > t->d) return ICS_ERR_RANGE;
  }
  ics_cl *cl = t->cl;
  cl_uint *row = malloc(sizeof *row * nrays), *ge = malloc(sizeof *ge * nrays);
  double *b0 = malloc(sizeof *b0 * nrays), *sl = malloc(sizeof *sl * nrays);
  cl_uint *ns = malloc(sizeof *ns * nrays);
  ics_cl_run r = {CL_SUCCESS, NULL, 0};
  if (!row || !ge || !b0 || !sl || !ns) r.err = CL_OUT_OF_HOST_MEMORY, r.call = "malloc(rays)";
  for (size_t q = 0; q < nrays && r.err == CL_SUCCESS; q++)
    row[q] = (cl_uint)ray_rows[q], ge[q] = (cl_uint)rays[q].gamma_end, b0[q] = rays[q].beta0,
    sl[q] = rays[q].slope;
  cl_mem m_row = ics_cl_run_buffer(&r, cl, CL_MEM_READ_ONLY, sizeof *row * nrays, row, "clCreateBuffer(rays)");
  cl_mem m_b0 = ics_cl_run_buffer(&r, cl, CL_MEM_READ_ONLY, sizeof *b0 * nrays, b0, "clCreateBuffer(rays)");
  cl_mem m_sl = ics_cl_run_buffer(&r, cl, CL_MEM_READ_ONLY, sizeof *sl * nrays, sl, "clCreateBuffer(rays)");
  cl_mem m_ge = ics_cl_run_buffer(&r, cl, CL_MEM_READ_ONLY, sizeof *ge * nrays, ge, "clCreateBuffer(rays)");
  cl_mem m_pre = ics_cl_run_buffer(&r, cl, CL_MEM_READ_ONLY, sizeof *prefix * nterms * ld, prefix,
                                   "clCreateBuffer(prefix sums)");
  cl_mem m_out = ics_cl_run_buffer(&r, cl, CL_MEM_WRITE_ONLY, sizeof *out * nterms * nrays, NULL,
                                   "clCreateBuffer(results)");
  cl_mem m_ns = ics_cl_run_buffer(&r, cl, CL_MEM_WRITE_ONLY, sizeof *ns * nrays, NULL, "clCreateBuffer(results)");
  cl_kernel k = cl->mm_k[2];
  cl_uint PP = (cl_uint)t->P, nr = (cl_uint)nrays, nt = (cl_uint)nterms, lld = (cl_uint)ld;
  const void *args[12] = {&t->node, &PP, &m_row, &m_b0, &m_sl, &m_ge, &nr, &m_pre, &nt, &lld, &m_out, &m_ns};
  const size_t sizes[12] = {sizeof(cl_mem), sizeof PP, sizeof(cl_mem), sizeof(cl_mem), sizeof(cl_mem),
                            sizeof(cl_mem), sizeof nr, sizeof(cl_mem), sizeof nt, sizeof lld,
                            sizeof(cl_mem), sizeof(cl_mem)};
  for (cl_uint i = 0; i < 12; i++) ics_cl_run_arg(&r, k, i, sizes[i], args[i]);
  cl_event ev[1];
  size_t g[1] = {nrays};
  ics_cl_run_launch(&r, cl->d.q, k, 1, g, &ev[0]);
  if (r.err == CL_SUCCESS) {
    cl_int e = clEnqueueReadBuffer(cl->d.q, m_out, CL_TRUE, 0, sizeof *out * nterms * nrays, out, 0,
                                   NULL, NULL);
    if (e == CL_SUCCESS)
      e = clEnqueueReadBuffer(cl->d.q, m_ns, CL_TRUE, 0, sizeof *ns * nrays, ns, 0, NULL, NULL);
    if (e != CL_SUCCESS) r.err = e, r.call = "clEnqueueReadBuffer(results)";
  }
  ics_status st = ics_cl_run_finish(&r, cl, ev, ms_device, msg, msg_size);
  if (st == ICS_OK && nseg)
    for (size_t q = 0; q < nrays; q++) nseg[q] = ns[q];
  cl_mem all[] = {m_row, m_b0, m_sl, m_ge, m_pre, m_out, m_ns};
  for (size_t i = 0; i < sizeof all / sizeof *all; i++)
    if (all[i]) clReleaseMemObject(all[i]);
  free(row), free(ge), free(b0), free(sl), free(ns);
  return st;
}
