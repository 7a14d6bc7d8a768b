/* cl_device.c — the OpenCL device, context and queue that libicshadow's OpenCL code shares
 * (the cl backend, the SAT builder): device choice, program builds with their log, error names,
 * event times (cl_device.h).
 *
 * Device choice: the wanted device (the cl backend's option cl.device, the primitives' and its
 * default ICS_CL_DEVICE), when given, is a device index in the order of the platform list
 * (platform by platform), or a case-insensitive substring of "platform: device"; otherwise the
 * first GPU with cl_khr_fp64, else the first device with it (the kernels compute in double where
 * the CPU code does). */
#define _POSIX_C_SOURCE 200809L
#include "cl_device.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <pthread.h>
#include <unistd.h>

const char *ics_cl_err_name(cl_int e) {
  switch (e) {
#define E(x) case x: return #x;
    E(CL_DEVICE_NOT_FOUND) E(CL_DEVICE_NOT_AVAILABLE) E(CL_COMPILER_NOT_AVAILABLE)
    E(CL_MEM_OBJECT_ALLOCATION_FAILURE) E(CL_OUT_OF_RESOURCES) E(CL_OUT_OF_HOST_MEMORY)
    E(CL_BUILD_PROGRAM_FAILURE) E(CL_INVALID_VALUE) E(CL_INVALID_DEVICE) E(CL_INVALID_CONTEXT)
    E(CL_INVALID_COMMAND_QUEUE) E(CL_INVALID_MEM_OBJECT) E(CL_INVALID_BUFFER_SIZE)
    E(CL_INVALID_PROGRAM) E(CL_INVALID_KERNEL) E(CL_INVALID_KERNEL_ARGS) E(CL_INVALID_ARG_INDEX)
    E(CL_INVALID_ARG_VALUE) E(CL_INVALID_ARG_SIZE) E(CL_INVALID_WORK_DIMENSION)
    E(CL_INVALID_WORK_GROUP_SIZE) E(CL_INVALID_GLOBAL_WORK_SIZE) E(CL_INVALID_EVENT)
    E(CL_INVALID_OPERATION) E(CL_INVALID_PLATFORM)
#undef E
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";
    default: return "an unknown OpenCL error";
  }
}

#define MAX_DEVICES 64

typedef struct cl_pick {
  cl_platform_id platform;
  cl_device_id device;
  char name[120]; /* "platform: device" */
} cl_pick;

/* A string property of a device (platform NULL) or of a platform, whatever its length: a
 * malloc'ed string ("" when the query fails), or NULL when out of memory. */
static char *info_string(cl_platform_id p, cl_device_id d, cl_uint what) {
  size_t n = 0;
  cl_int e = p ? clGetPlatformInfo(p, what, 0, NULL, &n) : clGetDeviceInfo(d, what, 0, NULL, &n);
  char *s = malloc(e == CL_SUCCESS ? n + 1 : 1);
  if (!s) return NULL;
  s[0] = 0;
  if (e == CL_SUCCESS) {
    e = p ? clGetPlatformInfo(p, what, n, s, NULL) : clGetDeviceInfo(d, what, n, s, NULL);
    s[e == CL_SUCCESS ? n : 0] = 0;
  }
  return s;
}

static int has_fp64(cl_device_id d) {
  char *ext = info_string(NULL, d, CL_DEVICE_EXTENSIONS);
  int yes = ext && strstr(ext, "cl_khr_fp64") != NULL;
  free(ext);
  return yes;
}

static int contains_nocase(const char *hay, const char *needle) {
  size_t n = strlen(needle);
  for (; *hay; hay++) {
    size_t i = 0;
    while (i < n && hay[i] && tolower((unsigned char)hay[i]) == tolower((unsigned char)needle[i])) i++;
    if (i == n) return 1;
  }
  return n == 0;
}

/* The device to run on (file comment; want may be NULL, label names it in messages); 0, or -1
 * with the reason in why. */
static int pick_device(cl_pick *out, const char *want, const char *label, char *why,
                       size_t why_size) {
  cl_platform_id plats[16];
  cl_uint np = 0;
  cl_int e = clGetPlatformIDs(16, plats, &np);
  if (e != CL_SUCCESS || np == 0) {
    if (why) snprintf(why, why_size, "no OpenCL platform (%s; install an ICD such as "
                      "pocl-opencl-icd)", e != CL_SUCCESS ? ics_cl_err_name(e) : "none listed");
    return -1;
  }
  if (np > 16) np = 16; /* the count of all platforms; the first 16 were written */
  cl_pick all[MAX_DEVICES];
  cl_device_type type[MAX_DEVICES];
  int fp64[MAX_DEVICES], n = 0;
  for (cl_uint i = 0; i < np && n < MAX_DEVICES; i++) {
    cl_device_id devs[MAX_DEVICES];
    cl_uint nd = 0;
    if (clGetDeviceIDs(plats[i], CL_DEVICE_TYPE_ALL, MAX_DEVICES, devs, &nd) != CL_SUCCESS) continue;
    if (nd > MAX_DEVICES) nd = MAX_DEVICES;
    char *pname = info_string(plats[i], NULL, CL_PLATFORM_NAME);
    for (cl_uint j = 0; j < nd && n < MAX_DEVICES; j++) {
      char *dname = info_string(NULL, devs[j], CL_DEVICE_NAME);
      type[n] = 0;
      clGetDeviceInfo(devs[j], CL_DEVICE_TYPE, sizeof type[n], &type[n], NULL);
      all[n].platform = plats[i];
      all[n].device = devs[j];
      snprintf(all[n].name, sizeof all[n].name, "%s: %s", pname ? pname : "", dname ? dname : "");
      fp64[n] = has_fp64(devs[j]);
      free(dname);
      n++;
    }
    free(pname);
  }
  if (!n) {
    if (why) snprintf(why, why_size, "no OpenCL device on %u platform%s", np, np == 1 ? "" : "s");
    return -1;
  }
  int chosen = -1;
  if (want && *want) {
    char *end;
    long idx = strtol(want, &end, 10);
    if (!*end && end != want) {
      if (idx < 0 || idx >= n) {
        if (why) snprintf(why, why_size, "%s=%s: there are devices 0..%d", label, want, n - 1);
        return -1;
      }
      chosen = (int)idx;
    } else {
      for (int i = 0; i < n && chosen < 0; i++)
        if (contains_nocase(all[i].name, want)) chosen = i;
      if (chosen < 0) {
        if (why) {
          int m = snprintf(why, why_size, "%s=%s matches no device (", label, want);
          for (int i = 0; i < n && m >= 0 && (size_t)m < why_size; i++)
            m += snprintf(why + m, why_size - (size_t)m, "%s%d: %s", i ? "; " : "", i, all[i].name);
          if (m >= 0 && (size_t)m < why_size) snprintf(why + m, why_size - (size_t)m, ")");
        }
        return -1;
      }
    }
    if (!fp64[chosen]) {
      if (why) snprintf(why, why_size, "OpenCL device %s lacks cl_khr_fp64, which libicshadow's "
                        "OpenCL kernels need", all[chosen].name);
      return -1;
    }
  } else {
    for (int i = 0; i < n && chosen < 0; i++)
      if (fp64[i] && (type[i] & CL_DEVICE_TYPE_GPU)) chosen = i;
    for (int i = 0; i < n && chosen < 0; i++)
      if (fp64[i]) chosen = i;
    if (chosen < 0) {
      if (why) snprintf(why, why_size, "no OpenCL device with cl_khr_fp64 (%d device%s; first: %s)",
                        n, n == 1 ? "" : "s", all[0].name);
      return -1;
    }
  }
  *out = all[chosen];
  return 0;
}

int ics_cl_available(const char *want, const char *label, char *why, size_t why_size) {
  cl_pick pk;
  return ics_cl_load(why, why_size) && pick_device(&pk, want, label, why, why_size) == 0;
}

ics_status ics_cl_dev_open(ics_cl_dev *d, const char *want, const char *label, char *msg,
                           size_t msg_size) {
  memset(d, 0, sizeof *d);
  cl_pick pk;
  if (!ics_cl_load(msg, msg_size) || pick_device(&pk, want, label, msg, msg_size))
    return ICS_ERR_UNSUPPORTED;
  d->device = pk.device;
  snprintf(d->name, sizeof d->name, "OpenCL, %s", pk.name);
  cl_int e = clGetDeviceInfo(d->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof d->max_alloc,
                             &d->max_alloc, NULL);
  if (e != CL_SUCCESS) {
    if (msg) snprintf(msg, msg_size, "clGetDeviceInfo(CL_DEVICE_MAX_MEM_ALLOC_SIZE) on %s: %s",
                      pk.name, ics_cl_err_name(e));
    memset(d, 0, sizeof *d);
    return ICS_ERR_UNSUPPORTED;
  }
  const char *call = "clCreateContext";
  cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)pk.platform, 0};
  d->ctx = clCreateContext(props, 1, &d->device, NULL, NULL, &e);
  if (e == CL_SUCCESS) {
    call = "clCreateCommandQueue";
    d->q = clCreateCommandQueue(d->ctx, d->device, CL_QUEUE_PROFILING_ENABLE, &e);
  }
  if (e != CL_SUCCESS) {
    if (msg) snprintf(msg, msg_size, "%s on %s: %s", call, pk.name, ics_cl_err_name(e));
    ics_cl_dev_close(d);
    return e == CL_OUT_OF_HOST_MEMORY || e == CL_OUT_OF_RESOURCES ? ICS_ERR_NOMEM : ICS_ERR_UNSUPPORTED;
  }
  return ICS_OK;
}

void ics_cl_dev_close(ics_cl_dev *d) {
  if (d->q) clReleaseCommandQueue(d->q);
  if (d->ctx) clReleaseContext(d->ctx);
  memset(d, 0, sizeof *d);
}

/* The compiler's own output on stderr (PoCL runs clang in the process, which prints "N warnings
 * generated." for a first build) is kept out of the user's stderr: fd 2 goes to a private
 * temporary file while the program builds, and the end of what was written there is returned,
 * to be shown only when the build fails. Builds take a lock for that time, so two threads
 * building at once cannot leave fd 2 on the other's file (one lock per library this file is
 * compiled into: a process that builds through libicshadow_cl.so and the renderer's shared cl
 * backend on two threads at the same moment is not covered; static links share one); whatever
 * else the process writes to stderr during a build (about a second, once per program with
 * PoCL's cache) goes into that record too. -1 (and no lock held) when fd 2 is closed or cannot be redirected. */
static pthread_mutex_t quiet_lock = PTHREAD_MUTEX_INITIALIZER;

static int quiet_stderr_begin(void) {
  if (fcntl(2, F_GETFD) < 0) return -1; /* no stderr: tmpfile would take fd 2 itself */
  pthread_mutex_lock(&quiet_lock);
  fflush(stderr);
  FILE *t = tmpfile();
  int saved = t ? dup(2) : -1;
  if (saved >= 0 && dup2(fileno(t), 2) < 0) {
    close(saved);
    saved = -1;
  }
  if (t) fclose(t); /* fd 2 keeps the (unlinked, read-write) file open */
  if (saved < 0) pthread_mutex_unlock(&quiet_lock);
  return saved;
}

static void quiet_stderr_end(int saved, char *said, size_t said_size) {
  if (saved < 0) return;
  fflush(stderr);
  off_t n = lseek(2, 0, SEEK_CUR), keep = (off_t)said_size - 1;
  ssize_t got = n > 0 ? pread(2, said, (size_t)(n < keep ? n : keep), n < keep ? 0 : n - keep) : 0;
  said[got > 0 ? got : 0] = 0;
  dup2(saved, 2);
  close(saved);
  pthread_mutex_unlock(&quiet_lock);
}

ics_status ics_cl_build(const ics_cl_dev *d, const char *src, const char *what, int nkernels,
                        const char *const *names, cl_program *prog, cl_kernel *kernels,
                        char *msg, size_t msg_size) {
  cl_int e;
  *prog = clCreateProgramWithSource(d->ctx, 1, &src, NULL, &e);
  if (e != CL_SUCCESS) {
    if (msg) snprintf(msg, msg_size, "clCreateProgramWithSource(%s): %s", what, ics_cl_err_name(e));
    return ICS_ERR_UNSUPPORTED;
  }
  char said[1024] = ""; /* what the compiler printed on stderr itself (PoCL's clang) */
  int saved = quiet_stderr_begin();
  e = clBuildProgram(*prog, 1, &d->device, "-cl-std=CL1.2", NULL, NULL);
  quiet_stderr_end(saved, said, sizeof said);
  if (e != CL_SUCCESS) {
    char log[2048] = "";
    clGetProgramBuildInfo(*prog, d->device, CL_PROGRAM_BUILD_LOG, sizeof log - 1, log, NULL);
    if (msg) snprintf(msg, msg_size, "building %s for %s failed (%s): %s%s%s", what, d->name,
                      ics_cl_err_name(e), log, *said ? "\n" : "", said);
    return ICS_ERR_UNSUPPORTED;
  }
  for (int i = 0; i < nkernels; i++) {
    kernels[i] = clCreateKernel(*prog, names[i], &e);
    if (e != CL_SUCCESS) {
      if (msg) snprintf(msg, msg_size, "clCreateKernel(%s) in %s: %s", names[i], what, ics_cl_err_name(e));
      return ICS_ERR_UNSUPPORTED;
    }
  }
  return ICS_OK;
}

double ics_cl_event_ms(cl_event ev) {
  cl_ulong t0 = 0, t1 = 0;
  clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof t0, &t0, NULL);
  clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof t1, &t1, NULL);
  return t1 > t0 ? (double)(t1 - t0) * 1e-6 : 0;
}

ics_status ics_cl_status(cl_int e) {
  return e == CL_MEM_OBJECT_ALLOCATION_FAILURE || e == CL_OUT_OF_RESOURCES ||
                 e == CL_OUT_OF_HOST_MEMORY || e == CL_INVALID_BUFFER_SIZE
             ? ICS_ERR_NOMEM : ICS_ERR_UNSUPPORTED;
}
