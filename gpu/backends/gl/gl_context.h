/* gl_context.h — an OpenGL 4.5 core context without a window (gl_context.c): OSMesa, EGL on the
 * device platform (a GPU driver: NVIDIA's, Mesa's hardware drivers) or EGL surfaceless (Mesa),
 * and the GL entry points the gl backend calls, loaded through the context's GetProcAddress.
 * Private to the renderer library. */
#ifndef ICS_GL_CONTEXT_H
#define ICS_GL_CONTEXT_H

#include <GL/glcorearb.h>
#include <stddef.h>

#include "icshadow/status.h"

/* the entry points: X(type, name) for gl##name */
#define ICS_GL_FUNCTIONS(X)                                                                     \
  X(PFNGLGETSTRINGPROC, GetString)                                                              \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                                            \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                          \
  X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                                                      \
  X(PFNGLGETINTEGER64VPROC, GetInteger64v)                                                      \
  X(PFNGLGETERRORPROC, GetError)                                                                \
  X(PFNGLGETGRAPHICSRESETSTATUSPROC, GetGraphicsResetStatus)                                    \
  X(PFNGLCREATESHADERPROC, CreateShader)                                                        \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                        \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                                      \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                          \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                                \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                                        \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                      \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                                        \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                          \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                        \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                              \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                      \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                                            \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                            \
  X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                                                \
  X(PFNGLPROGRAMUNIFORM1UIPROC, ProgramUniform1ui)                                              \
  X(PFNGLPROGRAMUNIFORM1DPROC, ProgramUniform1d)                                                \
  X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                                                      \
  X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                                            \
  X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                                            \
  X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)                                      \
  X(PFNGLCLEARNAMEDBUFFERDATAPROC, ClearNamedBufferData)                                        \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                      \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                                                    \
  X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                                                  \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                                                  \
  X(PFNGLDISPATCHCOMPUTEINDIRECTPROC, DispatchComputeIndirect)                                  \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                                            \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                                                      \
  X(PFNGLFINISHPROC, Finish)                                                                    \
  X(PFNGLGENQUERIESPROC, GenQueries)                                                            \
  X(PFNGLCREATETEXTURESPROC, CreateTextures)                                                    \
  X(PFNGLTEXTUREBUFFERPROC, TextureBuffer)                                                      \
  X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                                                  \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                    \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                                      \
  X(PFNGLQUERYCOUNTERPROC, QueryCounter)                                                        \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

typedef struct ics_gl_fns {
#define ICS_GL_FIELD(type, name) type name;
  ICS_GL_FUNCTIONS(ICS_GL_FIELD)
#undef ICS_GL_FIELD
} ics_gl_fns;

typedef struct ics_gl {
  ics_gl_fns gl;
  char context[64];   /* "osmesa", "egl-device N", "egl-surfaceless" */
  char renderer[160]; /* GL_RENDERER */
  char version[96];   /* GL_VERSION */
  int software;       /* llvmpipe / softpipe: LP_NUM_THREADS applies */
  int robust;         /* EGL: a robust context that reports resets (lost contexts) */
  int kind;           /* (gl_context.c) */
  void *display, *ctx, *osmesa_buf;
  /* what was current on the thread before ics_gl_make_current, restored by ics_gl_release */
  void *prev_display, *prev_ctx, *prev_draw, *prev_read;
  int prev_w, prev_h;
} ics_gl;

/* Opens a 4.5 core context of kind `which`: "osmesa", "egl" (the device platform's first
 * hardware device, else surfaceless) or "auto" (NULL too: egl, then osmesa; docs/backend_gl.md),
 * makes it current on the calling thread (ics_gl_release gives the thread back) and loads the
 * entry points. ICS_ERR_UNSUPPORTED with why (each kind tried and its failure) when none opens. */
ics_status ics_gl_open(ics_gl *g, const char *which, char *why, size_t why_size);
/* makes g current on the calling thread, remembering what was current (0 on failure) */
int ics_gl_make_current(ics_gl *g);
/* makes current again what was current before ics_gl_make_current (or nothing) */
void ics_gl_release(ics_gl *g);
void ics_gl_close(ics_gl *g); /* a zeroed or closed one is fine */
/* 1 when the EGL device platform lists a device that is not Mesa's software one (a GPU driver),
 * without opening a context; else 0 with why. */
int ics_gl_hardware_device(char *why, size_t why_size);
/* the context kind asked for: the gl backend's option gl.context in opts (may be NULL), else
 * ICS_GL_CONTEXT, else "auto" (backend_gl.c) */
struct ics_render_opts;
const char *ics_gl_context_kind(const struct ics_render_opts *opts);
/* 1 when `which` names a kind this build has ("auto", "osmesa", "egl"), else 0 */
int ics_gl_kind_known(const char *which);

/* With g current: compiles a compute shader from `source` (a file that starts with its #version
 * line) with `head` inserted after that line (the defines choosing an entry point; `name` for
 * messages) and links it into *prog. 0 with the compiler's or linker's log in msg. */
int ics_gl_compile(ics_gl *g, const char *source, const char *head, const char *name,
                   GLuint *prog, char *msg, size_t msg_size);
/* Uniforms by name (one the compiler removed is skipped). */
void ics_gl_uniform_i(ics_gl *g, GLuint prog, const char *name, int v);
void ics_gl_uniform_ui(ics_gl *g, GLuint prog, const char *name, unsigned v);
void ics_gl_uniform_d(ics_gl *g, GLuint prog, const char *name, double v);
/* A buffer of `bytes` (at least 4) holding `data`, or zeros when data is NULL; updatable. */
GLuint ics_gl_buffer(ics_gl *g, size_t bytes, const void *data);
/* The name of a glGetError code, and of a glGetGraphicsResetStatus one. */
const char *ics_gl_error_name(GLenum e);
const char *ics_gl_reset_name(GLenum reset);

#endif
