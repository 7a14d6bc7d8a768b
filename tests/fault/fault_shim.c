/* fault_shim.c — an LD_PRELOAD library for the write-fault tests (tests/cli/write_faults.sh):
 * with ICS_FAULT=fsync or ICS_FAULT=rename, every call of that function fails with EIO (after
 * the first ICS_FAULT_AFTER calls, default 0); without ICS_FAULT it passes every call through.
 * The disk-full and device cases are made without it (RLIMIT_FSIZE, mknod: write_targets.sh). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

static int should_fail(const char *fn) {
  static int calls;
  const char *f = getenv("ICS_FAULT");
  if (!f || strcmp(f, fn)) return 0;
  const char *a = getenv("ICS_FAULT_AFTER");
  return ++calls > (a ? atoi(a) : 0);
}

int fsync(int fd) {
  static int (*real)(int);
  if (!real) real = (int (*)(int))dlsym(RTLD_NEXT, "fsync");
  if (should_fail("fsync")) {
    errno = EIO;
    return -1;
  }
  return real(fd);
}

int rename(const char *from, const char *to) {
  static int (*real)(const char *, const char *);
  if (!real) real = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
  if (should_fail("rename")) {
    errno = EIO;
    return -1;
  }
  return real(from, to);
}
