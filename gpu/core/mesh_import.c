/* mesh_import.c — mesh files through Assimp (ics_mesh_create_file, mesh.h), read in a child
 * process by the module icshadow-assimp.so (gpu/readers/assimp, loaded before the fork;
 * gpu/core/module.h), so nothing maps Assimp unless a scene has a mesh file.
 *
 * Assimp's readers are not hardened against malformed files. fuzz/fuzz_mesh_file.c found
 * Debian's Assimp 5.2.5 aborting the process on an assertion (a post-processing step, on a PLY
 * file with a damaged header) and never returning (a PLY header without end_header: it seeks at
 * the end of the file forever). So the import runs in a child (fork), which sends the vertex
 * positions back as Assimp holds them (floats) and the triangles as global vertex indices,
 * through a pipe. The parent applies scale, rotation and translation in double precision and
 * builds the mesh (ics_mesh_create_triangles). A child that dies, exits early or is not done
 * within the time limit becomes the file's error: no crash, no hang. The time limit is 60 s plus
 * 2 s per MiB of file by default, which leaves Assimp's speed on large legitimate files
 * (tens of MB/s) far inside it. A PLY header without end_header is refused before Assimp
 * sees it: a message at once rather than a timeout; so is a file that is not a regular file (a
 * FIFO would block). fork is called from the thread that reads the scene, which waits for the
 * child; the child asks to be killed when that thread ends (PR_SET_PDEATHSIG), i.e. when the
 * process is killed meanwhile (while Assimp spins or blocks it would otherwise be orphaned for
 * good), restores the default crash-signal dispositions (a
 * caller's crash handler is not for Assimp's aborts), runs Assimp and _exits. A caller must not ignore SIGCHLD or reap children it did not start, and,
 * since the child runs C++ code after fork, should read scenes before starting threads that may
 * hold the C or C++ runtime's locks (the CLI does). */
#define _POSIX_C_SOURCE 200809L
#include "mesh.h"

#include "icshadow/input_file.h"
#include "path_inside.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef ICS_HAVE_ASSIMP
#include "mesh_reader.h"
#include "module.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#endif

int ics_mesh_files_supported(void) {
#ifdef ICS_HAVE_ASSIMP
  return 1;
#else
  return 0;
#endif
}

#define PLY_HEADER_MAX 65536

/* s with trailing blanks, tabs and line ends removed: 1 when it is `word` */
static int is_word(char *s, const char *word) {
  size_t n = strlen(s);
  while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n')) s[--n] = 0;
  return !strcmp(s, word);
}

/* 1 when a file's first line passes Assimp 5.2.5's PLY test: "ply" in any case, anything after */
static int ply_magic(const char *line) {
  for (int i = 0; i < 3; i++)
    if (line[i] != "ply"[i] && line[i] != "PLY"[i]) return 0;
  return 1;
}

uint64_t ics_mesh_file_faces(const char *path) {
  char why[256], line[256];
  FILE *f = ics_input_open(path, 0, 0, NULL, why, sizeof why);
  if (!f) return 0;
  uint64_t faces = 0;
  if (fgets(line, sizeof line, f) && ply_magic(line)) {
    static const char key[] = "element face ";
    for (long pos = ftell(f); pos >= 0 && pos < PLY_HEADER_MAX && fgets(line, sizeof line, f);
         pos = ftell(f)) {
      if (!strncmp(line, key, sizeof key - 1) && line[sizeof key - 1] >= '0' &&
          line[sizeof key - 1] <= '9') {
        errno = 0;
        unsigned long long n = strtoull(line + sizeof key - 1, NULL, 10);
        faces = errno ? 0 : n; /* (a count past 2^64 is no count) */
      }
      if (is_word(line, "end_header")) break;
    }
  }
  fclose(f);
  return faces;
}

#ifdef ICS_HAVE_ASSIMP

/* 1 when Assimp would not take f for PLY, or when a line that is "end_header" starts within its
 * first PLY_HEADER_MAX bytes (positions from ftell: NUL bytes do not shorten them; only whole
 * lines count, not the tail of a line longer than the buffer). Both as Assimp 5.2.5 reads them:
 * its magic test takes "ply" in any case ("PLY" too) with anything after it, its header parser
 * only an exact, lower-case end_header. */
static int ply_header_ended(FILE *f) {
  char line[256];
  if (!fgets(line, sizeof line, f) || !ply_magic(line)) return 1;
  int at_start = 1;
  for (long pos = ftell(f); pos >= 0 && pos < PLY_HEADER_MAX && fgets(line, sizeof line, f);
       pos = ftell(f)) {
    int whole = strchr(line, '\n') != NULL;
    if (at_start && is_word(line, "end_header")) return 1;
    at_start = whole;
  }
  return 0;
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* reads n bytes before `deadline`: 0, or 1 the child closed early, 2 time out, 3 a read error */
static int read_all(int fd, void *p, size_t n, double deadline) {
  char *c = p;
  while (n) {
    double left = deadline - now_s();
    if (left <= 0) return 2;
    struct pollfd pf = {fd, POLLIN, 0};
    int r = poll(&pf, 1, (int)fmin(left * 1000 + 1, 60000));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) return 3;
    if (r == 0) continue;
    ssize_t got = read(fd, c, n);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return 3;
    if (got == 0) return 1;
    c += got, n -= (size_t)got;
  }
  return 0;
}
#endif

ics_status ics_mesh_read_file(ics_mesh_raw *raw, const char *path, double seconds,
                              const char *root, char *msg, size_t msg_size) {
  memset(raw, 0, sizeof *raw);
#ifndef ICS_HAVE_ASSIMP
  (void)seconds, (void)root;
  if (msg)
    snprintf(msg, msg_size, "%s: mesh files need Assimp, which was not found when the renderer "
             "was built (install libassimp-dev and rebuild)", path);
  return ICS_ERR_UNSUPPORTED;
#else
  struct stat sb;
  char why[256];
  FILE *probe = ics_input_open(path, 0, 0, NULL, why, sizeof why);
  if (!probe || fstat(fileno(probe), &sb)) {
    if (probe) fclose(probe);
    if (msg) snprintf(msg, msg_size, "%s: cannot open mesh file: %s", path, probe ? strerror(errno) : why);
    return ICS_ERR_IO;
  }
  int header_ok = ply_header_ended(probe);
  fclose(probe);
  if (!header_ok) {
    if (msg)
      snprintf(msg, msg_size, "%s: a PLY header without an end_header line in its first %d bytes",
               path, PLY_HEADER_MAX);
    return ICS_ERR_PARSE;
  }
  if (!(seconds > 0)) seconds = 60 + 2 * (double)sb.st_size / 1048576.0;
  char why_module[1024];
  const ics_mesh_reader_funcs *reader = ics_module_api("assimp", why_module, sizeof why_module);
  if (!reader) {
    if (msg) snprintf(msg, msg_size, "%s: mesh files need Assimp's reader: %s", path, why_module);
    return ICS_ERR_UNSUPPORTED;
  }
  int fds[2];
  if (pipe(fds) || fcntl(fds[0], F_SETFD, FD_CLOEXEC) || fcntl(fds[1], F_SETFD, FD_CLOEXEC)) {
    if (msg) snprintf(msg, msg_size, "%s: cannot start the mesh reader: %s", path, strerror(errno));
    return ICS_ERR_IO;
  }
  fflush(NULL); /* nothing buffered twice */
  pid_t parent = getpid(), pid = fork();
  if (pid < 0) {
    if (msg) snprintf(msg, msg_size, "%s: cannot start the mesh reader: %s", path, strerror(errno));
    close(fds[0]), close(fds[1]);
    return ICS_ERR_IO;
  }
  if (pid == 0) {
    close(fds[0]);
    reader->child_import(fds[1], path, root, parent);
  }
  close(fds[1]);
  double deadline = now_s() + seconds;
  ics_mesh_child_header h;
  char *names = NULL;
  float *v = NULL;
  uint32_t *t = NULL;
  ics_status st = ICS_OK;
  int r = read_all(fds[0], &h, sizeof h, deadline);
  if (r == 0) {
    h.msg[sizeof h.msg - 1] = 0;
    if (h.status != ICS_OK) {
      st = h.status == ICS_ERR_SIZE || h.status == ICS_ERR_IO || h.status == ICS_ERR_NOMEM ||
                   h.status == ICS_ERR_INVALID_ARG
               ? (ics_status)h.status
               : ICS_ERR_PARSE;
      if (msg) snprintf(msg, msg_size, "%s: %s", path, h.msg);
    } else if (h.nt == 0 || h.nt > ICS_MESH_MAX_TRIANGLES || h.nv > (uint64_t)INT32_MAX / 3 ||
               h.files_bytes > ICS_MESH_CHILD_FILES_MAX) {
      st = ICS_ERR_PARSE; /* the child's own checks: a header it cannot have sent */
      if (msg) snprintf(msg, msg_size, "%s: the mesh reader sent %llu vertices and %llu triangles",
                        path, (unsigned long long)h.nv, (unsigned long long)h.nt);
    } else if (!(names = malloc((size_t)h.files_bytes + 1)) ||
               !(v = malloc(sizeof *v * 3 * (size_t)(h.nv ? h.nv : 1))) ||
               !(t = malloc(sizeof *t * 3 * (size_t)h.nt))) {
      st = ICS_ERR_NOMEM;
      if (msg) snprintf(msg, msg_size, "%s: out of memory for %llu vertices", path,
                        (unsigned long long)h.nv);
    } else {
      r = read_all(fds[0], names, h.files_bytes, deadline);
      names[h.files_bytes] = 0; /* the list ends with an empty name */
      if (r == 0 && h.files_bytes && names[h.files_bytes - 1]) r = 1;
      if (r == 0) r = read_all(fds[0], v, sizeof *v * 3 * (size_t)h.nv, deadline);
      if (r == 0) r = read_all(fds[0], t, sizeof *t * 3 * (size_t)h.nt, deadline);
    }
  }
  if (r != 0 || st != ICS_OK) kill(pid, SIGKILL); /* it may be stuck; not reaped yet: still ours */
  close(fds[0]);
  int ws = 0;
  pid_t got;
  while ((got = waitpid(pid, &ws, 0)) < 0 && errno == EINTR) {}
  if (got != pid) ws = 0; /* SIGCHLD ignored or reaped elsewhere: the cause is unknown */
  if (r != 0 && st == ICS_OK) {
    st = ICS_ERR_PARSE;
    if (msg) {
      if (r == 2)
        snprintf(msg, msg_size, "%s: Assimp did not finish reading the mesh within %.3g s", path,
                 seconds);
      else if (WIFSIGNALED(ws) && WTERMSIG(ws) != SIGKILL)
        snprintf(msg, msg_size, "%s: Assimp failed on this file (its reader died of signal %d, "
                 "%s)", path, WTERMSIG(ws), strsignal(WTERMSIG(ws)));
      else
        snprintf(msg, msg_size, "%s: the mesh reader stopped before sending the mesh", path);
    }
  }
  if (st == ICS_OK) {
    int *tri = (int *)t; /* indices past INT32_MAX are refused as out of range */
    for (size_t k = 0; k < 3 * h.nt; k++) tri[k] = t[k] > INT32_MAX ? -1 : (int)t[k];
    *raw = (ics_mesh_raw){v, tri, h.nv, h.nt, names};
    return ICS_OK;
  }
  free(names), free(v), free(t);
  return st;
#endif
}

void ics_mesh_raw_release(ics_mesh_raw *raw) {
  free(raw->v), free(raw->tri), free(raw->files);
  memset(raw, 0, sizeof *raw);
}

/* a mesh as Assimp gave it that cannot make a surface, named: a vertex not finite, an index out
 * of range, fewer than three distinct vertices (Assimp joins identical ones), no triangle of
 * non-zero area */
static ics_status raw_check(const ics_mesh_raw *raw, const char *path, char *msg, size_t msg_size) {
  for (uint64_t k = 0; k < raw->nv; k++) {
    const float *v = raw->v + 3 * k;
    if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) {
      if (msg) snprintf(msg, msg_size, "%s: vertex %llu is (%g, %g, %g): not finite", path,
                        (unsigned long long)k, v[0], v[1], v[2]);
      return ICS_ERR_NAN;
    }
  }
  int area = 0;
  for (uint64_t t = 0; t < raw->nt && !area; t++) {
    const int *i = raw->tri + 3 * t;
    if (i[0] < 0 || i[1] < 0 || i[2] < 0) continue; /* ics_mesh_create_triangles names it */
    const float *a = raw->v + 3 * i[0], *b = raw->v + 3 * i[1], *c = raw->v + 3 * i[2];
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    area = e1[1] * e2[2] - e1[2] * e2[1] != 0 || e1[2] * e2[0] - e1[0] * e2[2] != 0 ||
           e1[0] * e2[1] - e1[1] * e2[0] != 0;
  }
  if (raw->nv < 3 || !area) {
    if (msg) snprintf(msg, msg_size, "%s: no triangle of non-zero area (%llu distinct vertices, "
                      "%llu triangles): the mesh has no surface", path,
                      (unsigned long long)raw->nv, (unsigned long long)raw->nt);
    return ICS_ERR_SIZE;
  }
  return ICS_OK;
}

ics_status ics_mesh_create_raw(ics_mesh **out, const ics_mesh_raw *raw, const double scale[3],
                               const double rot_deg[3], const double translate[3],
                               const char *path, char *msg, size_t msg_size) {
  *out = NULL;
  ics_status st = raw_check(raw, path, msg, msg_size);
  if (st != ICS_OK) return st;
  double *xyz = malloc(sizeof *xyz * 3 * (size_t)(raw->nv ? raw->nv : 1));
  if (!xyz) {
    if (msg) snprintf(msg, msg_size, "%s: out of memory for %llu vertices", path,
                      (unsigned long long)raw->nv);
    return ICS_ERR_NOMEM;
  }
  double ax[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ics_frame_rotate(ax, rot_deg);
  /* ax's rows are the rotated world axes; a point's rotated image is sum_i p_i ax[i] */
  for (size_t k = 0; k < raw->nv; k++) {
    const float *v = raw->v + 3 * k;
    double p[3] = {v[0] * scale[0], v[1] * scale[1], v[2] * scale[2]};
    for (int w = 0; w < 3; w++)
      xyz[3 * k + w] = p[0] * ax[0][w] + p[1] * ax[1][w] + p[2] * ax[2][w] + translate[w];
  }
  st = ics_mesh_create_triangles(out, xyz, (int)raw->nv, raw->tri, (int)raw->nt);
  if (st == ICS_ERR_NAN && msg)
    snprintf(msg, msg_size, "%s: a vertex under the object's scale, rotation and translation is "
             "not finite (over 1.8e308)", path);
  else if (st == ICS_ERR_INVALID_ARG && msg)
    snprintf(msg, msg_size, "%s: a triangle names a vertex that does not exist", path);
  else if (st != ICS_OK && msg)
    snprintf(msg, msg_size, "%s: %s", path, ics_status_str(st));
  free(xyz);
  return st;
}

ics_status ics_mesh_create_file(ics_mesh **out, const char *path, const double scale[3],
                                const double rot_deg[3], const double translate[3],
                                double seconds, char **files, char *msg, size_t msg_size) {
  *out = NULL;
  if (files) *files = NULL;
  ics_mesh_raw raw;
  ics_status st = ics_mesh_read_file(&raw, path, seconds, NULL, msg, msg_size);
  if (st == ICS_OK) st = ics_mesh_create_raw(out, &raw, scale, rot_deg, translate, path, msg, msg_size);
  if (st == ICS_OK && files) *files = raw.files, raw.files = NULL;
  ics_mesh_raw_release(&raw);
  return st;
}
