/* cmd_kernel.c — `icshadow kernel ellipse ...` (being written: see the ellipse work). */
#include <stdio.h>
#include "commands.h"
int cmd_kernel(int argc, char **argv) {
  (void)argc; (void)argv;
  fprintf(stderr, "icshadow kernel: not built yet\n");
  return 1;
}
