/* cmd_eval.c — `icshadow eval FUNC`: one number per line on stdin, one %.17g result per line
 * on stdout. A line that is not a number (or holds a NUL byte) is reported on stderr with its
 * line number, gets "nan" on stdout (so outputs stay aligned with inputs), and makes the exit
 * status 2. A failure to read stdin or write stdout is reported and gives exit status 1. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"

static const struct {
  const char *name;
  double (*f)(double);
  const char *what;
} funcs[] = {
    {"ellipk", ics_ellipk, "K(m), parameter m = k^2 <= 1"},
    {"ellipe", ics_ellipe, "E(m), parameter m = k^2 <= 1"},
    {"ellipk_m1", ics_ellipk_m1, "K(1 - m1), complementary parameter m1 >= 0"},
    {"ellipe_m1", ics_ellipe_m1, "E(1 - m1), complementary parameter m1 >= 0"},
    {"varx", ics_ellipse_varx, "x-variance of the ellipse with radii (1, b), b >= 0"},
    {"vx", ics_ellipse_vx, "abToVarx: V_x(t) of the unit ellipse (1 - t, t), t in [0, 1]"},
    {"vy", ics_ellipse_vy, "V_y(t) = V_x(1 - t), t in [0, 1]"},
    {"ratio", ics_ellipse_ratio, "V_y(t) / V_x(t), t in [0, 1]"},
    {"ratio_to_t", ics_ellipse_ratio_to_t, "ratioToab: t with ratio(t) = rat, rat in [0, inf]"},
};
enum { NFUNCS = sizeof funcs / sizeof funcs[0] };

static void help(FILE *f) {
  fprintf(f, "usage: icshadow eval FUNC < numbers\n"
             "Reads one number per line from stdin and writes FUNC of it, one %%.17g per line.\n"
             "Outside a function's domain the result is nan. A line that is not a number is\n"
             "reported on stderr (with its line number), gives nan, and the exit status is 2.\n\n"
             "FUNC:\n");
  for (int i = 0; i < NFUNCS; i++) fprintf(f, "  %-11s %s\n", funcs[i].name, funcs[i].what);
}

int cmd_eval(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  if (argc != 2) {
    help(stderr);
    return 2;
  }
  int which = -1;
  for (int i = 0; i < NFUNCS; i++)
    if (!strcmp(argv[1], funcs[i].name)) which = i;
  if (which < 0) {
    fprintf(stderr, "icshadow eval: unknown function '%s'\n", argv[1]);
    help(stderr);
    return 2;
  }
  char *line = NULL;
  size_t cap = 0;
  ssize_t len;
  long lineno = 0;
  int status = 0;
  while ((len = getline(&line, &cap, stdin)) != -1) {
    lineno++;
    if (len > 0 && line[len - 1] == '\n') line[--len] = '\0';
    double x;
    if (strlen(line) != (size_t)len) {
      fprintf(stderr, "icshadow eval: line %ld: contains a NUL byte\n", lineno);
      printf("nan\n");
      status = 2;
      continue;
    }
    if (cli_parse_double(line, &x) != 0) {
      fprintf(stderr, "icshadow eval: line %ld: not a number: '%.60s'\n", lineno, line);
      printf("nan\n");
      status = 2;
      continue;
    }
    printf("%.17g\n", funcs[which].f(x));
  }
  int read_error = ferror(stdin) ? errno : 0;
  free(line);
  if (read_error) {
    fprintf(stderr, "icshadow eval: cannot read stdin: %s\n", strerror(read_error));
    return 1;
  }
  if (cli_stdout_failed("eval")) return 1;
  return status;
}
