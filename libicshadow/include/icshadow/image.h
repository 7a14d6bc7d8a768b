/* icshadow/image.h — a simple float image: W x H pixels, 3 (RGB) or 4 (RGBA) interleaved
 * channels, rows top to bottom (row 0 is the top row, as in OpenEXR and the latitude-longitude
 * layout of docs/architecture.md "Frames and file formats"), linear values. Pure C, no
 * dependencies. An image is a heap object with public fields: ics_image_create (or a reader
 * such as ics_exr_read) makes it, ics_image_destroy frees it. */
#ifndef ICSHADOW_IMAGE_H
#define ICSHADOW_IMAGE_H

#include <stddef.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_IMAGE_MAX_DIM 65536 /* per axis; width * height * channels must fit a size_t */

typedef struct ics_image {
  int width, height;
  int channels; /* 3: R, G, B; 4: R, G, B, A */
  float *data;  /* width * height * channels floats, pixel (i, j) at (j * width + i) * channels */
} ics_image;

/* Creates a zero-filled image. ICS_ERR_SIZE unless 1 <= width, height <= ICS_IMAGE_MAX_DIM;
 * ICS_ERR_INVALID_ARG unless channels is 3 or 4 (or out is NULL); ICS_ERR_NOMEM. On failure
 * *out is NULL. */
ICS_API ics_status ics_image_create(ics_image **out, int width, int height, int channels);
/* Frees the pixels and the image (NULL is fine). */
ICS_API void ics_image_destroy(ics_image *img);

/* First pixel whose R, G or B is NaN, infinite or negative (alpha is not checked):
 * returns 0 and sets *i, *j (column, row) and *c (channel) for it; 1 when all are finite
 * and >= 0. NULL out-pointers are allowed. */
ICS_API int ics_image_find_bad(const ics_image *img, int *i, int *j, int *c);

/* The difference of two images' R, G, B (alpha is not compared), as image comparisons report it. */
typedef struct ics_image_diff {
  double rmse;      /* sqrt(mean over pixels and R, G, B of (a - b)^2) */
  double max_abs;   /* max |a - b| */
  int max_x, max_y; /* where max_abs is first reached (row order) */
  int max_channel;  /* 0, 1, 2 */
  double psnr;      /* 10 log10(1 / mse) in dB (peak value 1); INFINITY for identical images */
} ics_image_diff;

/* Compares a with b (same width and height; 3 or 4 channels each, in double precision).
 * ICS_ERR_INVALID_ARG for a NULL argument, different sizes or another channel count. */
ICS_API ics_status ics_image_diff_rgb(const ics_image *a, const ics_image *b, ics_image_diff *out);

#ifdef __cplusplus
}
#endif
#endif
