/* icshadow/cl.h — libicshadow's primitives on an OpenCL device (part of the renderer library,
 * docs/sat.md "On OpenCL"): a device context and summed-area tables built on it. Built with
 * OpenCL (CMake finds it); without it every function returns ICS_ERR_UNSUPPORTED. The device is
 * the cl backend's choice: ICS_CL_DEVICE (an index or a substring of "platform: device"), else
 * the first GPU with fp64, else the first device with fp64 (docs/backend_cl.md). */
#ifndef ICSHADOW_CL_H
#define ICSHADOW_CL_H

#include <stddef.h>

#include "icshadow/api.h"
#include "icshadow/sat.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ics_cl ics_cl;

/* Opens the device and builds the programs (*out NULL on failure; msg says why: no platform,
 * no device, no fp64, ICS_CL_DEVICE matching nothing, a build log). */
ICS_API ics_status ics_cl_create(ics_cl **out, char *msg, size_t msg_size);
ICS_API void ics_cl_destroy(ics_cl *cl); /* NULL is allowed */
/* "OpenCL, platform: device" */
ICS_API const char *ics_cl_device(const ics_cl *cl);

/* The inclusive summed-area table of a w x h x d float volume (x fastest, tightly packed; d = 1
 * for a 2D table), in the layout and precision modes of icshadow/sat.h, built on the device and
 * read back into `table` (w h d floats for ICS_SAT_FLOAT, _FLOAT_OFFSET and the high parts of
 * _COMPENSATED, doubles for _DOUBLE) and `lo` (the low parts of _COMPENSATED; NULL otherwise).
 * ICS_SAT_FLOAT_OFFSET subtracts `offset` before summing (the table holds the sums of a - offset;
 * pass ics_sat2d_offset / ics_sat3d_offset of a CPU table of the same data for the CPU's table);
 * the other modes ignore it. The sums are the CPU builder's, in its order: on x86-64 the table
 * equals the CPU's bit for bit. *ms_device (may be NULL) gets the device time of the passes
 * (profiling), without the transfers. ICS_ERR_SIZE for an empty volume, more than 2^31 cells or
 * buffers over the device's largest allocation; ICS_ERR_INVALID_ARG for NULL pointers or an
 * unknown mode; ICS_ERR_NOMEM when the device is out of memory. Non-finite input is not checked
 * (it propagates into the table as in any float sum). */
ICS_API ics_status ics_cl_sat_build(ics_cl *cl, const float *data, size_t w, size_t h, size_t d,
                                    ics_sat_precision mode, float offset, void *table, float *lo,
                                    double *ms_device, char *msg, size_t msg_size);

#ifdef __cplusplus
}
#endif
#endif
