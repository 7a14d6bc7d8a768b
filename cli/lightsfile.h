/* lightsfile.h — the lights file (JSON: docs/lights_format.md; frames in docs/architecture.md
 * "Frames and file formats") and the lights SPEC strings of the CLI. Writing is the core's
 * ics_light_write_json; reading a file is libicshadow_render's ics_lightsfile_read (jansson: line/column in error
 * messages), present when the CLI was built with the renderer (ICS_HAVE_RENDER). */
#ifndef ICS_CLI_LIGHTSFILE_H
#define ICS_CLI_LIGHTSFILE_H

#include <stddef.h>
#include <stdio.h>

#include "icshadow.h"

/* Reads a lights file. Accepts "tilt_deg": [wx, wy] instead of "mean" (mean = tan w, |w| < 90)
 * and "var": [varx, vary], "angle_deg": a instead of "cov". "color" defaults to [1, 1, 1] and
 * "weight" to 1. Unknown keys and conflicting alternatives (mean + tilt_deg, cov + var or
 * angle_deg, angle_deg without var) are refused. On success *out is malloc'ed (free it) and 0 is returned; otherwise err holds
 * "FILE:LINE:COLUMN: reason" (JSON syntax) or "FILE: lights[i].field: reason" and -1 is
 * returned (-2: jansson missing at build time). */
int lights_read_file(const char *path, ics_light **out, int *n, char *err, size_t errlen);

/* SPEC: lights separated by ':', each "mx,my,varx,vary[,angle_deg[,weight[,r,g,b]]]" (plane
 * mean, variances along the light's axes rotated by angle_deg counter-clockwise from +x;
 * weight default 1, colour default 1,1,1). Empty lights or fields and more than 9 fields are
 * refused. Returns 0 (and a malloc'ed *out) or -1 with err. */
int lights_parse_spec(const char *spec, ics_light **out, int *n, char *err, size_t errlen);

/* FILE if `arg` names an existing file (a directory is refused), else SPEC. Same returns as
 * above. */
int lights_load(const char *arg, ics_light **out, int *n, char *err, size_t errlen);

#endif
