/* mesh_assimp.c — the module icshadow-assimp.so (gpu/core/module.h): mesh files through Assimp,
 * in the child process that gpu/core/mesh_import.c forks and waits for (its header says why a
 * child: Assimp's readers abort or never return on some malformed files). The child's file
 * system for Assimp names every file it opens and refuses what is not a regular file or lies
 * outside the scene's folder; the triangles go back through the pipe (mesh_reader.h). */
#define _POSIX_C_SOURCE 200809L
#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include "icshadow/input_file.h"
#include "mesh.h"
#include "mesh_reader.h"
#include "module.h"
#include "path_inside.h"

/* ---- the child's file system for Assimp: every file it opens (the mesh, a glTF's buffers, an
 * OBJ's materials) through ics_input_open, so no FIFO or device blocks it, and their names kept
 * for the parent, which adds them to the scene's inputs (no output may replace them) ---- */
static char *child_files;           /* the names opened besides the mesh itself, NUL-terminated */
static uint32_t child_files_bytes;
static const char *child_mesh_path;
static const char *child_root;      /* the folder every file must lie in (NULL: anywhere) */
static char child_refused[1024];    /* the first file refused, with the reason */
static int child_outside;           /* one was outside child_root: the import fails */

static size_t io_read(struct aiFile *f, char *buf, size_t size, size_t count) {
  return fread(buf, size, count, (FILE *)f->UserData);
}
static size_t io_write(struct aiFile *f, const char *buf, size_t size, size_t count) {
  (void)f, (void)buf, (void)size, (void)count;
  return 0; /* the reader never writes */
}
static size_t io_tell(struct aiFile *f) {
  long p = ftell((FILE *)f->UserData);
  return p < 0 ? 0 : (size_t)p;
}
static size_t io_size(struct aiFile *f) {
  struct stat sb;
  return fstat(fileno((FILE *)f->UserData), &sb) ? 0 : (size_t)sb.st_size;
}
static enum aiReturn io_seek(struct aiFile *f, size_t off, enum aiOrigin origin) {
  int whence = origin == aiOrigin_CUR ? SEEK_CUR : origin == aiOrigin_END ? SEEK_END : SEEK_SET;
  return fseek((FILE *)f->UserData, (long)off, whence) ? aiReturn_FAILURE : aiReturn_SUCCESS;
}
static void io_flush(struct aiFile *f) { (void)f; }

static void note_file(const char *name) {
  size_t n = strlen(name) + 1;
  if (!strcmp(name, child_mesh_path)) return;
  for (uint32_t at = 0; at < child_files_bytes; at += (uint32_t)strlen(child_files + at) + 1)
    if (!strcmp(child_files + at, name)) return;
  char *grown = child_files_bytes + n <= ICS_MESH_CHILD_FILES_MAX ? realloc(child_files, child_files_bytes + n) : NULL;
  if (!grown) _exit(3); /* the parent reports a reader that stopped early */
  child_files = grown;
  memcpy(child_files + child_files_bytes, name, n);
  child_files_bytes += (uint32_t)n;
}

static struct aiFile *io_open(struct aiFileIO *io, const char *name, const char *mode) {
  (void)io;
  if (strpbrk(mode, "wa+")) return NULL;
  char why[sizeof child_refused];
  if (ics_path_check_inside(name, child_root, why, sizeof why) != ICS_OK) {
    if (!child_outside) snprintf(child_refused, sizeof child_refused, "%s", why);
    child_outside = 1;
    return NULL;
  }
  char reason[256];
  FILE *fp = ics_input_open(name, 0, 0, NULL, reason, sizeof reason);
  if (!fp) {
    if (!child_refused[0])
      snprintf(child_refused, sizeof child_refused, "it needs %.700s: %s", name, reason);
    return NULL;
  }
  struct aiFile *f = calloc(1, sizeof *f);
  if (!f) _exit(3);
  *f = (struct aiFile){io_read, io_write, io_tell, io_size, io_seek, io_flush, (aiUserData)fp};
  note_file(name);
  return f;
}
static void io_close(struct aiFileIO *io, struct aiFile *f) {
  (void)io;
  if (f) fclose((FILE *)f->UserData);
  free(f);
}

static int write_all(int fd, const void *p, size_t n) {
  const char *c = p;
  while (n) {
    ssize_t w = write(fd, c, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return -1;
    c += w, n -= (size_t)w;
  }
  return 0;
}

/* the child: Assimp's import, sent through fd; never returns */
static void child_import(int fd, const char *path, const char *root, pid_t parent) {
#ifdef __linux__
  /* dies with the parent (killed while Assimp spins or blocks, it would be orphaned for good);
   * a parent already gone before the request took effect is caught by getppid */
  prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
  if (getppid() != parent) _exit(1);
  /* the caller's crash handlers (a fuzzer's, a crash reporter's) are not for Assimp's aborts:
   * the default dispositions, so that the parent sees the signal */
  static const int sigs[] = {SIGABRT, SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGPIPE};
  for (size_t i = 0; i < sizeof sigs / sizeof *sigs; i++) signal(sigs[i], SIG_DFL);
  sigset_t all;
  sigemptyset(&all);
  sigprocmask(SIG_SETMASK, &all, NULL);
  ics_mesh_child_header h;
  memset(&h, 0, sizeof h);
  child_mesh_path = path;
  child_root = root;
  struct aiFileIO io = {io_open, io_close, NULL};
  const struct aiScene *sc = aiImportFileEx(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices,
      &io);
  if (!sc || child_outside) { /* (Assimp reads on without an OBJ's materials: refused anyway) */
    /* Assimp turns its exceptions into the error string: std::bad_alloc is out of memory */
    const char *why = aiGetErrorString();
    h.status = child_outside         ? ICS_ERR_INVALID_ARG
               : child_refused[0]    ? ICS_ERR_IO
               : !strcmp(why, "std::bad_alloc") ? ICS_ERR_NOMEM
                                     : ICS_ERR_PARSE;
    if (child_refused[0])
      snprintf(h.msg, sizeof h.msg, "cannot read mesh: %s", child_refused);
    else if (h.status == ICS_ERR_NOMEM)
      snprintf(h.msg, sizeof h.msg, "cannot read mesh: out of memory (%s)", why);
    else
      snprintf(h.msg, sizeof h.msg, "cannot read mesh: %s", why);
    _exit(write_all(fd, &h, sizeof h) ? 1 : 0);
  }
  for (unsigned i = 0; i < sc->mNumMeshes; i++) {
    h.nv += sc->mMeshes[i]->mNumVertices;
    for (unsigned f = 0; f < sc->mMeshes[i]->mNumFaces; f++)
      h.nt += sc->mMeshes[i]->mFaces[f].mNumIndices == 3;
  }
  if (h.nt == 0 || h.nt > ICS_MESH_MAX_TRIANGLES || h.nv > (uint64_t)INT32_MAX / 3) {
    h.status = ICS_ERR_SIZE;
    if (h.nv > (uint64_t)INT32_MAX / 3)
      snprintf(h.msg, sizeof h.msg, "%llu vertices (at most %d)", (unsigned long long)h.nv,
               INT32_MAX / 3);
    else
      snprintf(h.msg, sizeof h.msg, "%llu triangles (expected 1..%d)", (unsigned long long)h.nt,
               ICS_MESH_MAX_TRIANGLES);
    h.nv = h.nt = 0;
    _exit(write_all(fd, &h, sizeof h) ? 1 : 0);
  }
  for (unsigned i = 0; i < sc->mNumMeshes; i++) { /* every index within its mesh's vertices */
    const struct aiMesh *me = sc->mMeshes[i];
    for (unsigned f = 0; f < me->mNumFaces; f++)
      for (unsigned k = 0; me->mFaces[f].mNumIndices == 3 && k < 3; k++)
        if (me->mFaces[f].mIndices[k] >= me->mNumVertices) {
          h.status = ICS_ERR_PARSE;
          snprintf(h.msg, sizeof h.msg, "mesh %u, face %u: vertex index %u of %u vertices", i, f,
                   me->mFaces[f].mIndices[k], me->mNumVertices);
          h.nv = h.nt = 0;
          _exit(write_all(fd, &h, sizeof h) ? 1 : 0);
        }
  }
  h.files_bytes = child_files_bytes;
  int bad = write_all(fd, &h, sizeof h) || (child_files_bytes && write_all(fd, child_files, child_files_bytes));
  float v[3 * 256];
  uint32_t t[3 * 256];
  for (unsigned i = 0; i < sc->mNumMeshes && !bad; i++) {
    const struct aiMesh *me = sc->mMeshes[i];
    for (unsigned k = 0; k < me->mNumVertices && !bad; k += 256) {
      unsigned n = me->mNumVertices - k < 256 ? me->mNumVertices - k : 256;
      for (unsigned j = 0; j < n; j++)
        v[3 * j] = (float)me->mVertices[k + j].x, v[3 * j + 1] = (float)me->mVertices[k + j].y,
        v[3 * j + 2] = (float)me->mVertices[k + j].z;
      bad = write_all(fd, v, sizeof *v * 3 * n);
    }
  }
  uint32_t vbase = 0;
  unsigned n = 0;
  for (unsigned i = 0; i < sc->mNumMeshes && !bad; i++) {
    const struct aiMesh *me = sc->mMeshes[i];
    for (unsigned f = 0; f < me->mNumFaces && !bad; f++) {
      if (me->mFaces[f].mNumIndices != 3) continue;
      for (int k = 0; k < 3; k++) t[3 * n + k] = vbase + me->mFaces[f].mIndices[k];
      if (++n == 256) bad = write_all(fd, t, sizeof *t * 3 * n), n = 0;
    }
    vbase += me->mNumVertices;
  }
  if (!bad && n) bad = write_all(fd, t, sizeof *t * 3 * n);
  _exit(bad ? 1 : 0);
}

static const ics_mesh_reader_funcs funcs = {child_import};
ICS_MODULE_DEFINE("assimp", &funcs)
