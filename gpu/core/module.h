/* module.h — the renderer's parts that need heavy libraries (the gl backend: EGL, OSMesa and
 * LLVM; the cl backend: OpenCL; the reference's Embree meshes; Assimp's mesh files) are shared
 * modules, loaded on first use (docs/architecture.md "Modules"), so a command that needs none of
 * them maps none of them and the rest runs where one is missing. A module is
 * icshadow-NAME.so in the module folder: $ICS_MODULE_DIR when set, else beside the code that
 * loads it: LIBDIR/icshadow for the library (and the Python package's copy), for a program in
 * bin/ that links the renderer statically ../LIBDIR/icshadow (the install tree) or the build
 * tree's lib/icshadow; no absolute path is compiled in. It exports one symbol,
 * ics_module_entry, whose build id must be the core's (an MD5 of every header they share,
 * cmake/module_build_id.cmake); the core hands it the functions it may call (module_host.h), so
 * a module links none of the renderer and works under a program that links the renderer
 * statically, the shared library, or the Python package. */
#ifndef ICS_RENDER_MODULE_H
#define ICS_RENDER_MODULE_H

#include <stddef.h>

#include "module_build_id.h" /* ICS_MODULE_BUILD_ID (generated) */

typedef struct ics_module_host ics_module_host;

/* What a module exports, as `ics_module_entry`. */
typedef struct ics_module_info {
  const char *build_id; /* ICS_MODULE_BUILD_ID when built */
  const char *name;
  void (*init)(const ics_module_host *host); /* called once, before api is used */
  const void *api;                           /* the module's table: an ics_backend, ... */
} ics_module_info;

/* Module `name`'s table, loading it on the first call (thread-safe; a failure is remembered
 * and reported again without retrying); NULL with the reason in why: not built, not found (the
 * folders tried), a library it needs missing (dlerror's words), a module of another build. */
const void *ics_module_api(const char *name, char *why, size_t why_size);

/* In a module (module_client.c): takes the host's table. */
void ics_module_client_init(const ics_module_host *host);
/* In a module: its entry, the one symbol it exports; api is its table. */
#define ICS_MODULE_DEFINE(NAME, API)                                                            \
  __attribute__((visibility("default"))) const ics_module_info ics_module_entry = {            \
      ICS_MODULE_BUILD_ID, NAME, ics_module_client_init, API};

#endif
