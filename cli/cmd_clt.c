/* cmd_clt.c — (placeholder: being written by the kernel-theory work). */
#include <stdio.h>
#include "commands.h"
int cmd_clt(int argc, char **argv) {
  (void)argc; (void)argv;
  fprintf(stderr, "icshadow clt: not built yet\n");
  return 1;
}
