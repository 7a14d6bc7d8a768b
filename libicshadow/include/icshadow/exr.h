/* icshadow/exr.h — OpenEXR input/output of float images (environment maps) through the
 * OpenEXR Core C API (openexr.h, -lOpenEXRCore). Optional component: when the library was
 * built without OpenEXR every function returns ICS_ERR_UNSUPPORTED with a message saying so
 * (ics_exr_available() tells in advance).
 *
 * Files: one single-part scanline image; channels exactly {R, G, B} or {R, G, B, A}, each
 * HALF or FLOAT, no subsampling. The image is the DISPLAY window (the latitude-longitude
 * frame): the data window is placed inside it at its offset, pixels outside the data window
 * are 0 and data outside the display window (overscan) is dropped; pixel positions in
 * messages are display-window positions from its top-left corner. Reading decodes every
 * channel PLANAR into float and interleaves afterwards: OpenEXR 3.1.5's interleaved-RGBA fast
 * path writes half data in reversed channel order (ABGR), measured here (docs/architecture.md
 * "Stack facts measured here"); the planar path has no such special case.
 * Pixels that are NaN, infinite or negative (R, G, B) are rejected with their position.
 * Written files are ZIP-compressed, INCREASING_Y; ics_exr_write's carry envmap = latlong.
 * ics_exr_write_channels writes any set of named float channels (a render with its AOVs, an
 * estimate with its standard error); ics_exr_read_channels reads them back. */
#ifndef ICSHADOW_EXR_H
#define ICSHADOW_EXR_H

#include <stddef.h>

#include "icshadow/image.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ics_exr_type {
  ICS_EXR_HALF = 1, /* 16-bit half float (values above 65504 become inf: rejected on write) */
  ICS_EXR_FLOAT = 2 /* 32-bit float */
} ics_exr_type;

/* 1 when the library was built with OpenEXR, else 0. */
ICS_API int ics_exr_available(void);

/* Reads `path` into a new image *out (3 or 4 channels, as in the file; ics_image_destroy frees
 * it). On failure *out is NULL and, when msg is non-NULL, msg receives a one-line reason
 * (truncated to msg_size):
 * ICS_ERR_IO (cannot open / read / truncated data), ICS_ERR_PARSE (not an EXR, corrupt header
 * or chunk), ICS_ERR_UNSUPPORTED (tiled/deep/multi-part, wrong channel set, UINT or
 * subsampled channels, or no OpenEXR at build time), ICS_ERR_INVALID_ARG (NaN / inf /
 * negative pixel), ICS_ERR_SIZE, ICS_ERR_NOMEM. */
ICS_API ics_status ics_exr_read(const char *path, ics_image **out, char *msg, size_t msg_size);

/* Writes *img (3 or 4 channels) to `path` directly (callers wanting atomic output write a
 * temporary name and rename). ICS_ERR_INVALID_ARG for a NaN / inf / negative pixel, or a value
 * that overflows half when type is ICS_EXR_HALF; ICS_ERR_IO on write errors. The file is
 * written to a temporary file beside `path` (or beside the file a symbolic link names) and
 * renamed onto it once complete: a failure leaves an existing file as it was and no temporary
 * behind. A target that exists and is not a regular file (a device, FIFO, socket, directory) or
 * a symbolic link to nothing is refused with ICS_ERR_IO before anything is opened; it is never
 * written in place or removed (write to a file and copy it there). */
ICS_API ics_status ics_exr_write(const char *path, const ics_image *img, ics_exr_type type,
                                 char *msg, size_t msg_size);

/* Channels per file that ics_exr_write_channels accepts. */
#define ICS_EXR_MAX_CHANNELS 256

/* Pixels (width x height) of the display window, and of the data window, that the readers
 * accept: 2^31 / 24, about 89.5 million (a 3-channel map and its planar copy in 2 GiB; what
 * `icshadow make-env` writes at most). A larger window is refused with ICS_ERR_SIZE before
 * anything is allocated, whatever the file's size. */
#define ICS_EXR_MAX_PIXELS ((long)((1UL << 31) / 24))

/* Named float channels of one image, interleaved. */
typedef struct ics_exr_channels {
  int width, height;        /* 1..ICS_IMAGE_MAX_DIM */
  int count;                /* 1..ICS_EXR_MAX_CHANNELS */
  const char *const *names; /* count distinct names of 1..255 bytes ("R", "light0.V", "Z") */
  const float *data;        /* pixel (i, j) channel c at ((j * width + i) * count + c), row 0 at
                               the top */
  const char *info;         /* NULL, or a text kept in the file's string attribute "icshadow"
                               (what made the image: the renderer writes its summary JSON) */
} ics_exr_channels;

/* Writes *ch to `path` directly, as ics_exr_write does (envmap = latlong only when latlong is
 * non-zero). Values may be negative; ICS_ERR_INVALID_ARG for a NaN or infinite value (its
 * pixel and channel named), one that overflows half when type is ICS_EXR_HALF, an empty or
 * repeated name, or sizes out of range; ICS_ERR_IO on write errors and refused targets (as for
 * ics_exr_write: through a temporary file, renamed once complete); ICS_ERR_UNSUPPORTED without
 * OpenEXR. */
ICS_API ics_status ics_exr_write_channels(const char *path, const ics_exr_channels *ch,
                                          ics_exr_type type, int latlong, char *msg,
                                          size_t msg_size);

/* Reads every channel of `path` (HALF or FLOAT; in the file's order, which is sorted by name)
 * into a new *out (ics_exr_channels_destroy frees it); the image is the display window as in
 * ics_exr_read, info the "icshadow" string attribute (NULL when absent). Errors as for
 * ics_exr_read, except that any channel set is accepted and only NaN and infinite values are
 * refused. */
ICS_API ics_status ics_exr_read_channels(const char *path, ics_exr_channels **out, char *msg,
                                         size_t msg_size);
/* Frees what ics_exr_read_channels made (NULL is fine). */
ICS_API void ics_exr_channels_destroy(ics_exr_channels *ch);
/* The index of the channel called `name`, or -1. */
ICS_API int ics_exr_channel_index(const ics_exr_channels *ch, const char *name);

#ifdef __cplusplus
}
#endif
#endif
