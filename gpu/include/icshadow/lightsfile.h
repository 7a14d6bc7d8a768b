/* icshadow/lightsfile.h — reading the lights file (JSON; docs/lights_format.md), written by
 * `icshadow fit-light` and read by scenes ("lights_file") and the CLI (libicshadow_render: it
 * uses jansson, which gives line and column in syntax errors).
 *
 * {"lights": [{"mean": [mx, my], "cov": [[cxx, cxy], [cxy, cyy]], "color": [r, g, b],
 *  "weight": w}, ...]}. Readers also accept "tilt_deg": [wx, wy] instead of "mean"
 * (mean = tan w, |w| < 90) and "var": [varx, vary] with an optional "angle_deg" instead of
 * "cov"; "color" defaults to [1, 1, 1] and "weight" to 1. Unknown keys and conflicting
 * alternatives (mean + tilt_deg, cov + var or angle_deg, angle_deg without var) are refused. */
#ifndef ICSHADOW_LIGHTSFILE_H
#define ICSHADOW_LIGHTSFILE_H

#include <stddef.h>

#include "icshadow/api.h"
#include "icshadow/light.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_LIGHTSFILE_MAX 4096 /* lights in one file */
#define ICS_LIGHTSFILE_MAX_BYTES (16u << 20) /* bytes of one file (4096 lights take under 2 MiB) */

/* Reads a lights file. On success *out is malloc'ed (free() it) with *n lights. On failure *out
 * is NULL and msg holds "PATH:LINE:COLUMN: reason" (JSON syntax) or "PATH: lights[i].field:
 * reason": ICS_ERR_IO (cannot open, or not a regular file), ICS_ERR_SIZE (more than
 * ICS_LIGHTSFILE_MAX_BYTES), ICS_ERR_PARSE (syntax, shape, unknown or conflicting keys,
 * values out of range), ICS_ERR_NOMEM. */
ICS_API ics_status ics_lightsfile_read(const char *path, ics_light **out, int *n, char *msg,
                                       size_t msg_size);

#ifdef __cplusplus
}
#endif
#endif
