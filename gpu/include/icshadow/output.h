/* icshadow/output.h — previews of rendered images: 8-bit sRGB PNG (libpng; optional at build
 * time). The float images themselves go to OpenEXR through icshadow/exr.h. Callers wanting
 * atomic files write to a temporary name and rename (the CLI does). */
#ifndef ICSHADOW_OUTPUT_H
#define ICSHADOW_OUTPUT_H

#include <stddef.h>

#include "icshadow/api.h"
#include "icshadow/image.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 1 when libicshadow_render was built with libpng. */
ICS_API int ics_output_png_available(void);

/* Writes img's R, G, B (linear; clamped to [0, 1], then the sRGB transfer function, rounded to
 * 8 bits) as an RGB PNG, row 0 at the top. ICS_ERR_UNSUPPORTED without libpng, ICS_ERR_IO with
 * the reason in msg, ICS_ERR_INVALID_ARG for a NaN pixel. */
ICS_API ics_status ics_output_png(const ics_image *img, const char *path, char *msg,
                                  size_t msg_size);

/* The sRGB encoding of a linear value in [0, 1] (IEC 61966-2-1), exposed for tests. */
ICS_API double ics_output_srgb(double linear);

#ifdef __cplusplus
}
#endif
#endif
