/* cmd_isoline.c — (placeholder: being written by the kernel-theory work). */
#include <stdio.h>
#include "commands.h"
int cmd_isoline(int argc, char **argv) {
  (void)argc; (void)argv;
  fprintf(stderr, "icshadow isoline: not built yet\n");
  return 1;
}
