/* fuzz_lights_spec.c — libFuzzer harness for the CLI's lights SPEC parser (cli/lightsfile.c) and,
 * through it, the number parser every numeric option uses (cli_parse_double). Invariants: a SPEC
 * that parses gives at least one light with finite means, positive-semidefinite
 * covariances and finite non-negative weights and colours; written as a lights file
 * (ics_light_write_json, %.17g) and read back (lights_read_file) the lights have the same values (a
 * negative zero comes back as +0: JSON's "-0" is read as the integer 0); a
 * number that parses prints (%.17g) to a string that parses to the same double. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"
#include "fuzz_require.h"
#include "lightsfile.h"


int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 4096) return 0;
  char *s = malloc(size + 1);
  if (!s) return 0;
  memcpy(s, data, size);
  s[size] = 0;

  double x;
  if (cli_parse_double(s, &x) == 0) {
    char buf[64];
    double y;
    snprintf(buf, sizeof buf, "%.17g", x);
    REQUIRE(cli_parse_double(buf, &y) == 0 && memcmp(&x, &y, sizeof x) == 0);
  }

  ics_light *l = NULL;
  int n = 0;
  char err[1024];
  if (lights_parse_spec(s, &l, &n, err, sizeof err) == 0) {
    REQUIRE(n >= 1 && l);
    for (int k = 0; k < n; k++) require_light(&l[k]);
#ifdef ICS_HAVE_RENDER
    char path[256];
    const char *td = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/fuzz_lights.%ld.json", td && *td ? td : "/tmp", (long)getpid());
    FILE *f = fopen(path, "w");
    if (f) {
      REQUIRE(ics_light_write_json(f, l, n) == 0);
      fclose(f);
      ics_light *b = NULL;
      int m = 0;
      REQUIRE(lights_read_file(path, &b, &m, err, sizeof err) == 0 && m == n);
      for (int k = 0; k < n; k++) { /* equal values: jansson reads "-0" as the integer 0 */
        const double *x = &l[k].mean[0], *y = &b[k].mean[0];
        for (int i = 0; i < (int)(sizeof *l / sizeof(double)); i++) REQUIRE(x[i] == y[i]);
      }
      free(b);
      remove(path);
    }
#endif
    free(l);
  } else {
    REQUIRE(l == NULL && err[0]);
  }
  free(s);
  return 0;
}
