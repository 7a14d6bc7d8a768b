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
    {"ellipk", ics_ellint_k, "K(m), parameter m = k^2 <= 1"},
    {"ellipe", ics_ellint_e, "E(m), parameter m = k^2 <= 1"},
    {"ellipk_m1", ics_ellint_k_m1, "K(1 - m1), complementary parameter m1 >= 0"},
    {"ellipe_m1", ics_ellint_e_m1, "E(1 - m1), complementary parameter m1 >= 0"},
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
             "Outside a function's domain the result is nan. A line that is not a number (a\n"
             "blank line too) is reported on stderr with its line number, gives nan, and the\n"
             "exit status is 2.\n\n"
             "FUNC:\n");
  for (int i = 0; i < NFUNCS; i++) fprintf(f, "  %-11s %s\n", funcs[i].name, funcs[i].what);
}

static const char CMD[] = "eval";

int cmd_eval(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  const char *name = NULL;
  int nnames = 0;
  const cli_option opts[] = {{NULL, .kind = CLI_STRING, .dest = &name, .given = &nnames}};
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (nnames == 0) return cli_error(CMD, "give a FUNC (the list: icshadow eval --help)");
  if (nnames > 1)
    return cli_error(CMD, "expected one FUNC, got %d arguments (the numbers come on stdin: "
                     "icshadow eval FUNC < FILE)", nnames);
  int which = -1;
  for (int i = 0; i < NFUNCS; i++)
    if (!strcmp(name, funcs[i].name)) which = i;
  if (which < 0) {
    cli_error(CMD, "unknown function '%s'", name);
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
      status = cli_error(CMD, "line %ld: contains a NUL byte", lineno);
      printf("nan\n");
      continue;
    }
    if (cli_parse_double(line, &x) != 0) {
      status = cli_error(CMD, "line %ld: not a number: '%.60s'", lineno, line);
      printf("nan\n");
      continue;
    }
    printf("%.17g\n", funcs[which].f(x));
  }
  int read_error = ferror(stdin) ? errno : 0;
  free(line);
  if (read_error) return cli_failure(CMD, "cannot read stdin: %s", strerror(read_error));
  if (cli_stdout_failed(CMD)) return 1;
  return status;
}
