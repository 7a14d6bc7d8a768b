/* cmd_bench.c — `icshadow bench KIND [options]`: dispatches to the benchmark of one peer
 * primitive, of the slab renderer's propagation or of whole frames (bench_<kind>.c). Each prints one CSV line per configuration. */
#include <stdio.h>
#include <string.h>

#include "commands.h"

static const struct {
  const char *name;
  int (*run)(int, char **);
  const char *summary;
} kinds[] = {
    {"sat2d", bench_sat2d, "2D summed-area table: time, bytes, fraction of the memcpy floor"},
    {"sat3d", bench_sat3d, "3D summed-area table: time, bytes, fraction of the memcpy floor"},
    {"minmax", bench_minmax, "1D min-max mipmap traversal vs brute-force ray marching"},
    {"occtex", bench_occtex, "occlusion textures: prefilters and combinations vs brute force"},
    {"slab", bench_slab, "light-buffer propagation per kernel member and backend vs the memcpy floor"},
    {"frame", bench_frame, "whole frames of a scene: skipping, dense and Monte Carlo side by side"},
};

static void help(FILE *f) {
  fprintf(f, "usage: icshadow bench KIND [options]   (icshadow bench KIND --help)\n\nKIND:\n");
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
    fprintf(f, "  %-7s %s\n", kinds[i].name, kinds[i].summary);
}

int cmd_bench(int argc, char **argv) {
  if (argc < 2 || !strcmp(argv[1], "-h") || !strcmp(argv[1], "--help")) {
    help(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
    if (!strcmp(argv[1], kinds[i].name)) return kinds[i].run(argc - 1, argv + 1);
  cli_error("bench", "unknown kind '%s'", argv[1]);
  help(stderr);
  return 2;
}
