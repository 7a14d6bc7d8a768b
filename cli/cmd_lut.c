/* cmd_lut.c — `icshadow lut ...` (being written: see the lookup-table work). */
#include <stdio.h>
#include "commands.h"
int cmd_lut(int argc, char **argv) {
  (void)argc; (void)argv;
  fprintf(stderr, "icshadow lut: not built yet\n");
  return 1;
}
