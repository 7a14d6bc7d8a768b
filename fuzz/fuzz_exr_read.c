/* fuzz_exr_read.c — libFuzzer harness for the OpenEXR readers (libicshadow/src/exr.c): the input
 * is written to a file and read by ics_exr_read_channels and ics_exr_read. Invariants beyond "no
 * crash, no sanitizer report": a file that reads has sizes in range (1..65536 a side, at most
 * ICS_EXR_MAX_PIXELS, 1..ICS_EXR_MAX_CHANNELS channels with distinct names) and finite values;
 * ics_exr_read agrees with it on the size; and a small one written back with
 * ics_exr_write_channels reads back identical (names, values, info). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_require.h"
#include "icshadow.h"

static char in_path[256], out_path[256];

static void paths(void) {
  if (in_path[0]) return;
  const char *td = getenv("TMPDIR");
  snprintf(in_path, sizeof in_path, "%s/fuzz_exr_in.%ld.exr", td && *td ? td : "/tmp", (long)getpid());
  snprintf(out_path, sizeof out_path, "%s/fuzz_exr_out.%ld.exr", td && *td ? td : "/tmp", (long)getpid());
}


int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  paths();
  FILE *f = fopen(in_path, "wb");
  if (!f) return 0;
  fwrite(data, 1, size, f);
  fclose(f);
  char msg[1024];
  ics_exr_channels *ch = NULL;
  ics_status st = ics_exr_read_channels(in_path, &ch, msg, sizeof msg);
  ics_image *img = NULL;
  ics_status st2 = ics_exr_read(in_path, &img, msg, sizeof msg);
  if (st == ICS_OK) {
    REQUIRE(ch && ch->width >= 1 && ch->height >= 1 && ch->width <= ICS_IMAGE_MAX_DIM &&
            ch->height <= ICS_IMAGE_MAX_DIM);
    REQUIRE((long)ch->width * ch->height <= ICS_EXR_MAX_PIXELS);
    REQUIRE(ch->count >= 1 && ch->count <= ICS_EXR_MAX_CHANNELS);
    for (int a = 0; a < ch->count; a++)
      for (int b = a + 1; b < ch->count; b++) REQUIRE(strcmp(ch->names[a], ch->names[b]));
    size_t nv = (size_t)ch->width * ch->height * ch->count;
    for (size_t i = 0; i < nv; i++) REQUIRE(isfinite(ch->data[i]));
    if (st2 == ICS_OK) REQUIRE(img->width == ch->width && img->height == ch->height);
    if ((size_t)ch->width * ch->height <= 4096) {
      ics_exr_channels *back = NULL;
      REQUIRE(ics_exr_write_channels(out_path, ch, ICS_EXR_FLOAT, 0, msg, sizeof msg) == ICS_OK);
      REQUIRE(ics_exr_read_channels(out_path, &back, msg, sizeof msg) == ICS_OK);
      REQUIRE(back->width == ch->width && back->height == ch->height && back->count == ch->count);
      for (int c = 0; c < ch->count; c++) REQUIRE(!strcmp(back->names[c], ch->names[c]));
      REQUIRE(!memcmp(back->data, ch->data, nv * sizeof *ch->data));
      REQUIRE((!back->info && !ch->info) || (back->info && ch->info && !strcmp(back->info, ch->info)));
      ics_exr_channels_destroy(back);
      remove(out_path);
    }
  } else {
    REQUIRE(ch == NULL && msg[0]);
  }
  if (st2 == ICS_OK) {
    size_t nv = (size_t)img->width * img->height * img->channels;
    for (size_t i = 0; i < nv; i++)
      REQUIRE(isfinite(img->data[i]) && (i % img->channels == 3 || img->data[i] >= 0)); /* R, G, B >= 0 */
  }
  ics_exr_channels_destroy(ch);
  ics_image_destroy(img);
  remove(in_path);
  return 0;
}
