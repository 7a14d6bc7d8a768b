/* test_render_plan.c — the render plan: passes left out on scenes built not to need them
 * (no volumes: no detail or volume tracking; grey transport: one light-buffer channel;
 * zero-variance light: integer shifts, no taps; no meshes: no BVH), passes present on scenes that
 * need them, the depth complexity of the layered depth image, the budgets (refused before
 * allocating, with the estimate), and the memory figure: a render's peak resident memory stays
 * within 1.25 x memory_bytes + 32 MiB on scenes of several sizes (each in a child process, whose
 * VmHWM is its own). */
#define _GNU_SOURCE
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "render_util.h"
#include "testutil.h"

static const char *surfaces =
    "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 3, \"resolution\": [%d, %d]},"
    " \"render\": {\"slab_spacing\": 0.01, \"d1\": 1},"
    " \"lights\": [{\"mean\": [0.2, 0], \"cov\": [[0, 0], [0, 0]]}, {\"mean\": [0, 0.1], \"var\": [0.01, 0.002]}],"
    " \"materials\": {\"a\": {\"color\": [0.5, 0.5, 0.5]}, \"b\": {\"opacity\": 0.5, \"transport\": [%s]}},"
    " \"objects\": [{\"shape\": \"box\", \"center\": [0, 0, 0], \"size\": [0.5, 0.5, 0.5], \"material\": \"b\"},"
    "  {\"shape\": \"sphere\", \"center\": [0.6, 0, 0.3], \"radius\": 0.2, \"material\": \"b\"},"
    "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [3, 3], \"material\": \"a\"}]}";

static int has_pass(const ics_plan *p, const char *name) {
  for (int i = 0; i < ics_plan_pass_count(p); i++)
    if (!strcmp(ics_plan_pass_at(p, i)->name, name)) return 1;
  return 0;
}
static int has_omitted(const ics_plan *p, const char *name) {
  for (int i = 0; i < ics_plan_omitted_count(p); i++)
    if (strstr(ics_plan_omitted_at(p, i)->name, name)) return 1;
  return 0;
}

static ics_plan *plan_of(const char *json, char *msg, size_t n, ics_status *st, ics_scene **sc) {
  *sc = scene_from_json(json);
  ics_plan *p = NULL;
  *st = ics_plan_create(&p, *sc, NULL, msg, n);
  return p;
}

static void test_omissions(void) {
  char json[4096], msg[1024];
  ics_status st;
  ics_scene *s;
  snprintf(json, sizeof json, surfaces, 64, 64, "0.3, 0.3, 0.3");
  ics_plan *p = plan_of(json, msg, sizeof msg, &st, &s);
  CHECK(st == ICS_OK, "surfaces plan: %s", msg);
  if (p) {
    CHECK(has_omitted(p, "detail") && has_omitted(p, "volume tracking"), "no volumes: detail omitted");
    CHECK(has_omitted(p, "colour light buffers"), "grey transport: one channel");
    CHECK(has_omitted(p, "convolution taps (light 0)") && has_pass(p, "shift"),
          "zero-variance light 0: integer shifts");
    CHECK(has_pass(p, "convolution") && !has_omitted(p, "convolution taps (light 1)"), "light 1 convolves");
    CHECK(has_omitted(p, "mesh_bvh") && !has_pass(p, "detail"), "no meshes, no detail pass");
    CHECK(ics_plan_pass_at(p, 0)->bytes > 0 && !strcmp(ics_plan_pass_at(p, 0)->name, "layered_depth_image"),
          "LDI pass first");
    /* depth complexity: box (2) + sphere (2) + receiver (1) overlap at most where the box meets
     * the receiver's rays: the LDI has exactly the layers the rays cross */
    CHECK(strstr(ics_plan_pass_at(p, 0)->detail, "3 layer(s) max") != NULL, "layers: %s",
          ics_plan_pass_at(p, 0)->detail);
    ics_plan_destroy(p);
  }
  ics_scene_destroy(s);
  snprintf(json, sizeof json, surfaces, 64, 64, "1, 0.3, 0.3");
  p = plan_of(json, msg, sizeof msg, &st, &s);
  CHECK(p && !has_omitted(p, "colour light buffers"), "coloured transport: three channels");
  ics_plan_destroy(p);
  ics_scene_destroy(s);
  /* the default scene: detail, volumes */
  ics_scene *d;
  ics_scene_create_default(&d);
  CHECK(ics_plan_create(&p, d, NULL, msg, sizeof msg) == ICS_OK, "default plan: %s", msg);
  if (p) {
    CHECK(has_pass(p, "detail") && !has_omitted(p, "volume tracking"), "default scene: detail pass");
    ics_plan_destroy(p);
  }
  ics_scene_destroy(d);
}

static void test_budgets(void) {
  char json[4096], msg[1024];
  ics_status st;
  ics_scene *s;
  /* 16384^2 x 2 lights x 2 buffers (patel; blocker's sets exceed the work limit first): far
   * over a 64 MiB limit, refused before the geometry pass */
  snprintf(json, sizeof json, surfaces, 16384, 16384, "0.3, 0.3, 0.3");
  static const char limit[] = "\"d1\": 1, \"memory_limit_mib\": 64, \"model\": \"patel\"}";
  char *big = malloc(strlen(json) + sizeof limit);
  strcpy(big, json);
  char *r = strstr(big, "\"d1\": 1}");
  memmove(r + strlen(limit), r + 8, strlen(r + 8) + 1);
  memcpy(r, limit, strlen(limit));
  double t0 = (double)clock() / CLOCKS_PER_SEC;
  ics_plan *p = plan_of(big, msg, sizeof msg, &st, &s);
  double t = (double)clock() / CLOCKS_PER_SEC - t0;
  CHECK(st == ICS_ERR_SIZE && !p && strstr(msg, "MiB") && strstr(msg, "memory_limit_mib"),
        "memory budget: %s (%s)", msg, ics_status_str(st));
  CHECK(t < 0.5, "refused before the geometry pass (%.2f s)", t);
  ics_scene_destroy(s);
  free(big);
  /* tiny slabs: too many */
  snprintf(json, sizeof json, surfaces, 64, 64, "0.3, 0.3, 0.3");
  char *tiny = malloc(strlen(json) + 16);
  strcpy(tiny, json);
  r = strstr(tiny, "0.01");
  memmove(r + 8, r + 4, strlen(r + 4) + 1);
  memcpy(r, "0.000001", 8);
  p = plan_of(tiny, msg, sizeof msg, &st, &s);
  CHECK(st == ICS_ERR_SIZE && !p && strstr(msg, "slab"), "slab budget: %s", msg);
  ics_scene_destroy(s);
  free(tiny);
}

static long vm_hwm_kib(void) {
  FILE *f = fopen("/proc/self/status", "r");
  if (!f) return -1;
  char line[256];
  long v = -1;
  while (fgets(line, sizeof line, f))
    if (!strncmp(line, "VmHWM:", 6)) v = atol(line + 6);
  fclose(f);
  return v;
}

/* in a child: plan + render; exit 0 when peak RSS growth <= 1.25 memory_bytes + 32 MiB */
static void test_memory(const char *scene_json, const char *name) {
  fflush(stdout);
  pid_t pid = fork();
  if (pid == 0) {
    long before = vm_hwm_kib();
    ics_scene *s = scene_from_json(scene_json);
    render_result r = render_scene(s, NULL, 2);
    long after = vm_hwm_kib();
    double peak = (after - before) * 1024.0, limit = 1.25 * r.memory_bytes + 32.0 * 1048576;
    printf("%s: memory_bytes %.1f MiB, peak resident growth %.1f MiB (limit %.1f MiB)\n", name,
           r.memory_bytes / 1048576.0, peak / 1048576.0, limit / 1048576.0);
    fflush(stdout);
    _exit(before < 0 || after < 0 ? 3 : peak <= limit ? 0 : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s: peak memory over 1.25 x plan + 32 MiB "
        "(child status %d)", name, status);
}

int main(void) {
  test_omissions();
  test_budgets();
  char json[4096];
  int sizes[3][2] = {{128, 96}, {512, 384}, {1024, 768}};
  for (int i = 0; i < 3; i++) {
    snprintf(json, sizeof json, surfaces, sizes[i][0], sizes[i][1], "1, 0.3, 0.3");
    char name[64];
    snprintf(name, sizeof name, "surfaces %dx%d", sizes[i][0], sizes[i][1]);
    test_memory(json, name);
  }
  const char *def = ics_scene_default_json();
  test_memory(def, "default scene 320x240");
  return test_summary("test_render_plan");
}
