/* test_exr.c — OpenEXR I/O: float and half round trips (bit-exact; the half data uses values
 * exactly representable in half, different in every channel so a channel swap is caught),
 * and clear errors for missing, corrupt, truncated, wrong-channel, UINT, NaN / inf /
 * negative files; named channel sets (ics_exr_write_channels / ics_exr_read_channels) round
 * trip by name, read files written independently, and refuse repeated or empty names and
 * non-finite values. Files with channel sets or values ics_exr_write refuses are made here with
 * the OpenEXR Core API directly (write_raw). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

#include "icshadow.h"
#include "testutil.h"

static char dir[256];

static const char *tmpf(const char *name) {
  static char buf[8][512];
  static int k;
  k = (k + 1) % 8;
  snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
  return buf[k];
}

static int raw_cube; /* write_raw: tag the file as a cube map */
/* write_raw: when raw_windows is set, the display window is raw_disp and the data window
 * raw_data (w x h must be the data window's size) */
static int raw_windows;
static exr_attr_box2i_t raw_disp, raw_data;

static exr_attr_box2i_t box(int x0, int y0, int x1, int y1) {
  exr_attr_box2i_t b;
  b.min.x = x0;
  b.min.y = y0;
  b.max.x = x1;
  b.max.y = y1;
  return b;
}

/* a W x H file with the given channels (all of type pt); value of channel c at pixel p is
 * val(c, p) */
static int write_raw(const char *path, int w, int h, int nch, const char *const *names,
                     exr_pixel_type_t pt, float (*val)(int c, int p)) {
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  exr_context_t ctx;
  int part;
  float *planes[8];
  for (int c = 0; c < nch; c++) {
    planes[c] = malloc(sizeof(float) * w * h);
    for (int p = 0; p < w * h; p++) planes[c][p] = val(c, p);
  }
  exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
  if (rv == 0) rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
  if (rv == 0 && raw_windows) {
    exr_attr_v2f_t centre;
    centre.x = centre.y = 0;
    rv = exr_initialize_required_attr(ctx, part, &raw_disp, &raw_data, 1, &centre, 1,
                                      EXR_LINEORDER_INCREASING_Y, EXR_COMPRESSION_NONE);
  } else if (rv == 0) {
    rv = exr_initialize_required_attr_simple(ctx, part, w, h, EXR_COMPRESSION_NONE);
  }
  for (int c = 0; c < nch && rv == 0; c++)
    rv = exr_add_channel(ctx, part, names[c], pt, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
  if (rv == 0 && raw_cube) rv = exr_attr_set_envmap(ctx, part, "envmap", EXR_ENVMAP_CUBE);
  if (rv == 0) rv = exr_write_header(ctx);
  int32_t lines = 1;
  if (rv == 0) rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
  int y0 = raw_windows ? raw_data.min.y : 0;
  for (int y = 0; rv == 0 && y < h; y += lines) {
    exr_chunk_info_t ci;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    rv = exr_write_scanline_chunk_info(ctx, part, y0 + y, &ci);
    if (rv == 0) rv = exr_encoding_initialize(ctx, part, &ci, &enc);
    for (int c = 0; rv == 0 && c < enc.channel_count; c++) {
      int k = 0;
      while (strcmp(names[k], enc.channels[c].channel_name)) k++;
      enc.channels[c].encode_from_ptr = (const uint8_t *)(planes[k] + (size_t)y * w);
      enc.channels[c].user_pixel_stride = 4;
      enc.channels[c].user_line_stride = 4 * w;
      enc.channels[c].user_data_type = EXR_PIXEL_FLOAT;
      enc.channels[c].user_bytes_per_element = 4;
    }
    if (rv == 0) rv = exr_encoding_choose_default_routines(ctx, part, &enc);
    if (rv == 0) rv = exr_encoding_run(ctx, part, &enc);
    exr_encoding_destroy(ctx, &enc);
  }
  exr_finish(&ctx);
  for (int c = 0; c < nch; c++) free(planes[c]);
  return rv == 0 ? 0 : -1;
}

static float v_plain(int c, int p) { return (float)(1 + c + (p % 7) * 0.25); }
static float v_nan(int c, int p) { return c == 1 && p == 2 * 5 + 3 ? NAN : v_plain(c, p); }
static float v_inf(int c, int p) { return c == 2 && p == 7 ? INFINITY : v_plain(c, p); }
static float v_neg(int c, int p) { return c == 0 && p == 0 ? -0.5f : v_plain(c, p); }

static int file_exists(const char *p) {
  FILE *f = fopen(p, "rb");
  if (f) fclose(f);
  return f != NULL;
}

/* read must fail with `want` status, *out NULL and a message containing `needle` */
static void expect_fail(const char *path, ics_status want, const char *needle) {
  ics_image unset, *im = &unset;
  char msg[512] = "";
  ics_status st = ics_exr_read(path, &im, msg, sizeof msg);
  CHECK(st == want, "%s: status %s, expected %s (%s)", path, ics_status_str(st),
        ics_status_str(want), msg);
  CHECK(im == NULL, "%s: *out not NULL after failure", path);
  CHECK(strstr(msg, needle) != NULL, "%s: message '%s' lacks '%s'", path, msg, needle);
  printf("expected failure: %s\n", msg);
}

static long file_size(const char *p) {
  FILE *f = fopen(p, "rb");
  if (!f) return -1;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fclose(f);
  return n;
}

static void copy_prefix(const char *src, const char *dst, long n, long flip_at) {
  FILE *f = fopen(src, "rb"), *g = fopen(dst, "wb");
  for (long i = 0; i < n; i++) {
    int c = fgetc(f);
    if (i >= flip_at && i < flip_at + 64) c ^= 0x5a;
    fputc(c, g);
  }
  fclose(f);
  fclose(g);
}

/* `test_exr --write-bad DIR`: writes DIR/nan.exr, DIR/rg.exr, DIR/tiny.exr (2 x 1) and
 * DIR/trunc.exr for the CLI
 * tests (tests/cli_lightfit.cmake) and exits */
static int write_bad(const char *d) {
  static const char *const rgb[] = {"R", "G", "B"}, *const rg[] = {"R", "G"};
  if (strlen(d) + sizeof "/trunc.exr" > sizeof dir) { /* tmpf() would cut the path */
    fprintf(stderr, "test_exr: --write-bad: directory name longer than %zu bytes\n",
            sizeof dir - sizeof "/trunc.exr");
    return 1;
  }
  snprintf(dir, sizeof dir, "%s", d);
  char msg[256];
  ics_image *a = NULL;
  if (write_raw(tmpf("nan.exr"), 8, 4, 3, rgb, EXR_PIXEL_FLOAT, v_nan) ||
      write_raw(tmpf("rg.exr"), 8, 4, 2, rg, EXR_PIXEL_FLOAT, v_plain) ||
      write_raw(tmpf("tiny.exr"), 2, 1, 3, rgb, EXR_PIXEL_FLOAT, v_plain) ||
      ics_image_create(&a, 64, 32, 3) != ICS_OK)
    return 1;
  for (int p = 0; p < 64 * 32 * 3; p++) a->data[p] = (float)(p % 97) * 0.5f;
  ics_status st = ics_exr_write(tmpf("full.exr"), a, ICS_EXR_FLOAT, msg, sizeof msg);
  ics_image_destroy(a);
  if (st != ICS_OK) return 1;
  copy_prefix(tmpf("full.exr"), tmpf("trunc.exr"), file_size(tmpf("full.exr")) / 2, 1L << 40);
  return 0;
}

int main(int argc, char **argv) {
  if (argc == 3 && !strcmp(argv[1], "--write-bad")) return write_bad(argv[2]);
  snprintf(dir, sizeof dir, "%s", "test_exr_tmp");
  if (system("mkdir -p test_exr_tmp") != 0) return 1;
  CHECK(ics_exr_available() == 1, "built with OpenEXR");
  ics_image *a = NULL, *b = NULL;
  char msg[512];

  /* float round trip, RGB, odd size (several ZIP chunks of 16 lines), wide value range */
  CHECK(ics_image_create(&a, 37, 41, 3) == ICS_OK, "init");
  for (int p = 0; p < 37 * 41 * 3; p++)
    a->data[p] = (float)(p % 5 == 0 ? 0.0 : ldexp(1.0 + p * 0.001, (p % 41) - 20));
  ics_status st = ics_exr_write(tmpf("f.exr"), a, ICS_EXR_FLOAT, msg, sizeof msg);
  CHECK(st == ICS_OK, "write float: %s", msg);
  st = ics_exr_read(tmpf("f.exr"), &b, msg, sizeof msg);
  CHECK(st == ICS_OK, "read float: %s", msg);
  CHECK(b && b->width == 37 && b->height == 41 && b->channels == 3, "float size %dx%dx%d",
        b ? b->width : 0, b ? b->height : 0, b ? b->channels : 0);
  CHECK(b && !memcmp(a->data, b->data, sizeof(float) * 37 * 41 * 3), "float round trip exact");
  ics_image_destroy(b);
  ics_image_destroy(a);

  /* half round trip, RGBA: R, G, B, A differ at every pixel (k/8 + 16 c + 1 < 64, all exact
   * in half), so a reversed (ABGR) decode or any swap fails */
  CHECK(ics_image_create(&a, 19, 35, 4) == ICS_OK, "init");
  for (int p = 0; p < 19 * 35; p++)
    for (int c = 0; c < 4; c++) a->data[p * 4 + c] = (float)((p % 64) / 8.0 + 16 * c + 1);
  st = ics_exr_write(tmpf("h.exr"), a, ICS_EXR_HALF, msg, sizeof msg);
  CHECK(st == ICS_OK, "write half: %s", msg);
  st = ics_exr_read(tmpf("h.exr"), &b, msg, sizeof msg);
  CHECK(st == ICS_OK, "read half: %s", msg);
  CHECK(b && b->channels == 4 && b->width == 19 && b->height == 35, "half size");
  int bad = -1;
  for (int p = 0; b && p < 19 * 35 * 4 && bad < 0; p++)
    if (a->data[p] != b->data[p]) bad = p;
  CHECK(b && bad < 0, "half round trip: value %d is %g, wrote %g", bad,
        bad >= 0 ? b->data[bad] : 0.0, bad >= 0 ? a->data[bad] : 0.0);
  ics_image_destroy(b);
  /* half: a value above 65504 is refused, and no file is left */
  a->data[5] = 70000;
  remove(tmpf("big.exr"));
  st = ics_exr_write(tmpf("big.exr"), a, ICS_EXR_HALF, msg, sizeof msg);
  CHECK(st == ICS_ERR_INVALID_ARG && strstr(msg, "overflows half"), "half overflow: %s", msg);
  CHECK(!file_exists(tmpf("big.exr")), "no file after a refused write");
  a->data[5] = NAN;
  st = ics_exr_write(tmpf("big.exr"), a, ICS_EXR_FLOAT, msg, sizeof msg);
  CHECK(st == ICS_ERR_INVALID_ARG && !file_exists(tmpf("big.exr")), "NaN write refused: %s", msg);
  ics_image_destroy(a);

  /* files written here with the raw API read back too (uncompressed, RGB half) */
  static const char *const rgb[] = {"R", "G", "B"};
  CHECK(write_raw(tmpf("raw.exr"), 5, 4, 3, rgb, EXR_PIXEL_HALF, v_plain) == 0, "raw");
  st = ics_exr_read(tmpf("raw.exr"), &b, msg, sizeof msg);
  CHECK(st == ICS_OK && b->data[3 * 6 + 1] == v_plain(1, 6), "raw half read: %s", msg);
  ics_image_destroy(b);

  /* a data window smaller than the display window: the image is the display window (the
   * latitude-longitude frame), the data placed at its offset, zeros elsewhere; a data window
   * reaching outside the display window (overscan) is clipped to it */
  raw_windows = 1;
  raw_disp = box(0, 0, 127, 63);
  raw_data = box(32, 16, 95, 47);
  CHECK(write_raw(tmpf("win.exr"), 64, 32, 3, rgb, EXR_PIXEL_FLOAT, v_plain) == 0, "raw window");
  raw_disp = box(0, 0, 7, 3);
  raw_data = box(-2, -1, 9, 4);
  CHECK(write_raw(tmpf("over.exr"), 12, 6, 3, rgb, EXR_PIXEL_FLOAT, v_plain) == 0, "raw overscan");
  /* a tiny file whose display window claims 1793 x 64513 pixels (115.7 million): refused before
   * anything is allocated (it used to allocate and clear 1.4 GB per channel) */
  raw_disp = box(0, 0, 1792, 64512);
  raw_data = box(0, 0, 7, 3);
  CHECK(write_raw(tmpf("huge_disp.exr"), 8, 4, 3, rgb, EXR_PIXEL_FLOAT, v_plain) == 0, "raw huge display");
  raw_windows = 0;
  CHECK(file_size(tmpf("huge_disp.exr")) < 2000, "the huge-window file is small (%ld bytes)",
        file_size(tmpf("huge_disp.exr")));
  st = ics_exr_read(tmpf("huge_disp.exr"), &b, msg, sizeof msg);
  CHECK(st == ICS_ERR_SIZE && b == NULL && strstr(msg, "display window 1793 x 64513 is 115.7 million pixels"),
        "huge display window refused: %s", msg);
  {
    ics_exr_channels *r = NULL;
    st = ics_exr_read_channels(tmpf("huge_disp.exr"), &r, msg, sizeof msg);
    CHECK(st == ICS_ERR_SIZE && r == NULL, "channels: huge display window refused: %s", msg);
  }
  st = ics_exr_read(tmpf("win.exr"), &b, msg, sizeof msg);
  CHECK(st == ICS_OK && b->width == 128 && b->height == 64, "windowed read: %s, %dx%d", msg,
        b ? b->width : 0, b ? b->height : 0);
  if (st == ICS_OK) {
    int wrong = 0;
    for (int yy = 0; yy < 64; yy++)
      for (int xx = 0; xx < 128; xx++)
        for (int c = 0; c < 3; c++) {
          int in = xx >= 32 && xx < 96 && yy >= 16 && yy < 48;
          float want = in ? v_plain(c, (yy - 16) * 64 + (xx - 32)) : 0.0f;
          wrong += b->data[((size_t)yy * 128 + xx) * 3 + c] != want;
        }
    CHECK(wrong == 0, "windowed read: %d values misplaced", wrong);
    ics_image_destroy(b);
  }
  st = ics_exr_read(tmpf("over.exr"), &b, msg, sizeof msg);
  CHECK(st == ICS_OK && b->width == 8 && b->height == 4, "overscan read: %s", msg);
  if (st == ICS_OK) {
    int wrong = 0;
    for (int yy = 0; yy < 4; yy++)
      for (int xx = 0; xx < 8; xx++)
        for (int c = 0; c < 3; c++)
          wrong += b->data[((size_t)yy * 8 + xx) * 3 + c] != v_plain(c, (yy + 1) * 12 + (xx + 2));
    CHECK(wrong == 0, "overscan read: %d values misplaced", wrong);
    ics_image_destroy(b);
  }

  /* errors */
  expect_fail(tmpf("missing.exr"), ICS_ERR_IO, "cannot open");
  FILE *f = fopen(tmpf("text.exr"), "w");
  fputs("this is not an OpenEXR file\n", f);
  fclose(f);
  expect_fail(tmpf("text.exr"), ICS_ERR_PARSE, "not a readable OpenEXR file");
  /* truncated: a float map cut in half; and corrupt: 64 bytes of chunk data flipped */
  CHECK(ics_image_create(&a, 64, 64, 3) == ICS_OK, "init");
  for (int p = 0; p < 64 * 64 * 3; p++) a->data[p] = (float)(p % 97) * 0.5f;
  CHECK(ics_exr_write(tmpf("big.exr"), a, ICS_EXR_FLOAT, msg, sizeof msg) == ICS_OK, "%s", msg);
  ics_image_destroy(a);
  long n = file_size(tmpf("big.exr"));
  copy_prefix(tmpf("big.exr"), tmpf("trunc.exr"), n / 2, n);
  expect_fail(tmpf("trunc.exr"), ICS_ERR_PARSE, "corrupt or truncated");
  copy_prefix(tmpf("big.exr"), tmpf("flip.exr"), n, n - 600);
  {
    ics_image unset, *im = &unset;
    st = ics_exr_read(tmpf("flip.exr"), &im, msg, sizeof msg);
    CHECK(st != ICS_OK && im == NULL && strstr(msg, "flip.exr"), "flipped bytes: %s (%s)",
          ics_status_str(st), msg);
    printf("expected failure: %s\n", msg);
  }
  copy_prefix(tmpf("big.exr"), tmpf("hdr.exr"), 40, n); /* header cut */
  {
    ics_image unset, *im = &unset;
    st = ics_exr_read(tmpf("hdr.exr"), &im, msg, sizeof msg);
    CHECK(st != ICS_OK && im == NULL && strstr(msg, "not a readable OpenEXR"),
          "cut header: %s (%s)", ics_status_str(st), msg);
  }
  /* wrong channel sets */
  static const char *const rg[] = {"R", "G"}, *const rgbz[] = {"R", "G", "B", "Z"},
                           *const y[] = {"Y"};
  CHECK(write_raw(tmpf("rg.exr"), 5, 4, 2, rg, EXR_PIXEL_FLOAT, v_plain) == 0, "raw rg");
  expect_fail(tmpf("rg.exr"), ICS_ERR_UNSUPPORTED, "missing B");
  CHECK(write_raw(tmpf("rgbz.exr"), 5, 4, 4, rgbz, EXR_PIXEL_FLOAT, v_plain) == 0, "raw rgbz");
  expect_fail(tmpf("rgbz.exr"), ICS_ERR_UNSUPPORTED, "unexpected channel 'Z'");
  CHECK(write_raw(tmpf("y.exr"), 5, 4, 1, y, EXR_PIXEL_HALF, v_plain) == 0, "raw y");
  expect_fail(tmpf("y.exr"), ICS_ERR_UNSUPPORTED, "unexpected channel 'Y'");
  CHECK(write_raw(tmpf("uint.exr"), 5, 4, 3, rgb, EXR_PIXEL_UINT, v_plain) == 0, "raw uint");
  expect_fail(tmpf("uint.exr"), ICS_ERR_UNSUPPORTED, "UINT");
  /* a cube map */
  raw_cube = 1;
  CHECK(write_raw(tmpf("cube.exr"), 5, 30, 3, rgb, EXR_PIXEL_HALF, v_plain) == 0, "raw cube");
  raw_cube = 0;
  expect_fail(tmpf("cube.exr"), ICS_ERR_UNSUPPORTED, "only latitude-longitude maps");
  /* bad pixels, with their position */
  CHECK(write_raw(tmpf("nan.exr"), 5, 4, 3, rgb, EXR_PIXEL_FLOAT, v_nan) == 0, "raw nan");
  expect_fail(tmpf("nan.exr"), ICS_ERR_INVALID_ARG, "pixel (x 3, y 2) channel G is NaN");
  CHECK(write_raw(tmpf("inf.exr"), 5, 4, 3, rgb, EXR_PIXEL_HALF, v_inf) == 0, "raw inf");
  expect_fail(tmpf("inf.exr"), ICS_ERR_INVALID_ARG, "pixel (x 2, y 1) channel B is infinite");
  CHECK(write_raw(tmpf("neg.exr"), 5, 4, 3, rgb, EXR_PIXEL_FLOAT, v_neg) == 0, "raw neg");
  expect_fail(tmpf("neg.exr"), ICS_ERR_INVALID_ARG, "pixel (x 0, y 0) channel R is negative");

  /* named channels: float and half round trips by name (the file holds them sorted by name, so
   * the order read back differs from the order written), negative values allowed */
  {
    static const char *const names[] = {"R", "G", "B", "A", "light0.V", "light1.R", "Z"};
    enum { NW = 23, NH = 19, NC = 7 };
    float *data = malloc(sizeof(float) * NW * NH * NC);
    for (int p = 0; p < NW * NH; p++)
      for (int c = 0; c < NC; c++) data[p * NC + c] = (float)((p % 64) / 8.0 + 16 * c - 40);
    ics_exr_channels w = {NW, NH, NC, names, data, "made by test_exr"};
    for (int half = 0; half < 2; half++) {
      const char *path = tmpf(half ? "chan_h.exr" : "chan_f.exr");
      st = ics_exr_write_channels(path, &w, half ? ICS_EXR_HALF : ICS_EXR_FLOAT, 0, msg, sizeof msg);
      CHECK(st == ICS_OK, "write channels (%s): %s", half ? "half" : "float", msg);
      ics_exr_channels *r = NULL;
      st = ics_exr_read_channels(path, &r, msg, sizeof msg);
      CHECK(st == ICS_OK && r && r->width == NW && r->height == NH && r->count == NC,
            "read channels: %s", msg);
      if (st != ICS_OK) continue;
      CHECK(!strcmp(r->names[0], "A") && !strcmp(r->names[NC - 1], "light1.R"),
            "file order sorted by name: %s ... %s", r->names[0], r->names[NC - 1]);
      int wrong = 0;
      for (int c = 0; c < NC; c++) {
        int k = ics_exr_channel_index(r, names[c]);
        CHECK(k >= 0, "channel %s read back", names[c]);
        for (int p = 0; k >= 0 && p < NW * NH; p++) wrong += r->data[p * NC + k] != data[p * NC + c];
      }
      CHECK(wrong == 0, "channels round trip (%s): %d values differ", half ? "half" : "float", wrong);
      CHECK(ics_exr_channel_index(r, "light0") == -1, "no channel 'light0'");
      CHECK(r->info && !strcmp(r->info, "made by test_exr"), "info attribute: %s",
            r->info ? r->info : "(none)");
      ics_exr_channels_destroy(r);
    }
    /* latlong = 0 writes no envmap attribute; ics_exr_write's files carry latlong */
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx;
    exr_envmap_t env;
    CHECK(exr_start_read(&ctx, tmpf("chan_f.exr"), &init) == 0 &&
              exr_attr_get_envmap(ctx, 0, "envmap", &env) != 0, "no envmap attribute");
    exr_finish(&ctx);
    CHECK(exr_start_read(&ctx, tmpf("h.exr"), &init) == 0 &&
              exr_attr_get_envmap(ctx, 0, "envmap", &env) == 0 && env == EXR_ENVMAP_LATLONG,
          "ics_exr_write: envmap latlong");
    exr_finish(&ctx);
    /* refusals, no file left */
    static const char *const twice[] = {"R", "G", "B", "A", "Z", "light1.R", "Z"};
    static const char *const empty[] = {"R", "G", "B", "A", "", "light1.R", "Z"};
    remove(tmpf("chan_bad.exr"));
    w.names = twice;
    st = ics_exr_write_channels(tmpf("chan_bad.exr"), &w, ICS_EXR_FLOAT, 0, msg, sizeof msg);
    CHECK(st == ICS_ERR_INVALID_ARG && strstr(msg, "\"Z\" given twice"), "repeated name: %s", msg);
    w.names = empty;
    st = ics_exr_write_channels(tmpf("chan_bad.exr"), &w, ICS_EXR_FLOAT, 0, msg, sizeof msg);
    CHECK(st == ICS_ERR_INVALID_ARG && strstr(msg, "channel 4"), "empty name: %s", msg);
    w.names = names;
    data[(3 * NW + 5) * NC + 6] = INFINITY;
    st = ics_exr_write_channels(tmpf("chan_bad.exr"), &w, ICS_EXR_FLOAT, 0, msg, sizeof msg);
    CHECK(st == ICS_ERR_INVALID_ARG && strstr(msg, "pixel (x 5, y 3) channel Z is NaN or infinite"),
          "infinite value: %s", msg);
    w.count = 0;
    st = ics_exr_write_channels(tmpf("chan_bad.exr"), &w, ICS_EXR_FLOAT, 0, msg, sizeof msg);
    CHECK(st == ICS_ERR_INVALID_ARG, "no channels refused");
    CHECK(!file_exists(tmpf("chan_bad.exr")), "no file after refused channel writes");
    free(data);
  }
  /* files written independently (write_raw) read by name; NaN refused with its place,
   * negative values accepted */
  {
    ics_exr_channels unset, *r = &unset;
    st = ics_exr_read_channels(tmpf("rgbz.exr"), &r, msg, sizeof msg);
    CHECK(st == ICS_OK && r->count == 4, "read R, G, B, Z: %s", msg);
    int wrong = 0;
    for (int c = 0; st == ICS_OK && c < 4; c++) {
      int k = ics_exr_channel_index(r, rgbz[c]);
      for (int p = 0; p < 20; p++) wrong += k < 0 || r->data[p * 4 + k] != v_plain(c, p);
    }
    CHECK(wrong == 0, "raw R, G, B, Z by name: %d wrong", wrong);
    if (st == ICS_OK) ics_exr_channels_destroy(r);
    r = &unset;
    st = ics_exr_read_channels(tmpf("nan.exr"), &r, msg, sizeof msg);
    CHECK(st == ICS_ERR_INVALID_ARG && r == NULL && strstr(msg, "pixel (x 3, y 2) channel G is NaN"),
          "channels: NaN refused: %s", msg);
    st = ics_exr_read_channels(tmpf("neg.exr"), &r, msg, sizeof msg);
    CHECK(st == ICS_OK && r && r->count == 3 && r->data[ics_exr_channel_index(r, "R")] == -0.5f,
          "channels: negative accepted: %s", msg);
    ics_exr_channels_destroy(r);
    st = ics_exr_read_channels(tmpf("missing.exr"), &r, msg, sizeof msg);
    CHECK(st == ICS_ERR_IO && r == NULL && strstr(msg, "cannot open"), "channels: missing: %s", msg);
  }

  if (system("rm -rf test_exr_tmp") != 0) return 1;
  return test_summary("exr");
}
