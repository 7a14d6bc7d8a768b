/* gl_context.c — OpenGL 4.5 core contexts without a window (gl_context.h).
 *
 *   egl     the EGL device platform (EGL_EXT_platform_device): the first device that is not
 *           Mesa's software device, so the same binary renders on a GPU driver; else Mesa's
 *           surfaceless platform (EGL_MESA_platform_surfaceless, llvmpipe here). Contexts are
 *           configless (EGL_KHR_no_config_context) and current without a surface
 *           (EGL_KHR_surfaceless_context).
 *   osmesa  OSMesaCreateContextAttribs with a 4.5 core profile, current on a 1 x 1 buffer (the
 *           backend computes into buffers, it draws nothing). Gone from Mesa 25.1: EGL is the
 *           long-term path.
 *   auto    egl, then osmesa.
 * Each is compiled in when CMake found its library (ICS_HAVE_EGL, ICS_HAVE_OSMESA); OSMesa is
 * opened on first use (dlopen), not linked, since it maps LLVM. */
#define _GNU_SOURCE /* RTLD_DEFAULT */
#include "gl_context.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef ICS_HAVE_EGL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif
#ifdef ICS_HAVE_OSMESA
#include <GL/osmesa.h>
#include <dlfcn.h>
#include <pthread.h>

/* OSMesa, opened on first use (libOSMesa.so.8 links LLVM: a program that only asks whether
 * there is a GPU, as --backend auto does, should not map it): its six entry points */
#define ICS_OSMESA_FUNCS(X)                                                                     \
  X(OSMesaCreateContextAttribs) X(OSMesaMakeCurrent) X(OSMesaGetCurrentContext)                 \
  X(OSMesaDestroyContext) X(OSMesaGetColorBuffer) X(OSMesaGetProcAddress)
#define ICS_OSMESA_FIELD_(name) __typeof__(name) *name;
static struct {
  ICS_OSMESA_FUNCS(ICS_OSMESA_FIELD_)
} osm;
#undef ICS_OSMESA_FIELD_
static pthread_once_t osm_once = PTHREAD_ONCE_INIT;
static char osm_failure[512];

static void osmesa_load_once(void) {
  void *h = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
  const char *missing = NULL;
  /* each bound as the dynamic linker would: the global scope first (a preloaded library
   * interposes, as the fault tests' shim does), then the library itself */
#define ICS_OSMESA_RESOLVE_(name)                                                               \
  if (h && !missing && !(*(void **)&osm.name = dlsym(RTLD_DEFAULT, #name)) &&                   \
      !(*(void **)&osm.name = dlsym(h, #name)))                                                 \
    missing = #name;
  ICS_OSMESA_FUNCS(ICS_OSMESA_RESOLVE_)
#undef ICS_OSMESA_RESOLVE_
  if (!h) {
    const char *e = dlerror();
    snprintf(osm_failure, sizeof osm_failure, "osmesa: libOSMesa.so.8 does not load (%s)",
             e ? e : "dlopen failed");
  } else if (missing) {
    snprintf(osm_failure, sizeof osm_failure, "osmesa: libOSMesa.so.8 lacks %s", missing);
    memset(&osm, 0, sizeof osm);
    dlclose(h); /* (and LLVM with it) */
  }
}

/* 1 when OSMesa is there, else 0 with why */
static int osmesa_load(char *why, size_t why_size) {
  pthread_once(&osm_once, osmesa_load_once);
  if (osm_failure[0] && why) snprintf(why, why_size, "%s", osm_failure);
  return !osm_failure[0];
}
#define OSMesaCreateContextAttribs (osm.OSMesaCreateContextAttribs)
#define OSMesaMakeCurrent (osm.OSMesaMakeCurrent)
#define OSMesaGetCurrentContext (osm.OSMesaGetCurrentContext)
#define OSMesaDestroyContext (osm.OSMesaDestroyContext)
#define OSMesaGetColorBuffer (osm.OSMesaGetColorBuffer)
#define OSMesaGetProcAddress (osm.OSMesaGetProcAddress)
#endif

enum { KIND_NONE, KIND_EGL, KIND_OSMESA };

int ics_gl_kind_known(const char *which) {
  if (!which || !strcmp(which, "auto")) return 1;
#ifdef ICS_HAVE_EGL
  if (!strcmp(which, "egl")) return 1;
#endif
#ifdef ICS_HAVE_OSMESA
  if (!strcmp(which, "osmesa")) return 1;
#endif
  return 0;
}

typedef void (*ics_gl_proc)(void);

/* loads every entry point and checks the version; 0 with why on failure */
static int load(ics_gl *g, ics_gl_proc (*gpa)(const char *), char *why, size_t why_size) {
  int missing = 0;
#define ICS_GL_LOAD(type, name)                                                                \
  g->gl.name = (type)gpa("gl" #name);                                                          \
  if (!g->gl.name && !missing) {                                                               \
    missing = 1;                                                                               \
    snprintf(why, why_size, "%s: no entry point gl%s", g->context, #name);                     \
  }
  ICS_GL_FUNCTIONS(ICS_GL_LOAD)
#undef ICS_GL_LOAD
  if (missing) return 0;
  const char *r = (const char *)g->gl.GetString(GL_RENDERER);
  const char *v = (const char *)g->gl.GetString(GL_VERSION);
  snprintf(g->renderer, sizeof g->renderer, "%s", r ? r : "(unknown renderer)");
  snprintf(g->version, sizeof g->version, "%s", v ? v : "(unknown version)");
  GLint major = 0, minor = 0;
  g->gl.GetIntegerv(GL_MAJOR_VERSION, &major);
  g->gl.GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 4 || (major == 4 && minor < 5)) {
    snprintf(why, why_size, "%s: the driver gives OpenGL %s (%s), the gl backend needs 4.5",
             g->context, g->version, g->renderer);
    return 0;
  }
  g->software = strstr(g->renderer, "llvmpipe") || strstr(g->renderer, "softpipe");
  return 1;
}

#ifdef ICS_HAVE_EGL
static const char *egl_err(EGLint e) {
  switch (e) {
  case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
  case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
  case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
  case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
  case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
  case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
  case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
  case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
  case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
  case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
  default: return "EGL error";
  }
}

static ics_gl_proc egl_gpa(const char *name) { return (ics_gl_proc)eglGetProcAddress(name); }

/* The EGL devices that are not Mesa's software one (a GPU driver's), at most cap, into dev;
 * *listed: every device EGL lists (-1 when it cannot list them: no EGL_EXT_device_enumeration). */
static int egl_hardware_devices(EGLDeviceEXT *dev, int cap, int *listed) {
  PFNEGLQUERYDEVICESEXTPROC query_devices =
      (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
  PFNEGLQUERYDEVICESTRINGEXTPROC device_string =
      (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
  EGLDeviceEXT all[16];
  EGLint n = 0;
  *listed = -1;
  if (!query_devices || !device_string || !query_devices(16, all, &n)) return 0;
  *listed = (int)n;
  int k = 0;
  for (EGLint i = 0; i < n && k < cap; i++) {
    const char *ext = device_string(all[i], EGL_EXTENSIONS);
    if (!ext || !strstr(ext, "EGL_MESA_device_software")) dev[k++] = all[i];
  }
  return k;
}

/* a 4.5 core context on display dpy (initialised here); 0 with why */
static int egl_context(ics_gl *g, EGLDisplay dpy, char *why, size_t why_size) {
  EGLint major, minor;
  if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
    snprintf(why, why_size, "%s: eglInitialize: %s", g->context, egl_err(eglGetError()));
    return 0;
  }
  g->display = dpy;
  const char *ext = eglQueryString(dpy, EGL_EXTENSIONS);
  if (!ext || !strstr(ext, "EGL_KHR_no_config_context") ||
      !strstr(ext, "EGL_KHR_surfaceless_context")) {
    snprintf(why, why_size, "%s: EGL %d.%d lacks EGL_KHR_no_config_context or "
             "EGL_KHR_surfaceless_context", g->context, major, minor);
    return 0;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    snprintf(why, why_size, "%s: eglBindAPI(EGL_OPENGL_API): %s", g->context, egl_err(eglGetError()));
    return 0;
  }
  /* robust first (a reset is then reported by glGetGraphicsResetStatus), plain if refused */
  const EGLint robust[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                           EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                           EGL_CONTEXT_OPENGL_ROBUST_ACCESS, EGL_TRUE,
                           EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY, EGL_LOSE_CONTEXT_ON_RESET,
                           EGL_NONE};
  EGLContext c = major > 1 || minor >= 5
                     ? eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, robust)
                     : EGL_NO_CONTEXT;
  g->robust = c != EGL_NO_CONTEXT;
  const EGLint attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                         EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                         EGL_NONE};
  if (c == EGL_NO_CONTEXT) c = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attr);
  if (c == EGL_NO_CONTEXT) {
    snprintf(why, why_size, "%s: no OpenGL 4.5 core context (eglCreateContext: %s)", g->context,
             egl_err(eglGetError()));
    return 0;
  }
  g->ctx = c;
  g->kind = KIND_EGL;
  if (!ics_gl_make_current(g)) {
    snprintf(why, why_size, "%s: eglMakeCurrent: %s", g->context, egl_err(eglGetError()));
    return 0;
  }
  return load(g, egl_gpa, why, why_size);
}

/* The display stays initialised: EGL gives every caller of a platform the same display, so
 * eglTerminate would end every other context on it, other renderers' and the application's. */
static void egl_close(ics_gl *g) {
  if (g->ctx) {
    if (eglGetCurrentContext() == g->ctx) ics_gl_release(g);
    eglDestroyContext(g->display, g->ctx);
  }
  g->ctx = g->display = NULL;
}

/* the device platform's first hardware device, else the surfaceless platform */
static int egl_open(ics_gl *g, char *why, size_t why_size) {
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  if (!get_display) {
    snprintf(why, why_size, "egl: no eglGetPlatformDisplayEXT (EGL_EXT_platform_base)");
    return 0;
  }
  char dev_why[512] = "";
  EGLDeviceEXT devs[16];
  int listed, ndev = egl_hardware_devices(devs, 16, &listed); /* llvmpipe's: surfaceless below */
  for (int i = 0; i < ndev; i++) {
    snprintf(g->context, sizeof g->context, "egl-device %d", i);
    if (egl_context(g, get_display(EGL_PLATFORM_DEVICE_EXT, devs[i], NULL), dev_why,
                    sizeof dev_why))
      return 1;
    egl_close(g);
  }
  snprintf(g->context, sizeof g->context, "egl-surfaceless");
  if (egl_context(g, get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL), why,
                  why_size))
    return 1;
  if (dev_why[0]) {
    size_t n = strlen(why);
    snprintf(why + n, why_size - n, "; %s", dev_why);
  }
  egl_close(g);
  return 0;
}
#endif

#ifdef ICS_HAVE_OSMESA
static ics_gl_proc osmesa_gpa(const char *name) { return (ics_gl_proc)OSMesaGetProcAddress(name); }

static int osmesa_open(ics_gl *g, char *why, size_t why_size) {
  snprintf(g->context, sizeof g->context, "osmesa");
  if (!osmesa_load(why, why_size)) return 0;
  const int attr[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                      OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
  OSMesaContext c = OSMesaCreateContextAttribs(attr, NULL);
  if (!c) {
    snprintf(why, why_size, "osmesa: OSMesaCreateContextAttribs refused a 4.5 core profile");
    return 0;
  }
  g->ctx = c;
  g->osmesa_buf = calloc(1, 4);
  g->kind = KIND_OSMESA;
  if (!g->osmesa_buf || !ics_gl_make_current(g)) {
    snprintf(why, why_size, "osmesa: OSMesaMakeCurrent failed");
    return 0;
  }
  return load(g, osmesa_gpa, why, why_size);
}

static void osmesa_close(ics_gl *g) {
  if (g->ctx) {
    if (OSMesaGetCurrentContext() == g->ctx) ics_gl_release(g);
    OSMesaDestroyContext(g->ctx);
  }
  free(g->osmesa_buf);
  g->ctx = g->osmesa_buf = NULL;
}
#endif

int ics_gl_hardware_device(char *why, size_t why_size) {
#ifdef ICS_HAVE_EGL
  EGLDeviceEXT dev;
  int listed;
  if (egl_hardware_devices(&dev, 1, &listed)) return 1;
  if (why) {
    if (listed < 0) snprintf(why, why_size, "EGL lists no devices (no EGL_EXT_device_enumeration)");
    else snprintf(why, why_size, "no GPU (EGL lists %d device%s, Mesa's software rasterizer "
                  "only; --backend gl renders there)", listed, listed == 1 ? "" : "s");
  }
  return 0;
#else
  if (why) snprintf(why, why_size, "built without EGL, so no GPU is looked for (--backend gl "
                    "renders through OSMesa)");
  return 0;
#endif
}

void ics_gl_close(ics_gl *g) {
  if (!g) return;
#ifdef ICS_HAVE_EGL
  if (g->display) egl_close(g);
#endif
#ifdef ICS_HAVE_OSMESA
  if (g->osmesa_buf || (g->ctx && !g->display)) osmesa_close(g);
#endif
  memset(g, 0, sizeof *g);
}

int ics_gl_make_current(ics_gl *g) {
#ifdef ICS_HAVE_EGL
  if (g->kind == KIND_EGL) {
    g->prev_display = eglGetCurrentDisplay(), g->prev_ctx = eglGetCurrentContext();
    g->prev_draw = eglGetCurrentSurface(EGL_DRAW), g->prev_read = eglGetCurrentSurface(EGL_READ);
    return eglMakeCurrent(g->display, EGL_NO_SURFACE, EGL_NO_SURFACE, g->ctx);
  }
#endif
#ifdef ICS_HAVE_OSMESA
  if (g->kind == KIND_OSMESA) {
    g->prev_ctx = OSMesaGetCurrentContext(), g->prev_display = NULL;
    if (g->prev_ctx) {
      GLint w = 0, h = 0, format = 0;
      void *buf = NULL;
      OSMesaGetColorBuffer(g->prev_ctx, &w, &h, &format, &buf);
      g->prev_draw = buf, g->prev_w = w, g->prev_h = h;
    }
    return OSMesaMakeCurrent(g->ctx, g->osmesa_buf, GL_UNSIGNED_BYTE, 1, 1);
  }
#endif
  return 0;
}

void ics_gl_release(ics_gl *g) {
#ifdef ICS_HAVE_EGL
  if (g->kind == KIND_EGL) {
    if (g->prev_ctx && g->prev_ctx != g->ctx && g->prev_display)
      eglMakeCurrent(g->prev_display, g->prev_draw, g->prev_read, g->prev_ctx);
    else
      eglMakeCurrent(g->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
#endif
#ifdef ICS_HAVE_OSMESA
  if (g->kind == KIND_OSMESA) {
    if (g->prev_ctx && g->prev_ctx != g->ctx && g->prev_draw)
      OSMesaMakeCurrent(g->prev_ctx, g->prev_draw, GL_UNSIGNED_BYTE, g->prev_w, g->prev_h);
    else
      OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
  }
#endif
  g->prev_ctx = g->prev_display = g->prev_draw = g->prev_read = NULL;
}

ics_status ics_gl_open(ics_gl *g, const char *which, char *why, size_t why_size) {
  memset(g, 0, sizeof *g);
  if (!which) which = "auto";
  int any = !strcmp(which, "auto");
  char w1[768] = "", w2[768] = "";
  if (!ics_gl_kind_known(which)) {
    snprintf(why, why_size, "no OpenGL context kind '%s' in this build (auto"
#ifdef ICS_HAVE_EGL
             ", egl"
#endif
#ifdef ICS_HAVE_OSMESA
             ", osmesa"
#endif
             ")", which);
    return ICS_ERR_UNSUPPORTED;
  }
#ifdef ICS_HAVE_EGL
  if (any || !strcmp(which, "egl")) {
    if (egl_open(g, w1, sizeof w1)) return ICS_OK;
    ics_gl_close(g);
  }
#endif
#ifdef ICS_HAVE_OSMESA
  if (any || !strcmp(which, "osmesa")) {
    if (osmesa_open(g, w2, sizeof w2)) return ICS_OK;
    ics_gl_close(g);
  }
#endif
  snprintf(why, why_size, "no OpenGL 4.5 context: %s%s%s", w1, w1[0] && w2[0] ? "; " : "", w2);
  return ICS_ERR_UNSUPPORTED;
}

int ics_gl_compile(ics_gl *g, const char *source, const char *head, const char *name,
                   GLuint *prog, char *msg, size_t msg_size) {
  const char *nl = strchr(source, '\n');
  const GLchar *parts[3] = {source, head, nl ? nl + 1 : ""};
  const GLint lens[3] = {nl ? (GLint)(nl + 1 - source) : (GLint)strlen(source), -1, -1};
  GLuint sh = g->gl.CreateShader(GL_COMPUTE_SHADER);
  g->gl.ShaderSource(sh, 3, parts, lens);
  g->gl.CompileShader(sh);
  GLint ok = 0;
  g->gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  char log[4096] = "";
  if (!ok) {
    g->gl.GetShaderInfoLog(sh, sizeof log, NULL, log);
    g->gl.DeleteShader(sh);
    snprintf(msg, msg_size, "backend gl: %s does not compile on %s:\n%s", name, g->renderer, log);
    return 0;
  }
  GLuint p = g->gl.CreateProgram();
  g->gl.AttachShader(p, sh);
  g->gl.LinkProgram(p);
  g->gl.DeleteShader(sh);
  g->gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    g->gl.GetProgramInfoLog(p, sizeof log, NULL, log);
    g->gl.DeleteProgram(p);
    snprintf(msg, msg_size, "backend gl: %s does not link on %s:\n%s", name, g->renderer, log);
    return 0;
  }
  *prog = p;
  return 1;
}

void ics_gl_uniform_i(ics_gl *g, GLuint prog, const char *name, int v) {
  GLint loc = g->gl.GetUniformLocation(prog, name);
  if (loc >= 0) g->gl.ProgramUniform1i(prog, loc, v);
}

void ics_gl_uniform_ui(ics_gl *g, GLuint prog, const char *name, unsigned v) {
  GLint loc = g->gl.GetUniformLocation(prog, name);
  if (loc >= 0) g->gl.ProgramUniform1ui(prog, loc, v);
}

void ics_gl_uniform_d(ics_gl *g, GLuint prog, const char *name, double v) {
  GLint loc = g->gl.GetUniformLocation(prog, name);
  if (loc >= 0) g->gl.ProgramUniform1d(prog, loc, v);
}

GLuint ics_gl_buffer(ics_gl *g, size_t bytes, const void *data) {
  GLuint b = 0;
  g->gl.CreateBuffers(1, &b);
  g->gl.NamedBufferStorage(b, (GLsizeiptr)(bytes > 4 ? bytes : 4), data, GL_DYNAMIC_STORAGE_BIT);
  if (!data) {
    const GLuint zero = 0;
    g->gl.ClearNamedBufferData(b, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  }
  return b;
}

const char *ics_gl_error_name(GLenum e) {
  switch (e) {
  case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
  case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
  case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
  case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
  case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
  case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST (the context was lost)";
  default: return "a GL error";
  }
}

const char *ics_gl_reset_name(GLenum reset) {
  return reset == GL_GUILTY_CONTEXT_RESET     ? "GL_GUILTY_CONTEXT_RESET"
         : reset == GL_INNOCENT_CONTEXT_RESET ? "GL_INNOCENT_CONTEXT_RESET"
                                              : "GL_UNKNOWN_CONTEXT_RESET";
}


