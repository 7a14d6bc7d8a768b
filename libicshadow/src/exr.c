/* exr.c — OpenEXR I/O through the Core C API (see icshadow/exr.h).
 *
 * Built against OpenEXR only when CMake found it (ICS_HAVE_OPENEXR); otherwise every entry
 * point returns ICS_ERR_UNSUPPORTED. Reading: exr_start_read parses the header; each scanline
 * chunk is decoded with its own decode pipeline into PLANAR float buffers (one per channel,
 * user_pixel_stride 4 bytes), then interleaved into the ics_image. Writing (ics_exr_write_channels;
 * ics_exr_write is R, G, B[, A] through it): exr_start_write, one part, required attributes,
 * channels added in reverse order (the library sorts them by name), header, then one encode
 * pipeline per chunk reading planar float buffers (the library converts to half when asked),
 * into a temporary file beside the target that is renamed onto it once complete (write_target:
 * a failure leaves the previous file as it was; devices, FIFOs and links to nothing are refused,
 * never written in place or removed). Error messages of the library are captured per thread
 * (custom error_handler_fn) instead of printed. */
#define _XOPEN_SOURCE 700
#include "icshadow/exr.h"
#include "icshadow/input_file.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void set_msg(char *msg, size_t n, const char *fmt, ...) {
  if (!msg || !n) return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, n, fmt, ap);
  va_end(ap);
}

static const char *const chan_names[4] = {"R", "G", "B", "A"};

/* the index of `name` among n names, or -1 */
static int find_name(const char *const *names, int n, const char *name) {
  for (int k = 0; k < n; k++)
    if (!strcmp(names[k], name)) return k;
  return -1;
}

#ifndef ICS_HAVE_OPENEXR

int ics_exr_available(void) { return 0; }

ics_status ics_exr_read(const char *path, ics_image **out, char *msg, size_t msg_size) {
  if (out) *out = NULL;
  set_msg(msg, msg_size, "%s: cannot read OpenEXR: OpenEXR was not found when libicshadow was "
          "built (install libopenexr-dev and rebuild)", path ? path : "(null)");
  return ICS_ERR_UNSUPPORTED;
}

ics_status ics_exr_read_channels(const char *path, ics_exr_channels **out, char *msg,
                                 size_t msg_size) {
  if (out) *out = NULL;
  set_msg(msg, msg_size, "%s: cannot read OpenEXR: OpenEXR was not found when libicshadow was "
          "built (install libopenexr-dev and rebuild)", path ? path : "(null)");
  return ICS_ERR_UNSUPPORTED;
}

ics_status ics_exr_write_channels(const char *path, const ics_exr_channels *ch, ics_exr_type type,
                                  int latlong, char *msg, size_t msg_size) {
  (void)ch;
  (void)type;
  (void)latlong;
  set_msg(msg, msg_size, "%s: cannot write OpenEXR: OpenEXR was not found when libicshadow was "
          "built (install libopenexr-dev and rebuild)", path ? path : "(null)");
  return ICS_ERR_UNSUPPORTED;
}

#else

#include <openexr.h>

int ics_exr_available(void) { return 1; }

/* the last message of the OpenEXR library on this thread */
static _Thread_local char exr_lastmsg[512];

static void exr_error_cb(exr_const_context_t ctxt, exr_result_t code, const char *text) {
  (void)ctxt;
  snprintf(exr_lastmsg, sizeof exr_lastmsg, "%s (%s)", text ? text : "",
           exr_get_error_code_as_string(code));
}

static ics_status map_err(exr_result_t rv) {
  switch (rv) {
    case EXR_ERR_OUT_OF_MEMORY: return ICS_ERR_NOMEM;
    case EXR_ERR_FILE_ACCESS:
    case EXR_ERR_READ_IO:
    case EXR_ERR_WRITE_IO: return ICS_ERR_IO;
    case EXR_ERR_FEATURE_NOT_IMPLEMENTED: return ICS_ERR_UNSUPPORTED;
    default: return ICS_ERR_PARSE;
  }
}

static int chan_index(const char *name) { return find_name(chan_names, 4, name); }

/* What read_file returns: the display window's pixels, interleaved, `n` channels. */
typedef struct {
  long W, H;
  int n;
  char **names; /* n names; one block with the strings after the pointers */
  float *data;
  char *info;   /* the "icshadow" string attribute, or NULL */
} exr_pixels;

/* the slot of a file channel: its R, G, B, A index (rgba) or its place in names */
static int slot_of(const char *name, int rgba, char *const *names, int n) {
  return rgba ? chan_index(name) : find_name((const char *const *)names, n, name);
}

/* OpenEXR's stream functions over an open descriptor (user data: the int descriptor) */
static int64_t fd_read(exr_const_context_t ctxt, void *user, void *buf, uint64_t sz,
                       uint64_t offset, exr_stream_error_func_ptr_t error_cb) {
  int fd = *(const int *)user;
  uint64_t got = 0;
  while (got < sz) {
    ssize_t r = pread(fd, (char *)buf + got, sz - got, (off_t)(offset + got));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) return error_cb(ctxt, EXR_ERR_READ_IO, "reading %llu bytes at %llu: %s",
                               (unsigned long long)(sz - got),
                               (unsigned long long)(offset + got), strerror(errno)), -1;
    if (r == 0) break;
    got += (uint64_t)r;
  }
  return (int64_t)got;
}
static int64_t fd_size(exr_const_context_t ctxt, void *user) {
  (void)ctxt;
  struct stat sb;
  return fstat(*(const int *)user, &sb) ? -1 : (int64_t)sb.st_size;
}

/* Reads `path`: header checks, every channel decoded PLANAR into float, interleaved into the
 * display window. rgba: the channel set must be R, G, B[, A] (slots in that order); else any
 * set of HALF / FLOAT channels (slots in the file's order). Non-finite values are refused (and
 * negative R, G, B when rgba) with their position. */
static ics_status read_file(const char *path, int rgba, exr_pixels *px, char *msg, size_t msg_size) {
  memset(px, 0, sizeof *px);
  char why[256];
  ics_status ost;
  /* OpenEXR reads the descriptor this open checked, never the name again: a path swapped for a
   * FIFO after the check cannot block it */
  FILE *file = ics_input_open(path, 0, 0, &ost, why, sizeof why);
  if (!file) {
    set_msg(msg, msg_size, "%s: cannot open: %s", path, why);
    return ost;
  }
  int fd = fileno(file);
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = exr_error_cb;
  init.user_data = &fd;
  init.read_fn = fd_read;
  init.size_fn = fd_size;
  exr_context_t ctx = NULL;
  exr_lastmsg[0] = 0;
  exr_result_t rv = exr_start_read(&ctx, path, &init);
  if (rv != EXR_ERR_SUCCESS) {
    set_msg(msg, msg_size, "%s: not a readable OpenEXR file: %s", path,
            exr_lastmsg[0] ? exr_lastmsg : exr_get_default_error_message(rv));
    exr_finish(&ctx);
    fclose(file);
    return map_err(rv);
  }

  ics_status st = ICS_OK;
  float **planes = NULL;
  int parts = 0, nch = 0;
  exr_storage_t storage;
  const exr_attr_chlist_t *chl = NULL;
  exr_attr_box2i_t dw, disp;
  int have[4] = {0, 0, 0, 0};
  long w = 0, h = 0, W = 0, H = 0;
  if (exr_get_count(ctx, &parts) != EXR_ERR_SUCCESS || parts != 1) {
    set_msg(msg, msg_size, "%s: %d parts; only single-part images are supported", path, parts);
    st = ICS_ERR_UNSUPPORTED;
    goto done;
  }
  if (exr_get_storage(ctx, 0, &storage) != EXR_ERR_SUCCESS || storage != EXR_STORAGE_SCANLINE) {
    set_msg(msg, msg_size, "%s: only scanline images are supported (this one is %s)", path,
            storage == EXR_STORAGE_TILED ? "tiled" : "deep");
    st = ICS_ERR_UNSUPPORTED;
    goto done;
  }
  exr_envmap_t envmap;
  if (rgba && exr_attr_get_envmap(ctx, 0, "envmap", &envmap) == EXR_ERR_SUCCESS &&
      envmap != EXR_ENVMAP_LATLONG) {
    set_msg(msg, msg_size, "%s: a cube map; only latitude-longitude maps are supported", path);
    st = ICS_ERR_UNSUPPORTED;
    goto done;
  }
  if (exr_get_channels(ctx, 0, &chl) != EXR_ERR_SUCCESS || !chl ||
      exr_get_data_window(ctx, 0, &dw) != EXR_ERR_SUCCESS ||
      exr_get_display_window(ctx, 0, &disp) != EXR_ERR_SUCCESS) {
    set_msg(msg, msg_size, "%s: corrupt header: %s", path, exr_lastmsg);
    st = ICS_ERR_PARSE;
    goto done;
  }
  if (chl->num_channels < 1 || chl->num_channels > ICS_EXR_MAX_CHANNELS) {
    set_msg(msg, msg_size, "%s: %d channels (1..%d supported)", path, chl->num_channels,
            ICS_EXR_MAX_CHANNELS);
    st = ICS_ERR_UNSUPPORTED;
    goto done;
  }
  for (int c = 0; c < chl->num_channels; c++) {
    const exr_attr_chlist_entry_t *e = &chl->entries[c];
    int k = rgba ? chan_index(e->name.str) : c;
    if (k < 0) {
      set_msg(msg, msg_size, "%s: unexpected channel '%s' (expected R, G, B and optionally A)",
              path, e->name.str);
      st = ICS_ERR_UNSUPPORTED;
      goto done;
    }
    if (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT) {
      set_msg(msg, msg_size, "%s: channel %s is UINT; only HALF and FLOAT are supported", path,
              e->name.str);
      st = ICS_ERR_UNSUPPORTED;
      goto done;
    }
    if (e->x_sampling != 1 || e->y_sampling != 1) {
      set_msg(msg, msg_size, "%s: channel %s is subsampled; not supported", path, e->name.str);
      st = ICS_ERR_UNSUPPORTED;
      goto done;
    }
    if (rgba) have[k] = 1;
  }
  if (rgba && (!have[0] || !have[1] || !have[2])) {
    set_msg(msg, msg_size, "%s: wrong channel set: missing %s%s%s (expected R, G, B and "
            "optionally A)", path, have[0] ? "" : "R ", have[1] ? "" : "G ", have[2] ? "" : "B");
    st = ICS_ERR_UNSUPPORTED;
    goto done;
  }
  nch = rgba ? (have[3] ? 4 : 3) : chl->num_channels;
  {
    int32_t len = 0;
    const char *str = NULL;
    if (!rgba && exr_attr_get_string(ctx, 0, "icshadow", &len, &str) == EXR_ERR_SUCCESS && str &&
        len >= 0) {
      px->info = malloc((size_t)len + 1);
      if (!px->info) {
        st = ICS_ERR_NOMEM;
        set_msg(msg, msg_size, "%s: out of memory", path);
        goto done;
      }
      memcpy(px->info, str, (size_t)len);
      px->info[len] = 0;
    }
  }
  /* the names: pointers, then the strings, one block */
  size_t bytes = (size_t)nch * sizeof(char *);
  for (int c = 0; c < chl->num_channels; c++) bytes += strlen(chl->entries[c].name.str) + 1;
  px->names = malloc(bytes);
  planes = calloc((size_t)nch, sizeof *planes);
  if (!px->names || !planes) {
    st = ICS_ERR_NOMEM;
    set_msg(msg, msg_size, "%s: out of memory", path);
    goto done;
  }
  char *str = (char *)(px->names + nch);
  for (int c = 0; c < chl->num_channels; c++) {
    const char *nm = chl->entries[c].name.str;
    int k = rgba ? chan_index(nm) : c;
    size_t len = strlen(nm) + 1;
    memcpy(str, nm, len);
    px->names[k] = str;
    str += len;
  }
  /* the image is the DISPLAY window (the latitude-longitude frame); the data window is placed
   * inside it at its offset, pixels outside the data window are 0 (OpenEXR: no data there),
   * data outside the display window is dropped */
  w = (long)dw.max.x - dw.min.x + 1;
  h = (long)dw.max.y - dw.min.y + 1;
  W = (long)disp.max.x - disp.min.x + 1;
  H = (long)disp.max.y - disp.min.y + 1;
  if (!(w > 0 && w <= ICS_IMAGE_MAX_DIM && h > 0 && h <= ICS_IMAGE_MAX_DIM)) {
    set_msg(msg, msg_size, "%s: data window %ld x %ld: sizes must be in 1..%d", path, w, h,
            ICS_IMAGE_MAX_DIM);
    st = ICS_ERR_SIZE;
    goto done;
  }
  if (!(W > 0 && W <= ICS_IMAGE_MAX_DIM && H > 0 && H <= ICS_IMAGE_MAX_DIM)) {
    set_msg(msg, msg_size, "%s: cannot hold a %ld x %ld image (display window): %s", path, W, H,
            ics_status_str(ICS_ERR_SIZE));
    st = ICS_ERR_SIZE;
    goto done;
  }
  /* both sides are at most 65536 here, so the products fit a long */
  if (W * H > ICS_EXR_MAX_PIXELS || w * h > ICS_EXR_MAX_PIXELS) {
    int disp_big = W * H > ICS_EXR_MAX_PIXELS;
    long bw = disp_big ? W : w, bh = disp_big ? H : h;
    set_msg(msg, msg_size, "%s: %s window %ld x %ld is %.4g million pixels, more than the %.4g "
            "million a map may have (ICS_EXR_MAX_PIXELS)", path, disp_big ? "display" : "data",
            bw, bh, 1e-6 * (double)(bw * bh), 1e-6 * ICS_EXR_MAX_PIXELS);
    st = ICS_ERR_SIZE;
    goto done;
  }
  px->data = calloc((size_t)W * (size_t)H * (size_t)nch, sizeof *px->data);
  if (!px->data) {
    set_msg(msg, msg_size, "%s: cannot hold a %ld x %ld image (display window): %s", path, W, H,
            ics_status_str(ICS_ERR_NOMEM));
    st = ICS_ERR_NOMEM;
    goto done;
  }
  for (int k = 0; k < nch; k++) {
    planes[k] = malloc((size_t)w * (size_t)h * sizeof(float));
    if (!planes[k]) {
      st = ICS_ERR_NOMEM;
      set_msg(msg, msg_size, "%s: out of memory", path);
      goto done;
    }
  }

  int32_t lines = 0;
  if (exr_get_scanlines_per_chunk(ctx, 0, &lines) != EXR_ERR_SUCCESS || lines < 1) {
    set_msg(msg, msg_size, "%s: corrupt header (scanlines per chunk)", path);
    st = ICS_ERR_PARSE;
    goto done;
  }
  for (long y = dw.min.y; y <= dw.max.y; y += lines) {
    exr_chunk_info_t ci;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_lastmsg[0] = 0;
    rv = exr_read_scanline_chunk_info(ctx, 0, (int)y, &ci);
    if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_initialize(ctx, 0, &ci, &dec);
    if (rv == EXR_ERR_SUCCESS) {
      for (int c = 0; c < dec.channel_count; c++) {
        exr_coding_channel_info_t *ch = &dec.channels[c];
        int k = slot_of(ch->channel_name, rgba, px->names, nch);
        size_t row0 = (size_t)(ci.start_y - dw.min.y);
        if (k < 0 || k >= nch || ci.start_y < dw.min.y || ci.start_y + ci.height - 1 > dw.max.y ||
            ch->width != w) {
          rv = EXR_ERR_CORRUPT_CHUNK;
          break;
        }
        ch->decode_to_ptr = (uint8_t *)(planes[k] + row0 * (size_t)w);
        ch->user_pixel_stride = (int32_t)sizeof(float);
        ch->user_line_stride = (int32_t)(sizeof(float) * (size_t)w);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = (int16_t)sizeof(float);
      }
    }
    if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_choose_default_routines(ctx, 0, &dec);
    if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_run(ctx, 0, &dec);
    exr_decoding_destroy(ctx, &dec);
    if (rv != EXR_ERR_SUCCESS) {
      st = map_err(rv);
      set_msg(msg, msg_size, "%s: cannot decode scanlines from %ld (corrupt or truncated "
              "file): %s", path, y, exr_lastmsg[0] ? exr_lastmsg : exr_get_default_error_message(rv));
      goto done;
    }
  }
  for (long y = 0; y < h; y++) {
    long Y = y + dw.min.y - disp.min.y;
    if (Y < 0 || Y >= H) continue;
    for (long x = 0; x < w; x++) {
      long X = x + dw.min.x - disp.min.x;
      if (X < 0 || X >= W) continue;
      size_t p = (size_t)y * (size_t)w + (size_t)x, q = (size_t)Y * (size_t)W + (size_t)X;
      for (int k = 0; k < nch; k++) px->data[q * nch + k] = planes[k][p];
    }
  }
  for (size_t i = 0; i < (size_t)W * (size_t)H * (size_t)nch; i++) {
    float v = px->data[i];
    int k = (int)(i % (size_t)nch);
    if (isfinite(v) && !(rgba && k < 3 && v < 0)) continue;
    size_t q = i / (size_t)nch;
    set_msg(msg, msg_size, "%s: pixel (x %zu, y %zu) channel %s is %s (%g): %s", path,
            q % (size_t)W, q / (size_t)W, px->names[k],
            isnan(v) ? "NaN" : isinf(v) ? "infinite" : "negative", (double)v,
            rgba ? "radiance must be finite and >= 0" : "values must be finite");
    st = ICS_ERR_INVALID_ARG;
    break;
  }
done:
  if (planes)
    for (int k = 0; k < nch; k++) free(planes[k]);
  free(planes);
  exr_finish(&ctx);
  fclose(file);
  if (st == ICS_OK) {
    px->W = W, px->H = H, px->n = nch;
  } else {
    free(px->names), free(px->data), free(px->info);
    memset(px, 0, sizeof *px);
  }
  return st;
}

ics_status ics_exr_read(const char *path, ics_image **out, char *msg, size_t msg_size) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!path) return ICS_ERR_INVALID_ARG;
  exr_pixels px;
  ics_status st = read_file(path, 1, &px, msg, msg_size);
  if (st != ICS_OK) return st;
  free(px.names);
  ics_image *img = malloc(sizeof *img);
  if (!img) {
    free(px.data);
    set_msg(msg, msg_size, "%s: out of memory", path);
    return ICS_ERR_NOMEM;
  }
  img->width = (int)px.W, img->height = (int)px.H, img->channels = px.n, img->data = px.data;
  *out = img;
  return ICS_OK;
}

ics_status ics_exr_read_channels(const char *path, ics_exr_channels **out, char *msg,
                                 size_t msg_size) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!path) return ICS_ERR_INVALID_ARG;
  exr_pixels px;
  ics_status st = read_file(path, 0, &px, msg, msg_size);
  if (st != ICS_OK) return st;
  ics_exr_channels *ch = malloc(sizeof *ch);
  if (!ch) {
    free(px.names), free(px.data), free(px.info);
    set_msg(msg, msg_size, "%s: out of memory", path);
    return ICS_ERR_NOMEM;
  }
  ch->width = (int)px.W, ch->height = (int)px.H, ch->count = px.n;
  ch->names = (const char *const *)px.names;
  ch->data = px.data;
  ch->info = px.info;
  *out = ch;
  return ICS_OK;
}

/* names are 1..255 bytes and pairwise distinct: "" or a repeated name is the caller's error */
static int check_names(const ics_exr_channels *ch, char *msg, size_t msg_size, const char *path) {
  for (int c = 0; c < ch->count; c++) {
    const char *n = ch->names[c];
    size_t len = n ? strlen(n) : 0;
    if (len < 1 || len > 255) {
      set_msg(msg, msg_size, "%s: channel %d: a name of 1 to 255 bytes expected", path, c);
      return 0;
    }
    if (find_name(ch->names, c, n) >= 0) {
      set_msg(msg, msg_size, "%s: channel name \"%s\" given twice", path, n);
      return 0;
    }
  }
  return 1;
}

/* Where a write of `path` ends up and the temporary it is written through: the target is path,
 * or the file a symbolic link points to (the link stays); the temporary, TARGET.tmpPID-N, is
 * created here (O_EXCL, mode 0666 less the umask, as a plain fopen would give), in the target's
 * folder so the rename cannot cross file systems. A target that exists and is not a regular file
 * (a device, FIFO, socket, directory) or a link to nothing is refused: the writer never writes a
 * path in place and never removes a file it did not create. ICS_ERR_IO with the reason. */
static ics_status write_target(const char *path, char target[PATH_MAX + 1], char tmp[PATH_MAX + 32],
                               char *msg, size_t msg_size) {
  struct stat st;
  int is_link = lstat(path, &st) == 0 && S_ISLNK(st.st_mode);
  if (stat(path, &st) == 0) {
    if (!S_ISREG(st.st_mode)) {
      set_msg(msg, msg_size, "%s: not a regular file (%s): an OpenEXR file is written to a "
              "temporary file and renamed into place; write to a file instead", path,
              ics_input_kind((unsigned)st.st_mode));
      return ICS_ERR_IO;
    }
  } else if (is_link) {
    set_msg(msg, msg_size, "%s: a symbolic link to nothing; give the path it should point to", path);
    return ICS_ERR_IO;
  }
  if (is_link) {
    if (!realpath(path, target)) {
      set_msg(msg, msg_size, "%s: cannot resolve the link: %s", path, strerror(errno));
      return ICS_ERR_IO;
    }
  } else if (snprintf(target, PATH_MAX + 1, "%s", path) > PATH_MAX) {
    set_msg(msg, msg_size, "%s: path too long", path);
    return ICS_ERR_IO;
  }
  /* a name within 20 bytes of NAME_MAX takes its temporary from the name's first 64 bytes */
  const char *slash = strrchr(target, '/');
  int dirlen = slash ? (int)(slash - target) + 1 : 0, base_long = strlen(target + dirlen) > 235;
  static _Atomic unsigned serial;
  for (int attempt = 0; attempt < 100; attempt++) {
    snprintf(tmp, PATH_MAX + 32, "%.*s%.*s.tmp%ld-%u", dirlen, target, base_long ? 64 : PATH_MAX,
             target + dirlen, (long)getpid(), serial++);
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
    if (fd >= 0) {
      close(fd);
      return ICS_OK;
    }
    if (errno != EEXIST) break;
  }
  set_msg(msg, msg_size, "%s: cannot create a temporary file beside it: %s", path, strerror(errno));
  return ICS_ERR_IO;
}

ics_status ics_exr_write_channels(const char *path, const ics_exr_channels *ch, ics_exr_type type,
                                  int latlong, char *msg, size_t msg_size) {
  if (path && ch && (ch->count < 1 || ch->count > ICS_EXR_MAX_CHANNELS)) {
    set_msg(msg, msg_size, "%s: %d channels (1..%d per file)", path, ch->count,
            ICS_EXR_MAX_CHANNELS);
    return ICS_ERR_INVALID_ARG;
  }
  if (!path || !ch || !ch->data || !ch->names || ch->width < 1 || ch->height < 1 ||
      ch->width > ICS_IMAGE_MAX_DIM || ch->height > ICS_IMAGE_MAX_DIM ||
      (type != ICS_EXR_HALF && type != ICS_EXR_FLOAT)) {
    set_msg(msg, msg_size, "%s: invalid image or pixel type", path ? path : "(null)");
    return ICS_ERR_INVALID_ARG;
  }
  if (!check_names(ch, msg, msg_size, path)) return ICS_ERR_INVALID_ARG;
  const int nch = ch->count;
  const size_t npx = (size_t)ch->width * (size_t)ch->height;
  for (size_t p = 0; p < npx * nch; p++) {
    float v = ch->data[p];
    size_t q = p / nch;
    if (!isfinite(v)) {
      set_msg(msg, msg_size, "%s: pixel (x %zu, y %zu) channel %s is NaN or infinite", path,
              q % ch->width, q / ch->width, ch->names[p % nch]);
      return ICS_ERR_INVALID_ARG;
    }
    if (type == ICS_EXR_HALF && fabsf(v) > 65504.0f) {
      set_msg(msg, msg_size, "%s: pixel (x %zu, y %zu) value %g overflows half (max 65504); "
              "write float", path, q % ch->width, q / ch->width, (double)v);
      return ICS_ERR_INVALID_ARG;
    }
  }
  char target[PATH_MAX + 1], tmp[PATH_MAX + 32];
  ics_status tst = write_target(path, target, tmp, msg, msg_size);
  if (tst != ICS_OK) return tst;
  float **planes = calloc((size_t)nch, sizeof *planes);
  if (!planes) {
    remove(tmp);
    set_msg(msg, msg_size, "%s: out of memory", path);
    return ICS_ERR_NOMEM;
  }
  for (int k = 0; k < nch; k++) {
    planes[k] = malloc(npx * sizeof(float));
    if (!planes[k]) {
      for (int q = 0; q < k; q++) free(planes[q]);
      free(planes);
      remove(tmp);
      set_msg(msg, msg_size, "%s: out of memory", path);
      return ICS_ERR_NOMEM;
    }
    for (size_t p = 0; p < npx; p++) planes[k][p] = ch->data[p * nch + k];
  }

  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = exr_error_cb;
  exr_context_t ctx = NULL;
  int part = 0;
  exr_lastmsg[0] = 0;
  exr_pixel_type_t pt = type == ICS_EXR_HALF ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
  exr_result_t rv = exr_start_write(&ctx, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
  if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_initialize_required_attr_simple(ctx, part, ch->width, ch->height,
                                             EXR_COMPRESSION_ZIP);
  for (int k = nch - 1; k >= 0 && rv == EXR_ERR_SUCCESS; k--)
    rv = exr_add_channel(ctx, part, ch->names[k], pt, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
  if (rv == EXR_ERR_SUCCESS) rv = exr_set_lineorder(ctx, part, EXR_LINEORDER_INCREASING_Y);
  if (rv == EXR_ERR_SUCCESS && latlong)
    rv = exr_attr_set_envmap(ctx, part, "envmap", EXR_ENVMAP_LATLONG);
  if (rv == EXR_ERR_SUCCESS && ch->info) rv = exr_attr_set_string(ctx, part, "icshadow", ch->info);
  if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctx);
  int32_t lines = 1;
  if (rv == EXR_ERR_SUCCESS) rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
  for (int y = 0; rv == EXR_ERR_SUCCESS && y < ch->height; y += lines) {
    exr_chunk_info_t ci;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    rv = exr_write_scanline_chunk_info(ctx, part, y, &ci);
    if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_initialize(ctx, part, &ci, &enc);
    if (rv == EXR_ERR_SUCCESS) {
      for (int c = 0; c < enc.channel_count; c++) {
        exr_coding_channel_info_t *cc = &enc.channels[c];
        int k = find_name(ch->names, nch, cc->channel_name);
        if (k < 0) {
          rv = EXR_ERR_INVALID_ARGUMENT;
          break;
        }
        cc->encode_from_ptr = (const uint8_t *)(planes[k] + (size_t)ci.start_y * ch->width);
        cc->user_pixel_stride = (int32_t)sizeof(float);
        cc->user_line_stride = (int32_t)(sizeof(float) * (size_t)ch->width);
        cc->user_data_type = EXR_PIXEL_FLOAT;
        cc->user_bytes_per_element = (int16_t)sizeof(float);
      }
    }
    if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_choose_default_routines(ctx, part, &enc);
    if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_run(ctx, part, &enc);
    exr_encoding_destroy(ctx, &enc);
  }
  exr_result_t frv = exr_finish(&ctx);
  if (rv == EXR_ERR_SUCCESS) rv = frv;
  for (int k = 0; k < nch; k++) free(planes[k]);
  free(planes);
  if (rv != EXR_ERR_SUCCESS) {
    set_msg(msg, msg_size, "%s: cannot write OpenEXR: %s", path,
            exr_lastmsg[0] ? exr_lastmsg : exr_get_default_error_message(rv));
    remove(tmp);
    return map_err(rv) == ICS_ERR_PARSE ? ICS_ERR_IO : map_err(rv);
  }
  /* the bytes on the disk before the name: a crash after the rename leaves the whole new file
   * or the old one, never an empty one */
  int fd = open(tmp, O_RDONLY);
  if (fd < 0 || fsync(fd) != 0) {
    int saved = errno;
    if (fd >= 0) close(fd);
    set_msg(msg, msg_size, "%s: cannot write OpenEXR: flushing the finished file to disk: %s",
            path, strerror(saved));
    remove(tmp);
    return ICS_ERR_IO;
  }
  close(fd);
  if (rename(tmp, target) != 0) {
    set_msg(msg, msg_size, "%s: cannot write OpenEXR: renaming the finished file into place: %s",
            path, strerror(errno));
    remove(tmp);
    return ICS_ERR_IO;
  }
  return ICS_OK;
}

#endif

ics_status ics_exr_write(const char *path, const ics_image *img, ics_exr_type type, char *msg,
                         size_t msg_size) {
  if (!path || !img || !img->data || (img->channels != 3 && img->channels != 4)) {
    set_msg(msg, msg_size, "%s: invalid image or pixel type", path ? path : "(null)");
    return ICS_ERR_INVALID_ARG;
  }
  if (!ics_exr_available()) return ics_exr_write_channels(path, NULL, type, 1, msg, msg_size);
  int bi, bj, bc;
  if (img->width >= 1 && img->height >= 1 && !ics_image_find_bad(img, &bi, &bj, &bc)) {
    set_msg(msg, msg_size, "%s: pixel (x %d, y %d) channel %s is NaN, infinite or negative", path,
            bi, bj, chan_names[bc]);
    return ICS_ERR_INVALID_ARG;
  }
  ics_exr_channels ch = {img->width, img->height, img->channels, chan_names, img->data, NULL};
  return ics_exr_write_channels(path, &ch, type, 1, msg, msg_size);
}

void ics_exr_channels_destroy(ics_exr_channels *ch) {
  if (!ch) return;
  free((void *)ch->names);
  free((void *)ch->data);
  free((void *)ch->info);
  free(ch);
}

int ics_exr_channel_index(const ics_exr_channels *ch, const char *name) {
  return ch && name ? find_name(ch->names, ch->count, name) : -1;
}
