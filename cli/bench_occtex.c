/* bench_occtex.c — (placeholder: being written by the occtex work). */
#include <stdio.h>
#include "commands.h"
int bench_occtex(int argc, char **argv) { (void)argc; (void)argv; fprintf(stderr, "not built yet\n"); return 1; }
