/* module.c — loading the renderer's modules on first use (module.h): the folder, dlopen, the
 * entry's check, the host's table handed over once; every outcome remembered per module. */
#define _GNU_SOURCE /* dladdr */
#include "module.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
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
 * statically), into dir; 0 when it cannot be told */
static int own_folder(char *dir, size_t size) {
  Dl_info info;
  char path[PATH_MAX];
  if (!dladdr((const void *)&own_folder, &info) || !info.dli_fname) return 0;
  if (strchr(info.dli_fname, '/')) {
    if (!realpath(info.dli_fname, path)) return 0;
  } else { /* the main program named without a folder */
    ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
    if (n <= 0) return 0;
    path[n] = 0;
  }
  char *slash = strrchr(path, '/');
  if (!slash) return 0;
  *slash = 0;
  return snprintf(dir, size, "%s", path) < (int)size;
}

/* folder + "/" + rel into dirs[*n] (PATH_MAX; resolved where it exists), counted when it fits
 * and is not already there */
static void add_folder(char dirs[][PATH_MAX], int *n, const char *folder, const char *rel) {
  char path[PATH_MAX];
  int w = snprintf(path, sizeof path, "%s%s%s", folder, rel[0] ? "/" : "", rel);
  if (w <= 0 || w >= PATH_MAX) return;
  if (!realpath(path, dirs[*n])) memcpy(dirs[*n], path, (size_t)w + 1); /* shown as given */
  for (int i = 0; i < *n; i++)
    if (!strcmp(dirs[i], dirs[*n])) return; /* the same folder twice */
  (*n)++;
}

/* the folders to try, in order, into dirs (at least 4 of PATH_MAX); their count */
static int module_folders(char dirs[][PATH_MAX]) {
  int n = 0;
  const char *env = getenv("ICS_MODULE_DIR");
  if (env && env[0]) {
    add_folder(dirs, &n, env, "");
    return n;
  }
  char own[PATH_MAX];
  if (own_folder(own, sizeof own)) {
    add_folder(dirs, &n, own, "icshadow");              /* LIBDIR/ */
    add_folder(dirs, &n, own, ICS_MODULE_DIR_FROM_BIN); /* bin/ */
  }
  add_folder(dirs, &n, ICS_MODULE_BUILD_DIR, "");
  add_folder(dirs, &n, ICS_MODULE_INSTALL_DIR, "");
  return n;
}

static void load(loaded *m) {
  char dirs[4][PATH_MAX], file[PATH_MAX], tried[WHY_SIZE] = "";
  int nd = module_folders(dirs);
  for (int i = 0; i < nd; i++) {
    int w = snprintf(file, sizeof file, "%s/icshadow-%s.so", dirs[i], m->name);
    if (w < 0 || w >= (int)sizeof file || access(file, F_OK) != 0) {
      size_t t = strlen(tried);
      if (snprintf(tried + t, sizeof tried - t, "%s%s", t ? ", " : "", dirs[i]) < 0) tried[t] = 0;
      continue;
    }
    m->handle = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (!m->handle) {
      const char *e = dlerror();
      if (snprintf(m->why, sizeof m->why, "module %s does not load: %s", file,
                   e ? e : "dlopen failed") < 0)
        m->why[0] = 0;
      return;
    }
    const ics_module_info *e = dlsym(m->handle, "ics_module_entry");
    if (!e || e->abi != ICS_MODULE_ABI || !e->name || strcmp(e->name, m->name) || !e->api) {
      if (snprintf(m->why, sizeof m->why, "module %s is not this build's %s module (entry %s)",
                   file, m->name,
                   !e ? "missing" : e->abi != ICS_MODULE_ABI ? "of another version" : "wrong") < 0)
        m->why[0] = 0;
      dlclose(m->handle), m->handle = NULL;
      return;
    }
    e->init(&ics_module_host_table);
    m->api = e->api;
    return;
  }
  const char *env = getenv("ICS_MODULE_DIR");
  if (snprintf(m->why, sizeof m->why, "module icshadow-%s.so not found (looked in %s%s)", m->name,
               tried, env && env[0] ? ", set by ICS_MODULE_DIR" : "") < 0)
    m->why[0] = 0;
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

int ics_module_loaded(const char *name) {
  pthread_mutex_lock(&lock);
  int yes = 0;
  for (int i = 0; i < nmods; i++) yes |= !strcmp(mods[i].name, name) && mods[i].api != NULL;
  pthread_mutex_unlock(&lock);
  return yes;
}

int ics_render_module_count(void) { return NBUILT; }
const char *ics_render_module_name(int i) { return i >= 0 && i < NBUILT ? built[i].name : NULL; }
const char *ics_render_module_purpose(int i) {
  return i >= 0 && i < NBUILT ? built[i].purpose : NULL;
}
int ics_render_module_loads(const char *name, char *why, size_t why_size) {
  return name && ics_module_api(name, why, why_size) != NULL;
}
