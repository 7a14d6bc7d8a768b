/* path_inside.h — the rule that a scene reads files only in its own folder or below it
 * (docs/scene-format.md "Files a scene reads"), checked before each file is opened. */
#ifndef ICS_RENDER_PATH_INSIDE_H
#define ICS_RENDER_PATH_INSIDE_H

#include <stddef.h>

#include "icshadow/status.h"

/* ICS_OK when `path` resolves (symbolic links followed) to `root` or a name below it, or does
 * not exist (a missing file or folder, a link loop: its open reports why); ICS_ERR_INVALID_ARG
 * when it resolves elsewhere or cannot be resolved otherwise (ENAMETOOLONG, EACCES, ...), msg
 * naming the file, where it leads and the folder; ICS_ERR_NOMEM. root: a folder as realpath
 * gives it; NULL allows every path. */
ics_status ics_path_check_inside(const char *path, const char *root, char *msg, size_t msg_size);

#endif
