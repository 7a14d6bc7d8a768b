/* mesh_reader.h — what the mesh-file reader in its child process (the module icshadow-assimp.so,
 * gpu/readers/assimp/mesh_assimp.c) and the parent that waits for it (mesh_import.c) agree on:
 * the module's one function, and what it sends through the pipe. */
#ifndef ICS_RENDER_MESH_READER_H
#define ICS_RENDER_MESH_READER_H

#include <stdint.h>
#include <sys/types.h>

/* what the child sends first: its status and message, then files_bytes of file names, nv x 3
 * floats, nt x 3 uint32 */
typedef struct ics_mesh_child_header {
  int32_t status;
  uint32_t files_bytes; /* the other files Assimp opened: their names, each ending in a NUL */
  uint64_t nv, nt;
  char msg[1024 + 64];
} ics_mesh_child_header;

#define ICS_MESH_CHILD_FILES_MAX (1u << 20) /* bytes of those names */

/* The module's table. child_import runs in the child just forked by `parent`: reads the mesh
 * file `path` with Assimp (every file it opens inside root, when root is not NULL), sends the
 * result through fd and never returns. */
typedef struct ics_mesh_reader_funcs {
  void (*child_import)(int fd, const char *path, const char *root, pid_t parent);
} ics_mesh_reader_funcs;

#endif
