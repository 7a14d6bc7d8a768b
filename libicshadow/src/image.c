/* image.c — float RGB(A) images (see icshadow/image.h). */
#include "icshadow/image.h"

#include <math.h>
#include <stdlib.h>

ics_status ics_image_create(ics_image **out, int width, int height, int channels) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (channels != 3 && channels != 4) return ICS_ERR_INVALID_ARG;
  if (width < 1 || height < 1 || width > ICS_IMAGE_MAX_DIM || height > ICS_IMAGE_MAX_DIM)
    return ICS_ERR_SIZE;
  ics_image *img = malloc(sizeof *img);
  if (!img) return ICS_ERR_NOMEM;
  size_t n = (size_t)width * (size_t)height * (size_t)channels;
  img->data = calloc(n, sizeof *img->data);
  if (!img->data) {
    free(img);
    return ICS_ERR_NOMEM;
  }
  img->width = width;
  img->height = height;
  img->channels = channels;
  *out = img;
  return ICS_OK;
}

void ics_image_destroy(ics_image *img) {
  if (!img) return;
  free(img->data);
  free(img);
}

int ics_image_find_bad(const ics_image *img, int *i, int *j, int *c) {
  for (int y = 0; y < img->height; y++)
    for (int x = 0; x < img->width; x++) {
      const float *p = img->data + ((size_t)y * img->width + x) * img->channels;
      for (int k = 0; k < 3; k++)
        if (!isfinite(p[k]) || p[k] < 0) {
          if (i) *i = x;
          if (j) *j = y;
          if (c) *c = k;
          return 0;
        }
    }
  return 1;
}

ics_status ics_image_diff_rgb(const ics_image *a, const ics_image *b, ics_image_diff *out) {
  if (!a || !b || !out || !a->data || !b->data || a->width != b->width ||
      a->height != b->height || (a->channels != 3 && a->channels != 4) ||
      (b->channels != 3 && b->channels != 4))
    return ICS_ERR_INVALID_ARG;
  ics_image_diff d = {0, 0, 0, 0, 0, 0};
  double se = 0;
  for (int y = 0; y < a->height; y++)
    for (int x = 0; x < a->width; x++) {
      size_t p = (size_t)y * a->width + x;
      for (int c = 0; c < 3; c++) {
        double e = fabs((double)a->data[p * a->channels + c] - b->data[p * b->channels + c]);
        se += e * e;
        if (e > d.max_abs) d.max_abs = e, d.max_x = x, d.max_y = y, d.max_channel = c;
      }
    }
  double mse = se / (3.0 * (double)a->width * a->height);
  d.rmse = sqrt(mse);
  d.psnr = mse > 0 ? 10 * log10(1 / mse) : INFINITY;
  *out = d;
  return ICS_OK;
}
