/* module.c — loading the renderer's modules on first use (module.h): the folder, dlopen, the
 * entry's check, the host's table handed over once; every outcome remembered per module. */
#define _GNU_SOURCE /* dladdr1 */
#include "module.h"

#include <dlfcn.h>
#include <limits.h>
#include <link.h>
#include <sys/stat.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "icshadow/renderer.h"
#include "module_host.h"

/* the modules built (gpu/CMakeLists.txt), with what each is for */
static const struct {
  const char *name, *purpose;
} built[] = {
#ifdef ICS_HAVE_GL
    {"gl", "the gl backend (EGL, OSMesa)"},
#endif
#ifdef ICS_HAVE_OPENCL
    {"cl", "the cl backend (OpenCL, opened on first use)"},
#endif
#ifdef ICS_HAVE_EMBREE
    {"embree", "the reference's mesh crossings through Embree 3"},
#endif
#ifdef ICS_HAVE_ASSIMP
    {"assimp", "mesh files through Assimp"},
#endif
    {NULL, NULL}};
#define NBUILT ((int)(sizeof built / sizeof *built) - 1)

#define MAX_MODULES 8
#define WHY_SIZE 1024

typedef struct loaded {
  char name[32];
  void *handle;
  const void *api;
  char why[WHY_SIZE]; /* the failure, when api is NULL */
} loaded;

/* the renderer's functions a module may call (module_host.h) */
#define HOST_ENTRY_(ret, name, params, args) name,
#define HOST_VENTRY_(name, params, args) name,
const struct ics_module_host ics_module_host_table = {
    ICS_MODULE_HOST_FUNCS(HOST_ENTRY_, HOST_VENTRY_)};
#undef HOST_ENTRY_
#undef HOST_VENTRY_

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static loaded mods[MAX_MODULES];
static int nmods;

/* the folder of the object that holds this code (the library, or the program that links it
 * statically: its link map has no name, and /proc/self/exe is its file), into dir; 0 when it
 * cannot be told */
static int own_folder(char *dir, size_t size) {
  Dl_info info;
  struct link_map *lm = NULL;
  char path[PATH_MAX];
  if (!dladdr1((const void *)&own_folder, &info, (void **)&lm, RTLD_DL_LINKMAP)) return 0;
  if (lm && lm->l_name && lm->l_name[0]) {
    if (!realpath(lm->l_name, path)) return 0;
  } else {
    ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    if (n <= 0) return 0;
    path[n] = 0;
  }
  char *slash = strrchr(path, '/');
  if (!slash) return 0;
  *slash = 0;
  return snprintf(dir, size, "%s", path) < (int)size;
}

/* folder + "/" + rel, resolved, into dirs[*n] (PATH_MAX), counted when it is a folder not
 * already there */
static void add_folder(char dirs[][PATH_MAX], int *n, const char *folder, const char *rel) {
  char path[PATH_MAX];
  struct stat sb;
  int w = snprintf(path, sizeof path, "%s%s%s", folder, rel[0] ? "/" : "", rel);
  if (w <= 0 || w >= PATH_MAX || !realpath(path, dirs[*n]) || stat(dirs[*n], &sb) ||
      !S_ISDIR(sb.st_mode))
    return;
  for (int i = 0; i < *n; i++)
    if (!strcmp(dirs[i], dirs[*n])) return;
  (*n)++;
}

/* the folders to try, in order, into dirs (at least 3 of PATH_MAX); their count */
static int module_folders(char dirs[][PATH_MAX]) {
  int n = 0;
  char own[PATH_MAX];
  if (own_folder(own, sizeof own)) {
    add_folder(dirs, &n, own, "icshadow");                    /* LIBDIR/ */
    add_folder(dirs, &n, own, ICS_MODULE_DIR_FROM_BIN);       /* bin/, installed */
    add_folder(dirs, &n, own, ICS_MODULE_DIR_FROM_BUILD_BIN); /* bin/, the build tree */
  }
  return n;
}

/* 1 when module `name` was built (the table above) */
static int was_built(const char *name) {
  for (int i = 0; i < NBUILT; i++)
    if (!strcmp(built[i].name, name)) return 1;
  return 0;
}

/* the reason module m does not load (a message cut at its buffer's end is still a message) */
__attribute__((format(printf, 2, 3))) static void refuse(loaded *m, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  if (vsnprintf(m->why, sizeof m->why, fmt, ap) < 0) m->why[0] = 0;
  va_end(ap);
}

static void load(loaded *m) {
  char dirs[3][PATH_MAX], file[PATH_MAX], tried[WHY_SIZE] = "";
  const char *env = getenv("ICS_MODULE_DIR");
  int nd = 1;
  if (env && env[0]) /* only there, tried even when it is not a folder (the message says so) */
    snprintf(dirs[0], PATH_MAX, "%s", env);
  else
    nd = module_folders(dirs);
  if (!was_built(m->name)) {
    refuse(m, "module %s was not built (its library was not found when the renderer was built; "
           "`icshadow render --backends` lists the modules)", m->name);
    return;
  }
  for (int i = 0; i < nd; i++) {
    int w = snprintf(file, sizeof file, "%s/icshadow-%s.so", dirs[i], m->name);
    if (w < 0 || w >= (int)sizeof file || access(file, F_OK) != 0) {
      size_t t = strlen(tried);
      if (snprintf(tried + t, sizeof tried - t, "%s%s", t ? ", " : "", dirs[i]) < 0) tried[t] = 0;
      continue;
    }
    struct stat sb;
    if (stat(file, &sb) || !S_ISREG(sb.st_mode)) { /* a FIFO would block dlopen */
      refuse(m, "module %s is not a regular file", file);
      return;
    }
    m->handle = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (!m->handle) {
      const char *e = dlerror();
      refuse(m, "module %s does not load: %s", file, e ? e : "dlopen failed");
      return;
    }
    const ics_module_info *e = dlsym(m->handle, "ics_module_entry");
    const char *wrong = !e ? "no ics_module_entry"
                        : !e->build_id || strcmp(e->build_id, ICS_MODULE_BUILD_ID)
                            ? "built from other sources than this renderer"
                        : !e->name || strcmp(e->name, m->name) || !e->api ? "another module's entry"
                                                                          : NULL;
    if (wrong) {
      refuse(m, "module %s is refused: %s", file, wrong);
      dlclose(m->handle), m->handle = NULL;
      return;
    }
    e->init(&ics_module_host_table);
    m->api = e->api;
    return;
  }
  refuse(m, "module icshadow-%s.so not found (looked in %s%s)", m->name,
         tried[0] ? tried : "no folder beside the renderer",
         env && env[0] ? ", set by ICS_MODULE_DIR" : "");
}

const void *ics_module_api(const char *name, char *why, size_t why_size) {
  pthread_mutex_lock(&lock);
  loaded *m = NULL;
  for (int i = 0; i < nmods; i++)
    if (!strcmp(mods[i].name, name)) m = &mods[i];
  if (!m && nmods < MAX_MODULES && strlen(name) < sizeof m->name) {
    m = &mods[nmods++];
    snprintf(m->name, sizeof m->name, "%s", name);
    load(m);
  }
  const void *api = m ? m->api : NULL;
  if (!api && why) snprintf(why, why_size, "%s", m ? m->why : "too many modules");
  pthread_mutex_unlock(&lock);
  return api;
}

int ics_render_module_count(void) { return NBUILT; }
const char *ics_render_module_name(int i) { return i >= 0 && i < NBUILT ? built[i].name : NULL; }
const char *ics_render_module_purpose(int i) {
  return i >= 0 && i < NBUILT ? built[i].purpose : NULL;
}
int ics_render_module_loads(const char *name, char *why, size_t why_size) {
  return name && ics_module_api(name, why, why_size) != NULL;
}
