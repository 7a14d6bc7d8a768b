/* bench_sat.c — (placeholder: being written by the summed-area-table work). */
#include <stdio.h>
#include "commands.h"
int bench_sat2d(int argc, char **argv) { (void)argc; (void)argv; fprintf(stderr, "not built yet\n"); return 1; }
int bench_sat3d(int argc, char **argv) { (void)argc; (void)argv; fprintf(stderr, "not built yet\n"); return 1; }
