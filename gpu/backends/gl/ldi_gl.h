/* ldi_gl.h — the layered depth image built on the gl backend's device (gpu/backends/gl/ldi.comp): ray
 * cast into per-pixel linked lists, sorted into the buffers the shading reads, with the same
 * fragments as the plan's geometry pass (gpu/core/ldi.c). docs/backend_gl.md. */
#ifndef ICS_GL_LDI_H
#define ICS_GL_LDI_H

#include <stddef.h>

#include "gl_context.h"
#include "plan_internal.h"

enum { ICS_GL_LDI_CAST, ICS_GL_LDI_SCAN, ICS_GL_LDI_SORT, ICS_GL_LDI_NPROGS };

/* The result: the shading's buffers (owned; ics_gl_ldi_release), the fragment count, the
 * largest number of layers, how often the cast ran (a second time when the first pool was too
 * small) and the build's time on the host's clock (uploads and readbacks included). */
typedef struct ics_gl_ldi {
  GLuint offset, fz, fcode, fgrad, fspan, pix; /* as backend_gl.c's B_OFFSET .. B_PIX */
  size_t nfrag;
  int max_layers, casts;
  double ms;
} ics_gl_ldi;

/* With g current: compiles ldi.comp's programs (0 with the log in msg). */
int ics_gl_ldi_programs(ics_gl *g, GLuint prog[ICS_GL_LDI_NPROGS], char *msg, size_t msg_size);
/* With g current: builds P's layered depth image on the device. max_block: the driver's
 * GL_MAX_SHADER_STORAGE_BLOCK_SIZE, max_groups its GL_MAX_COMPUTE_WORK_GROUP_COUNT. ICS_OK;
 * ICS_ERR_SIZE (a buffer over the driver's limits, or crossings that may overflow the 32-bit
 * counter),
 * ICS_ERR_NOMEM (host or GL_OUT_OF_MEMORY) or ICS_ERR_UNSUPPORTED (another GL error, a lost
 * context), each with msg; on failure nothing is left allocated. */
ics_status ics_gl_ldi_build(ics_gl *g, const GLuint prog[ICS_GL_LDI_NPROGS], const ics_plan *P,
                            long long max_block, const int max_groups[3], ics_gl_ldi *out,
                            char *msg, size_t msg_size);
void ics_gl_ldi_release(ics_gl *g, ics_gl_ldi *l); /* a zeroed one is fine */

#endif
