/* fault_shim.c — an LD_PRELOAD library for the fault tests (tests/cli/write_faults.sh,
 * tests/render_gl.cmake): with ICS_FAULT=fsync or ICS_FAULT=rename, every call of that function
 * fails with EIO; with ICS_FAULT=gl-reset, glGetGraphicsResetStatus (as eglGetProcAddress and
 * OSMesaGetProcAddress hand it out) reports GL_GUILTY_CONTEXT_RESET, a lost context, which no
 * driver can be made to produce on demand; with ICS_FAULT=assimp-hang, Assimp's import
 * (aiImportFileEx, in the mesh reader's child) never returns, as a reader stuck on a malformed
 * file would. Each after the first ICS_FAULT_AFTER calls (default 0); without ICS_FAULT every
 * call passes through.
 * The disk-full and device cases are made without it (RLIMIT_FSIZE, mknod: write_targets.sh). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* the real function: the next definition in the global scope, else (a library the renderer's
 * modules opened with RTLD_LOCAL: EGL, OSMesa, Assimp) the one in that library, already loaded */
static void *real_fn(const char *name, const char *lib) {
  void *f = dlsym(RTLD_NEXT, name);
  if (!f && lib) {
    void *h = dlopen(lib, RTLD_LAZY | RTLD_NOLOAD);
    if (h) f = dlsym(h, name);
  }
  return f;
}

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

/* the lost context: a glGetGraphicsResetStatus that reports a reset */
typedef void (*gl_proc)(void);
static unsigned reset_status(void) { return should_fail("gl-reset") ? 0x8253u : 0u; } /* GUILTY */

static gl_proc hand_out(const char *name, gl_proc p) {
  const char *f = getenv("ICS_FAULT");
  if (p && f && !strcmp(f, "gl-reset") && !strcmp(name, "glGetGraphicsResetStatus"))
    return (gl_proc)reset_status;
  return p;
}

gl_proc eglGetProcAddress(const char *name) {
  static gl_proc (*real)(const char *);
  if (!real) real = (gl_proc(*)(const char *))real_fn("eglGetProcAddress", "libEGL.so.1");
  return real ? hand_out(name, real(name)) : NULL;
}

gl_proc OSMesaGetProcAddress(const char *name) {
  static gl_proc (*real)(const char *);
  if (!real) real = (gl_proc(*)(const char *))real_fn("OSMesaGetProcAddress", "libOSMesa.so.8");
  return real ? hand_out(name, real(name)) : NULL;
}

/* a mesh reader that never returns (the parent's time limit or death must end it) */
struct aiScene;
struct aiFileIO;
const struct aiScene *aiImportFileEx(const char *file, unsigned flags, struct aiFileIO *io) {
  static const struct aiScene *(*real)(const char *, unsigned, struct aiFileIO *);
  if (!real)
    real = (const struct aiScene *(*)(const char *, unsigned, struct aiFileIO *))real_fn(
        "aiImportFileEx", "libassimp.so.5");
  if (should_fail("assimp-hang"))
    for (;;) pause();
  return real(file, flags, io);
}
