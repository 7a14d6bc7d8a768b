/* cl_context.c — icshadow/cl.h's context: the device (cl_device.c) with the programs of the
 * primitives built once (sat.cl, minmax.cl). Without OpenCL (ICS_HAVE_OPENCL unset) every
 * function of icshadow/cl.h is here and returns ICS_ERR_UNSUPPORTED. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/cl.h"

#ifndef ICS_HAVE_OPENCL
ics_status ics_cl_create(ics_cl **out, char *msg, size_t msg_size) {
  if (out) *out = NULL;
  if (msg) snprintf(msg, msg_size, "libicshadow_cl was built without OpenCL");
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
  if (msg) snprintf(msg, msg_size, "libicshadow_cl was built without OpenCL");
  return ICS_ERR_UNSUPPORTED;
}
ics_status ics_cl_minmax_create(ics_cl *cl, const float *values, size_t rows, size_t d,
                                size_t stride, ics_cl_minmax **out, double *ms_device, char *msg,
                                size_t msg_size) {
  (void)cl, (void)values, (void)rows, (void)d, (void)stride, (void)ms_device;
  if (out) *out = NULL;
  if (msg) snprintf(msg, msg_size, "libicshadow_cl was built without OpenCL");
  return ICS_ERR_UNSUPPORTED;
}
void ics_cl_minmax_destroy(ics_cl_minmax *t) { (void)t; }
ics_status ics_cl_minmax_nodes(const ics_cl_minmax *t, float *nodes) {
  (void)t, (void)nodes;
  return ICS_ERR_UNSUPPORTED;
}
ics_status ics_cl_minmax_integrate(ics_cl_minmax *t, const size_t *ray_rows,
                                   const ics_minmax_ray *rays, size_t nrays, const double *prefix,
                                   size_t nterms, size_t ld, double *out, size_t *nseg,
                                   double *ms_device, char *msg, size_t msg_size) {
  (void)t, (void)ray_rows, (void)rays, (void)nrays, (void)prefix, (void)nterms, (void)ld, (void)out;
  (void)nseg, (void)ms_device;
  if (msg) snprintf(msg, msg_size, "libicshadow_cl was built without OpenCL");
  return ICS_ERR_UNSUPPORTED;
}
#else
#include "cl_context.h"
#include "minmax_cl_source.h" /* ics_minmax_cl_source: libicshadow_cl/src/minmax.cl */
#include "sat_cl_source.h"    /* ics_sat_cl_source: libicshadow_cl/src/sat.cl (cmake/embed_text.cmake) */

static const char *const SAT_KERNELS[ICS_CL_SAT_KERNELS] = {
    "sat_rows_f32", "sat_cols_f32", "sat_slices_f32", "sat_rows_f64", "sat_cols_f64",
    "sat_slices_f64", "sat_rows_ff", "sat_cols_ff", "sat_slices_ff"};
static const char *const MINMAX_KERNELS[ICS_CL_MINMAX_KERNELS] = {"mm_leaves", "mm_level",
                                                                  "mm_integrate"};

void ics_cl_destroy(ics_cl *cl) {
  if (!cl) return;
  for (int i = 0; i < ICS_CL_SAT_KERNELS; i++)
    if (cl->sat_k[i]) clReleaseKernel(cl->sat_k[i]);
  for (int i = 0; i < ICS_CL_MINMAX_KERNELS; i++)
    if (cl->mm_k[i]) clReleaseKernel(cl->mm_k[i]);
  if (cl->sat) clReleaseProgram(cl->sat);
  if (cl->mm) clReleaseProgram(cl->mm);
  ics_cl_dev_close(&cl->d);
  free(cl);
}

ics_status ics_cl_create(ics_cl **out, char *msg, size_t msg_size) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  ics_cl *cl = calloc(1, sizeof *cl);
  if (!cl) return ICS_ERR_NOMEM;
  ics_status st = ics_cl_dev_open(&cl->d, getenv("ICS_CL_DEVICE"), "ICS_CL_DEVICE", msg, msg_size);
  if (st == ICS_OK)
    st = ics_cl_build(&cl->d, ics_sat_cl_source, "sat.cl", ICS_CL_SAT_KERNELS, SAT_KERNELS,
                      &cl->sat, cl->sat_k, msg, msg_size);
  if (st == ICS_OK)
    st = ics_cl_build(&cl->d, ics_minmax_cl_source, "minmax.cl", ICS_CL_MINMAX_KERNELS,
                      MINMAX_KERNELS, &cl->mm, cl->mm_k, msg, msg_size);
  if (st != ICS_OK) {
    ics_cl_destroy(cl);
    return st;
  }
  *out = cl;
  return ICS_OK;
}

const char *ics_cl_device(const ics_cl *cl) { return cl ? cl->d.name : ""; }

void ics_cl_run_arg(ics_cl_run *r, cl_kernel k, cl_uint i, size_t size, const void *v) {
  if (r->err != CL_SUCCESS) return;
  cl_int e = clSetKernelArg(k, i, size, v);
  if (e != CL_SUCCESS) r->err = e, r->call = "clSetKernelArg";
}

void ics_cl_run_launch(ics_cl_run *r, cl_command_queue q, cl_kernel k, cl_uint dims,
                       const size_t *g, cl_event *ev) {
  if (r->err != CL_SUCCESS) return;
  cl_int e = clEnqueueNDRangeKernel(q, k, dims, NULL, g, NULL, 0, NULL, ev);
  if (e != CL_SUCCESS) r->err = e, r->call = "clEnqueueNDRangeKernel";
  else if (ev) r->nev++;
}

cl_mem ics_cl_run_buffer(ics_cl_run *r, const ics_cl *cl, cl_mem_flags flags, size_t bytes,
                         const void *init, const char *what) {
  if (r->err != CL_SUCCESS) return NULL;
  cl_int e;
  cl_mem m = clCreateBuffer(cl->d.ctx, flags | (init ? CL_MEM_COPY_HOST_PTR : 0), bytes ? bytes : 4,
                            (void *)init, &e);
  if (e != CL_SUCCESS) r->err = e, r->call = what;
  return m;
}

ics_status ics_cl_run_finish(ics_cl_run *r, const ics_cl *cl, cl_event *ev, double *ms_device,
                             char *msg, size_t msg_size) {
  if (r->nev) {
    cl_int e = clWaitForEvents((cl_uint)r->nev, ev);
    if (e != CL_SUCCESS && r->err == CL_SUCCESS) r->err = e, r->call = "clWaitForEvents";
  }
  for (int i = 0; i < r->nev; i++) {
    cl_int done = CL_COMPLETE; /* a command that failed on the device: a negative status */
    clGetEventInfo(ev[i], CL_EVENT_COMMAND_EXECUTION_STATUS, sizeof done, &done, NULL);
    if (done < 0 && r->err == CL_SUCCESS) r->err = done, r->call = "a kernel (execution status)";
    if (ms_device && r->err == CL_SUCCESS) *ms_device += ics_cl_event_ms(ev[i]);
    clReleaseEvent(ev[i]);
  }
  r->nev = 0;
  if (r->err == CL_SUCCESS) return ICS_OK;
  if (msg) snprintf(msg, msg_size, "%s on %s: %s", r->call, cl->d.name, ics_cl_err_name(r->err));
  return ics_cl_status(r->err);
}
#endif
