/* list.h — the one list of backends: each is gpu/backends/NAME/ defining `const ics_backend
 * ics_backend_NAME` (core/backend.h), in the order `--backend auto` tries them. A backend that
 * needs an optional component is listed under its ICS_HAVE_* condition. Adding a backend: its
 * folder, one line here, one block in gpu/CMakeLists.txt (docs/architecture.md). */
#ifndef ICS_RENDER_BACKEND_LIST_H
#define ICS_RENDER_BACKEND_LIST_H

#ifdef ICS_HAVE_GL
#define ICS_BACKEND_IF_GL(X) X(gl)
#else
#define ICS_BACKEND_IF_GL(X)
#endif
#ifdef ICS_HAVE_OPENCL
#define ICS_BACKEND_IF_CL(X) X(cl)
#else
#define ICS_BACKEND_IF_CL(X)
#endif

/* gl first, but auto takes it only on a GPU; cpu always starts, so cl and mc follow it */
#define ICS_BACKEND_LIST(X) ICS_BACKEND_IF_GL(X) X(cpu) ICS_BACKEND_IF_CL(X) X(mc)

#endif
