/* icshadow/cl.h — libicshadow's primitives on an OpenCL device, libicshadow_cl (a library of its
 * own beside the core: link with -licshadow_cl -licshadow; docs/sat.md and docs/minmax.md "On
 * OpenCL"): a device context, summed-area tables built on it, and 1D min-max mipmaps built and
 * traversed on it. Built with OpenCL (CMake finds it); without it every function returns
 * ICS_ERR_UNSUPPORTED. The device is
 * the cl backend's choice: ICS_CL_DEVICE (an index or a substring of "platform: device"), else
 * the first GPU with fp64, else the first device with fp64 (docs/backend_cl.md). */
#ifndef ICSHADOW_CL_H
#define ICSHADOW_CL_H

#include <stddef.h>

#include "icshadow/api.h"
#include "icshadow/minmax.h"
#include "icshadow/sat.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One thread at a time per ics_cl (and the min-max trees made with it): the kernels it holds
 * take their arguments per call. */
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
 * (profiling), without the transfers. ICS_ERR_SIZE for an empty volume, 2^31 cells or more or
 * buffers over the device's largest allocation; ICS_ERR_INVALID_ARG for NULL pointers or an
 * unknown mode; ICS_ERR_NOMEM when the device is out of memory. Non-finite input is not checked
 * (it propagates into the table as in any float sum). */
ICS_API ics_status ics_cl_sat_build(ics_cl *cl, const float *data, size_t w, size_t h, size_t d,
                                    ics_sat_precision mode, float offset, void *table, float *lo,
                                    double *ms_device, char *msg, size_t msg_size);

/* Min-max trees (icshadow/minmax.h) of `rows` rows of d samples (row r at values + r stride)
 * built on the device, where they stay for ics_cl_minmax_integrate. The same trees as
 * ics_minmax_create (min and max are exact: equal node for node) and the same refusals
 * (ICS_ERR_NAN for a NaN value, ICS_ERR_SIZE), and ICS_ERR_SIZE for trees over the device's
 * largest allocation. *ms_device: the device time of the build. */
typedef struct ics_cl_minmax ics_cl_minmax;
ICS_API ics_status ics_cl_minmax_create(ics_cl *cl, const float *values, size_t rows, size_t d,
                                        size_t stride, ics_cl_minmax **out, double *ms_device,
                                        char *msg, size_t msg_size);
ICS_API void ics_cl_minmax_destroy(ics_cl_minmax *t); /* NULL is allowed */
/* The nodes read back: rows x 2P (min, max) pairs, node k of row r at nodes[2 (r 2P + k)]
 * (P = ics_minmax_leaves of the same rows; what ics_minmax_node returns; slot 0 unused). */
ICS_API ics_status ics_cl_minmax_nodes(const ics_cl_minmax *t, float *nodes);
/* ics_minmax_integrate for nrays rays at once, ray q in row ray_rows[q]: out[q nterms + i] (the
 * same visits, runs and sums, in the CPU's order), nseg[q] (may be NULL) its count of lit runs.
 * The prefix sums (prefix[i ld + k], k = 0..d, as ics_minmax_prefix writes them) are shared by
 * the rows. ICS_ERR_RANGE for a row out of range or gamma_end > d (as ics_minmax_integrate),
 * ICS_ERR_INVALID_ARG for ld < d + 1, NULL pointers or nterms 0, ICS_ERR_INFINITE / ICS_ERR_NAN
 * for bad ray parameters; all checked before anything runs. */
ICS_API ics_status ics_cl_minmax_integrate(ics_cl_minmax *t, const size_t *ray_rows,
                                           const ics_minmax_ray *rays, size_t nrays,
                                           const double *prefix, size_t nterms, size_t ld,
                                           double *out, size_t *nseg, double *ms_device,
                                           char *msg, size_t msg_size);

#ifdef __cplusplus
}
#endif
#endif
