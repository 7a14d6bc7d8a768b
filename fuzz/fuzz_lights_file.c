/* fuzz_lights_file.c — libFuzzer harness for the lights-file reader (ics_lightsfile_read,
 * gpu/core/lights_json.c): the input is written to a scratch file and read. Invariants: a file
 * that is read gives 1..ICS_LIGHTSFILE_MAX lights with finite means, positive-semidefinite
 * covariances, finite non-negative colours and weights; a refused file gives no lights and a
 * message that names the file. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_require.h"
#include "icshadow/lightsfile.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 65536) return 0;
  static char path[256];
  if (!path[0]) {
    const char *td = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/fuzz_lights_file.%ld.json", td && *td ? td : "/tmp", (long)getpid());
  }
  FILE *f = fopen(path, "wb");
  if (!f) return 0;
  int ok = fwrite(data, 1, size, f) == size;
  if (fclose(f) || !ok) return 0;
  ics_light *l = NULL;
  int n = -1;
  char msg[2048] = "";
  ics_status st = ics_lightsfile_read(path, &l, &n, msg, sizeof msg);
  if (st != ICS_OK) {
    REQUIRE(l == NULL && strstr(msg, path) != NULL);
  } else {
    REQUIRE(l && n >= 1 && n <= ICS_LIGHTSFILE_MAX);
    for (int k = 0; k < n; k++) require_light(&l[k]);
  }
  free(l);
  return 0;
}
