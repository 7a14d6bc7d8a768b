/* output_png.c — sRGB PNG previews through libpng (see icshadow/output.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/output.h"

#ifdef ICS_HAVE_PNG
#include <png.h>
#endif

double ics_output_srgb(double x) {
  if (!(x > 0)) return 0;
  if (x >= 1) return 1;
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
}

int ics_output_png_available(void) {
#ifdef ICS_HAVE_PNG
  return 1;
#else
  return 0;
#endif
}

ics_status ics_output_png(const ics_image *img, const char *path, char *msg, size_t msg_size) {
#ifndef ICS_HAVE_PNG
  (void)img;
  if (msg)
    snprintf(msg, msg_size, "%s: PNG previews need libpng, which was not found when the renderer "
             "was built (install libpng-dev and rebuild)", path);
  return ICS_ERR_UNSUPPORTED;
#else
  size_t w = (size_t)img->width, h = (size_t)img->height;
  unsigned char *rows = malloc(3 * w * h);
  if (!rows) return ICS_ERR_NOMEM;
  for (size_t j = 0; j < h; j++)
    for (size_t i = 0; i < w; i++)
      for (int c = 0; c < 3; c++) {
        float v = img->data[(j * w + i) * (size_t)img->channels + (size_t)c];
        if (isnan(v)) {
          free(rows);
          if (msg) snprintf(msg, msg_size, "%s: NaN at pixel (%zu, %zu)", path, i, j);
          return ICS_ERR_INVALID_ARG;
        }
        rows[(j * w + i) * 3 + (size_t)c] = (unsigned char)lrint(255 * ics_output_srgb(v));
      }
  FILE *f = fopen(path, "wb");
  if (!f) {
    int e = errno;
    free(rows);
    if (msg) snprintf(msg, msg_size, "%s: cannot create: %s", path, strerror(e));
    return ICS_ERR_IO;
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
  png_infop info = png ? png_create_info_struct(png) : NULL;
  png_bytep *rp = malloc(sizeof *rp * h);
  if (!png || !info || !rp) {
    png_destroy_write_struct(&png, &info);
    free(rp);
    free(rows);
    fclose(f);
    return ICS_ERR_NOMEM;
  }
  for (size_t j = 0; j < h; j++) rp[j] = rows + 3 * w * j;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    free(rp);
    free(rows);
    fclose(f);
    if (msg) snprintf(msg, msg_size, "%s: libpng failed to write", path);
    return ICS_ERR_IO;
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  png_write_image(png, rp);
  png_write_end(png, NULL);
  png_destroy_write_struct(&png, &info);
  free(rp);
  free(rows);
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) {
    int e = errno;
    if (msg) snprintf(msg, msg_size, "%s: write failed: %s", path, strerror(e));
    return ICS_ERR_IO;
  }
  return ICS_OK;
#endif
}
