/* cl_device.h — what libicshadow's OpenCL code shares (cl_device.c): the chosen device with its
 * context and profiling queue, program builds (the log in the message on failure), OpenCL
 * error names, event times and the ics_status of a failed call. Private: compiled into
 * libicshadow_cl and into the renderer's cl backend, exported by neither. */
#ifndef ICS_CL_DEVICE_H
#define ICS_CL_DEVICE_H

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <stddef.h>

#include "cl_loader.h" /* OpenCL loaded on first use: every cl* call through its table */

#include "icshadow/status.h"

typedef struct ics_cl_dev {
  cl_device_id device;
  cl_context ctx;
  cl_command_queue q; /* in order, profiling enabled */
  cl_ulong max_alloc; /* CL_DEVICE_MAX_MEM_ALLOC_SIZE */
  char name[128];     /* "OpenCL, platform: device" */
} ics_cl_dev;

/* "CL_OUT_OF_RESOURCES" etc. */
const char *ics_cl_err_name(cl_int e);
/* 1 when a device can be chosen (`want`, an index or part of a name, or with want NULL the
 * default rule; label names where want came from, "ICS_CL_DEVICE"); else 0 with why. */
int ics_cl_available(const char *want, const char *label, char *why, size_t why_size);
/* Chooses the device as ics_cl_available does and opens its context and queue;
 * ICS_ERR_UNSUPPORTED with the reason (no platform, no device, no fp64, a `want` matching
 * nothing) or ICS_ERR_NOMEM. */
ics_status ics_cl_dev_open(ics_cl_dev *d, const char *want, const char *label, char *msg,
                           size_t msg_size);
void ics_cl_dev_close(ics_cl_dev *d); /* a zeroed or closed one is fine */
/* Builds program source `src` (named `what` in messages) and creates its kernels `names`. On
 * failure *prog and the kernels made so far are left for the caller to release. */
ics_status ics_cl_build(const ics_cl_dev *d, const char *src, const char *what, int nkernels,
                        const char *const *names, cl_program *prog, cl_kernel *kernels,
                        char *msg, size_t msg_size);
/* A finished command's device time (profiling), ms. */
double ics_cl_event_ms(cl_event ev);
/* ICS_ERR_NOMEM for the allocation failures, ICS_ERR_UNSUPPORTED for the rest. */
ics_status ics_cl_status(cl_int e);

#endif
