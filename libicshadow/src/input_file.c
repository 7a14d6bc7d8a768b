/* input_file.c — inputs opened as regular files only, with a size bound (icshadow/input_file.h).
 * O_NONBLOCK keeps open(2) from waiting for a FIFO's writer; the type and size are read from the
 * open descriptor (fstat), and O_NONBLOCK is cleared before the stream is handed out. */
#define _XOPEN_SOURCE 700
#include "icshadow/input_file.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *ics_input_kind(unsigned mode) {
  if (S_ISREG(mode)) return NULL;
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

static FILE *refuse(ics_status st, ics_status *status, int fd) {
  if (fd >= 0) close(fd);
  if (status) *status = st;
  return NULL;
}

FILE *ics_input_open(const char *path, uint64_t max_bytes, unsigned flags, ics_status *status,
                     char *why, size_t why_size) {
  if (why && why_size) why[0] = 0;
  if (status) *status = ICS_OK;
  int fd = path ? open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY) : -1;
  if (fd < 0) {
    if (why) snprintf(why, why_size, "%s", path ? strerror(errno) : "no file name");
    return refuse(ICS_ERR_IO, status, -1);
  }
  struct stat sb;
  if (fstat(fd, &sb) != 0) {
    if (why) snprintf(why, why_size, "%s", strerror(errno));
    return refuse(ICS_ERR_IO, status, fd);
  }
  const char *kind = ics_input_kind((unsigned)sb.st_mode);
  if (kind && (flags & ICS_INPUT_STREAM) && (S_ISFIFO(sb.st_mode) || S_ISCHR(sb.st_mode))) kind = NULL;
  if (kind) {
    if (why) snprintf(why, why_size, "not a regular file (%s)", kind);
    return refuse(ICS_ERR_IO, status, fd);
  }
  if (max_bytes && S_ISREG(sb.st_mode) && (uint64_t)sb.st_size > max_bytes) {
    if (why)
      snprintf(why, why_size, "%.4g bytes, more than the %.4g MiB this reader takes",
               (double)sb.st_size, (double)max_bytes / 1048576.0);
    return refuse(ICS_ERR_SIZE, status, fd);
  }
  int fl = fcntl(fd, F_GETFL);
  if (fl < 0 || fcntl(fd, F_SETFL, fl & ~O_NONBLOCK) != 0) {
    if (why) snprintf(why, why_size, "%s", strerror(errno));
    return refuse(ICS_ERR_IO, status, fd);
  }
  FILE *f = fdopen(fd, "rb");
  if (!f) {
    if (why) snprintf(why, why_size, "%s", strerror(errno));
    return refuse(ICS_ERR_NOMEM, status, fd);
  }
  return f;
}
