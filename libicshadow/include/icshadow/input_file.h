/* icshadow/input_file.h — opening a file the user named as an input (a scene, a lights file, a
 * grid, a mesh, an EXR): only a regular file is read, and only up to a stated size. A FIFO, a
 * device or a directory is refused at once with the reason, never opened in a way that could
 * block (the open itself is non-blocking and the type is checked on the open descriptor, so a
 * path swapped between a check and the open cannot slip a FIFO in). */
#ifndef ICSHADOW_INPUT_FILE_H
#define ICSHADOW_INPUT_FILE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "icshadow/api.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Opens `path` for reading ("rb") when it is a regular file of at most max_bytes bytes
 * (0: any size). With ICS_INPUT_STREAM in flags a FIFO or a character device (a pipe given as
 * /dev/stdin) is opened too, as a stream: the caller bounds what it reads from it (the open
 * itself never waits for a writer; a read of a FIFO nobody writes to ends at once). On failure
 * returns NULL with *status set (ICS_ERR_IO: cannot open, or not a regular file; ICS_ERR_SIZE:
 * larger than max_bytes) and, when why is non-NULL, a reason without the path ("not a regular
 * file (a FIFO)", "No such file or directory", "1.2e+08 bytes, more than the 64 MiB this
 * reader takes"). status may be NULL. */
#define ICS_INPUT_STREAM 1u
ICS_API FILE *ics_input_open(const char *path, uint64_t max_bytes, unsigned flags,
                             ics_status *status, char *why, size_t why_size);

/* What a non-regular file type is called in those messages ("a FIFO", "a directory", ...);
 * NULL for a regular file. mode is a struct stat's st_mode. */
ICS_API const char *ics_input_kind(unsigned mode);

#ifdef __cplusplus
}
#endif
#endif
