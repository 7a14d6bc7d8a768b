/* path_inside.c — a scene's files lie in its folder or below it (path_inside.h). */
#define _XOPEN_SOURCE 700 /* realpath */
#include "path_inside.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ics_status ics_path_check_inside(const char *path, const char *root, char *msg, size_t msg_size) {
  if (!root) return ICS_OK;
  errno = 0;
  char *real = realpath(path, NULL);
  if (!real) {
    /* a missing file, a component that is not a folder, a link loop: the open fails with its own
     * reason; any other failure (a resolved name over PATH_MAX through a chain of links, which
     * the kernel still opens) is refused: the rule fails closed */
    int e = errno;
    if (e == ENOENT || e == ENOTDIR || e == ELOOP) return ICS_OK;
    if (e == ENOMEM) return ICS_ERR_NOMEM;
    if (msg && msg_size)
      snprintf(msg, msg_size, "the file %s cannot be resolved (%s), so it cannot be shown to lie in "
               "the scene's folder %s (give --allow-outside-paths to read it)", path, strerror(e),
               root);
    return ICS_ERR_INVALID_ARG;
  }
  size_t n = strlen(root);
  int inside = !strncmp(real, root, n) && (real[n] == '/' || real[n] == 0 || !strcmp(root, "/"));
  if (!inside && msg && msg_size)
    snprintf(msg, msg_size, "the file %s (%s) lies outside the scene's folder %s (give "
             "--allow-outside-paths to read it)", path, real, root);
  free(real);
  return inside ? ICS_OK : ICS_ERR_INVALID_ARG;
}
