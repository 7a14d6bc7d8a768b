/* cl_context.h — the context behind icshadow/cl.h (cl_context.c): the device and the programs
 * of the primitives, and the bookkeeping of one call (the first failed OpenCL call, the events
 * whose device times it sums). Private to libicshadow_cl. */
#ifndef ICS_CL_CONTEXT_H
#define ICS_CL_CONTEXT_H

#include "cl_device.h"
#include "icshadow/cl.h"

#define ICS_CL_SAT_KERNELS 9    /* rows, columns, slices per accumulation type (f32, f64, ff) */
#define ICS_CL_MINMAX_KERNELS 3 /* leaves, one level, the traversal */

struct ics_cl {
  ics_cl_dev d;
  cl_program sat, mm;
  cl_kernel sat_k[ICS_CL_SAT_KERNELS], mm_k[ICS_CL_MINMAX_KERNELS];
};

/* One call: the first failure (nothing runs after it) and the events launched. */
typedef struct ics_cl_run {
  cl_int err;
  const char *call;
  int nev;
} ics_cl_run;

void ics_cl_run_arg(ics_cl_run *r, cl_kernel k, cl_uint i, size_t size, const void *v);
/* launches k over global size g; with ev, the event goes to ev[r->nev] */
void ics_cl_run_launch(ics_cl_run *r, cl_command_queue q, cl_kernel k, cl_uint dims,
                       const size_t *g, cl_event *ev);
cl_mem ics_cl_run_buffer(ics_cl_run *r, const ics_cl *cl, cl_mem_flags flags, size_t bytes,
                         const void *init, const char *what);
/* waits for and releases the events (their device time added to *ms_device); ICS_OK, or the
 * status and message of the first failure */
ics_status ics_cl_run_finish(ics_cl_run *r, const ics_cl *cl, cl_event *ev, double *ms_device,
                             char *msg, size_t msg_size);

#endif
