/* lut_tap_text.h — the text of ics_tab_ellipse_tap for the generated LUT headers
 * (lut_tap_text.c), written by lut.c after the radii. Private to the library. */
#ifndef ICS_LUT_TAP_TEXT_H
#define ICS_LUT_TAP_TEXT_H

#include <stdio.h>

/* the C header's version (double, the library's arithmetic) */
void ics_lut_write_tap_c(FILE *f);
/* the float version: GLSL (glsl != 0) or OpenCL C */
void ics_lut_write_tap_gpu(FILE *f, int glsl);

#endif
