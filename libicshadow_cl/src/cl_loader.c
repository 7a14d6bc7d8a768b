/* cl_loader.c — opening OpenCL's ICD loader on first use (cl_loader.h). */
#define ICS_CL_LOADER_IMPL
#include "cl_device.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

ics_cl_api ics_cl_fn;

static pthread_once_t once = PTHREAD_ONCE_INIT;
static int loaded;
static char failure[512];

static void load(void) {
  void *h = dlopen("libOpenCL.so.1", RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char *e = dlerror();
    snprintf(failure, sizeof failure, "OpenCL's ICD loader libOpenCL.so.1 does not load (%s; "
             "apt-get install ocl-icd-libopencl1 and a platform such as pocl-opencl-icd)",
             e ? e : "dlopen failed");
    return;
  }
  const char *missing = NULL;
#define ICS_CL_RESOLVE_(name)                                                                   \
  if (!missing && !(*(void **)&ics_cl_fn.name = dlsym(h, #name))) missing = #name;
  ICS_CL_FUNCS(ICS_CL_RESOLVE_)
#undef ICS_CL_RESOLVE_
  if (missing) {
    snprintf(failure, sizeof failure, "libOpenCL.so.1 lacks %s (an OpenCL 1.2 ICD loader is needed)",
             missing);
    memset(&ics_cl_fn, 0, sizeof ics_cl_fn);
    dlclose(h);
    return;
  }
  loaded = 1;
}

int ics_cl_load(char *why, size_t why_size) {
  pthread_once(&once, load);
  if (!loaded && why) snprintf(why, why_size, "%s", failure);
  return loaded;
}
