/* icshadow.c — the command-line tool: dispatches to one subcommand per job (cmd_*.c),
 * each a thin layer over libicshadow. */
#include <stdio.h>
#include <string.h>

#include "commands.h"

#ifndef ICS_VERSION_STRING
#define ICS_VERSION_STRING "unknown"
#endif

static const struct {
  const char *name;
  int (*run)(int, char **);
  const char *summary;
} commands[] = {
    {"eval", cmd_eval, "evaluate a function on numbers read from stdin, one per line"},
    {"kernel", cmd_kernel, "print the taps of a kernel for a light (JSON)"},
    {"lut", cmd_lut, "write lookup-table headers (C, GLSL, OpenCL) or report their error"},
    {"isoline", cmd_isoline, "x position of a shadow isoline behind an edge (correct/iterative/CLT)"},
    {"clt", cmd_clt, "CLT convergence of iterated kernels: sup error against steps (CSV)"},
    {"iterate", cmd_iterate, "iterate a Heaviside edge with a 1D kernel member: profile after N steps (CSV)"},
    {"kernel-table", cmd_kernel_table, "Table I measured: moments, width, taps and cost of each 1D kernel member (CSV)"},
    {"bench", cmd_bench, "benchmark a peer primitive (sat2d, sat3d, minmax, occtex): CSV"},
    {"make-env", cmd_make_env, "draw Gaussian lights into a lat-long OpenEXR environment map"},
    {"fit-light", cmd_fit_light, "fit K Gaussian lights to an OpenEXR environment map (JSON + CSV)"},
    {"render", cmd_render, "render a scene with the slab renderer (the default scene without SCENE)"},
    {"plan", cmd_plan, "print a scene's render plan: passes, bytes, what is left out and why (JSON)"},
};

static void usage(FILE *f) {
  fprintf(f,
          "usage: icshadow COMMAND [OPTIONS]   (icshadow COMMAND --help for details)\n"
          "libicshadow %s: the theory of convolution soft shadows.\n\ncommands:\n",
          ICS_VERSION_STRING);
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].summary);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
    usage(stdout);
    return cli_stdout_failed(NULL);
  }
  if (!strcmp(argv[1], "--version")) {
    printf("icshadow %s\n", ICS_VERSION_STRING);
    return cli_stdout_failed(NULL);
  }
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
    if (!strcmp(argv[1], commands[i].name)) {
      int rc = commands[i].run(argc - 1, argv + 1);
      /* a command that succeeded without noticing stdout failed (--help on a full disk or a
       * closed stdout) must not exit 0 */
      if (rc == 0 && cli_stdout_failed(commands[i].name)) rc = 1;
      return rc;
    }
  cli_error(NULL, "unknown command '%s'", argv[1]);
  usage(stderr);
  return 2;
}
