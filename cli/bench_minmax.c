/* bench_minmax.c — (placeholder: being written by the minmax work). */
#include <stdio.h>
#include "commands.h"
int bench_minmax(int argc, char **argv) { (void)argc; (void)argv; fprintf(stderr, "not built yet\n"); return 1; }
