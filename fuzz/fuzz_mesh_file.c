/* fuzz_mesh_file.c — libFuzzer harness for mesh files (ics_mesh_read_file and ics_mesh_create_raw,
 * gpu/core/mesh.c, and Assimp behind them): the input's first byte picks the format (even: OBJ,
 * odd: PLY, as the scratch file's extension), the rest is the file, read with a 5 s limit and
 * the scratch folder as the folder every file it names must lie in (mesh_import.c runs
 * Assimp in a child process: its crashes and hangs become refusals). Invariants: a refused file
 * gives no mesh and a message that names the file; a loaded one has 1..ICS_MESH_MAX_TRIANGLES triangles, finite
 * bounds with lo <= hi that hold every vertex, and a closedness flag of 0 or 1; and for rays from
 * outside its box towards its centre (along the axes, a diagonal and a skew direction), and
 * from the centre itself, every crossing ics_mesh_hits reports is finite, in front of the
 * origin (t > 0) and in order, no more of them than twice the triangles, and a count of
 * crossings behind the origin that is not negative. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_require.h"
#include "geometry.h"
#include "mesh.h"

static void check_rays(const ics_mesh *m) {
  double lo[3], hi[3], c[3], r = 0;
  ics_mesh_bounds(m, lo, hi);
  for (int i = 0; i < 3; i++) c[i] = 0.5 * (lo[i] + hi[i]), r = fmax(r, hi[i] - lo[i]);
  static const double dirs[][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {0.3, -0.7, 0.2}};
  ics_hits h = {0};
  int ntris = ics_mesh_triangle_count(m);
  for (size_t k = 0; k < 2 * sizeof dirs / sizeof *dirs; k++) {
    const double *d = dirs[k % 5];
    double o[3];
    for (int i = 0; i < 3; i++) o[i] = k < 5 ? c[i] - 2 * (r + 1) * d[i] : c[i];
    h.n = 0;
    int behind = 0;
    if (ics_mesh_hits(m, o, d, &h, &behind)) break; /* out of memory: nothing to check */
    REQUIRE(behind >= 0 && h.n <= 2 * ntris);
    for (int i = 0; i < h.n; i++) {
      REQUIRE(isfinite(h.h[i].t) && h.h[i].t > 0);
      REQUIRE(i == 0 || h.h[i - 1].t <= h.h[i].t);
    }
  }
  ics_hits_free(&h);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1 || size > 65536) return 0;
  static char path[2][256];
  const char *td = getenv("TMPDIR");
  int fmt = data[0] & 1;
  if (!path[fmt][0])
    snprintf(path[fmt], sizeof path[fmt], "%s/fuzz_mesh_file.%ld.%s", td && *td ? td : "/tmp",
             (long)getpid(), fmt ? "ply" : "obj");
  FILE *f = fopen(path[fmt], "wb");
  if (!f) return 0;
  int ok = fwrite(data + 1, 1, size - 1, f) == size - 1;
  if (fclose(f) || !ok) return 0;
  static const double one[3] = {1, 1, 1}, zero[3] = {0, 0, 0};
  static char *root; /* the scratch folder: the files the mesh names must lie in it */
  if (!root && !(root = realpath(td && *td ? td : "/tmp", NULL))) return 0;
  ics_mesh *m = NULL;
  char msg[2048] = "";
  ics_mesh_raw raw;
  ics_status st = ics_mesh_read_file(&raw, path[fmt], 5, root, msg, sizeof msg);
  if (st == ICS_OK)
    st = ics_mesh_create_raw(&m, &raw, one, zero, zero, path[fmt], msg, sizeof msg);
  ics_mesh_raw_release(&raw);
  if (st != ICS_OK) {
    REQUIRE(m == NULL && (st == ICS_ERR_NOMEM || strstr(msg, path[fmt]) != NULL));
    return 0;
  }
  int n = ics_mesh_triangle_count(m);
  REQUIRE(n >= 1 && n <= ICS_MESH_MAX_TRIANGLES);
  double lo[3], hi[3];
  ics_mesh_bounds(m, lo, hi);
  for (int i = 0; i < 3; i++) REQUIRE(isfinite(lo[i]) && isfinite(hi[i]) && lo[i] <= hi[i]);
  for (int k = 0; k < n; k++) {
    double v[3][3];
    ics_mesh_triangle(m, k, v);
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) REQUIRE(v[j][i] >= lo[i] && v[j][i] <= hi[i]);
  }
  int closed = ics_mesh_closed(m);
  REQUIRE(closed == 0 || closed == 1);
  check_rays(m);
  ics_mesh_destroy(m);
  return 0;
}
