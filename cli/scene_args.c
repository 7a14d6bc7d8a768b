/* scene_args.c — the SCENE argument and the render-setting overrides of `render` and `plan`
 * (see scene_args.h). */
#include "scene_args.h"

#ifdef ICS_HAVE_RENDER
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --resolution WxH, W and H in 1..ICS_SCENE_MAX_RES */
static int parse_res(const char *cmd, const char *opt, const char *v, void *dest) {
  int *wh = dest;
  char bw[32], bh[32];
  if (sscanf(v, "%31[0-9]x%31[0-9]", bw, bh) != 2 || strlen(v) != strlen(bw) + strlen(bh) + 1 ||
      cli_parse_int(bw, 1, ICS_SCENE_MAX_RES, &wh[0]) ||
      cli_parse_int(bh, 1, ICS_SCENE_MAX_RES, &wh[1]))
    return cli_error(cmd, "%s: expected WxH with W, H in 1..%d, got '%s'", opt, ICS_SCENE_MAX_RES,
                     v);
  return 0;
}

void scene_args_options(scene_args *a, cli_option *o) {
  const cli_option opts[SCENE_ARGS_NOPTS] = {
      {NULL, .kind = CLI_STRING, .dest = &a->scene, .given = &a->scenes},
      {"--resolution", .kind = CLI_CALL, .dest = a->res, .parse = parse_res},
      {"--kernel", .kind = CLI_STRING, .dest = &a->kernel},
      {"--samples", .kind = CLI_INT, .dest = &a->samples, .lo = 2, .hi = 64, .given = &a->have_samples},
      {"--compensate", .kind = CLI_STRING, .dest = &a->compensate},
      {"--radii", .kind = CLI_STRING, .dest = &a->radii},
      {"--slab-spacing", .kind = CLI_FINITE, .dest = &a->slab_spacing, .given = &a->have_slab},
      {"--d1", .kind = CLI_FINITE, .dest = &a->d1, .given = &a->have_d1},
      {"--seed", .kind = CLI_SEED, .dest = &a->seed, .given = &a->have_seed},
      {"--threads", .kind = CLI_INT, .dest = &a->threads, .lo = 0, .hi = 256},
      {"--dense", .kind = CLI_FLAG, .dest = &a->dense},
      {"--model", .kind = CLI_STRING, .dest = &a->model},
      {"--allow-outside-paths", .kind = CLI_FLAG, .dest = &a->outside},
  };
  memcpy(o, opts, sizeof opts);
}

void scene_args_help(FILE *f) {
  fprintf(f,
          "  SCENE               a scene file (JSON, docs/scene-format.md); none: the embedded\n"
          "                      default scene\n"
          "  --resolution WxH    override the camera's resolution\n"
          "  --kernel K          ellipse, poisson, gauss or tophat (override render.kernel)\n"
          "  --samples N         taps (ellipse, poisson) or grid side (gauss, tophat), 2..64\n"
          "  --compensate MODE   expected, integer, nonneg, signed or none (docs/renderer.md)\n"
          "  --radii exact|lut   ellipse radii from the elliptic integrals or the 256-entry LUT\n"
          "  --slab-spacing E    slab spacing in world units (> 0)\n"
          "  --d1 D              Patel's optimal distance (> 0)\n"
          "  --seed S            counter-RNG seed (same seed: same image)\n"
          "  --threads N         threads (0, the default: all cores)\n"
          "  --dense             propagate every light-buffer pixel at every slab (render.dense:\n"
          "                      no skipping of inactive regions and constant tiles)\n"
          "  --model M           override render.model (a scene's default: auto): auto (the\n"
          "                      closest model the backend renders: blocker on cpu, patel on\n"
          "                      cl, gl and mc, and patel for a scene of more than 64 volumes\n"
          "                      and solids; `plan` plans it as blocker), patel (Patel's\n"
          "                      slicing, as in the paper), solid (+ closed opaque objects\n"
          "                      solid), surface (+ own light terms in closed form) or blocker\n"
          "                      (+ blocker-aware penumbrae) (docs/renderer.md \"Models\"; cl\n"
          "                      and gl render patel only). blocker is the closest to the\n"
          "                      reference; at 3x the slab spacing it takes Patel's frame time\n"
          "                      (docs/results.md)\n"
          "  --allow-outside-paths  let the scene read files (lights_file, grids, meshes and the\n"
          "                      files they name) outside its own folder\n");
}

static int pick(const char *cmd, const char *opt, const char *v, const char *(*name)(int), int lo,
                int hi, int *out) {
  for (int i = lo; i < hi; i++)
    if (name(i) && !strcmp(v, name(i))) {
      *out = i;
      return 0;
    }
  char list[256] = "";
  size_t n = 0;
  for (int i = lo; i < hi && n < sizeof list; i++)
    n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", i > lo ? ", " : "", name(i));
  return cli_error(cmd, "%s: unknown value '%s' (expected %s)", opt, v, list);
}

static const char *kernel_name(int i) { return ics_render_kernel_name((ics_render_kernel)i); }
static const char *comp_name(int i) { return ics_render_comp_name((ics_render_comp)i); }
static const char *radii_name(int i) { return i == 0 ? "exact" : i == 1 ? "lut" : NULL; }
static const char *model_name(int i) { return ics_render_model_name((ics_render_model)i); }

int scene_args_model(const char *cmd, const char *v, ics_render_model *model) {
  int i = 0, rc = pick(cmd, "--model", v, model_name, 0, ICS_MODEL_COUNT_, &i);
  if (!rc) *model = (ics_render_model)i;
  return rc;
}

int scene_args_load(const char *cmd, const scene_args *a, ics_scene **s, ics_render_settings *rs,
                    ics_plan_opts *po) {
  char msg[CLI_MSG_MAX] = "";
  if (a->scenes > 1) return cli_error(cmd, "give one SCENE (got %d)", a->scenes);
  ics_scene_opts so = {.allow_outside_paths = a->outside};
  ics_status st = a->scene ? ics_scene_create_file_opts(s, a->scene, &so, msg, sizeof msg)
                           : ics_scene_create_default(s);
  if (st != ICS_OK)
    return st == ICS_ERR_NOMEM ? cli_failure(cmd, "%s", a->scene ? msg : "out of memory")
                               : cli_error(cmd, "%s", a->scene ? msg : ics_status_str(st));
  *rs = *ics_scene_settings(*s);
  int v = 0, rc = 0;
  if (a->kernel && !(rc = pick(cmd, "--kernel", a->kernel, kernel_name, 0, ICS_RK_COUNT_, &v))) {
    rs->kernel = (ics_render_kernel)v;
    if (!a->have_samples) {
      static const int dflt[] = {2, 8, 19, 5};
      rs->samples = dflt[v];
    }
  }
  if (!rc && a->have_samples) {
    static const int lo[] = {2, 3, 2, 2};
    if (a->samples < lo[rs->kernel])
      rc = cli_error(cmd, "--samples: %d is too few for %s (at least %d)", a->samples,
                     ics_render_kernel_name(rs->kernel), lo[rs->kernel]);
    rs->samples = a->samples;
  }
  if (!rc && a->compensate &&
      !(rc = pick(cmd, "--compensate", a->compensate, comp_name, 1, ICS_RC_COUNT_, &v)))
    rs->compensate = (ics_render_comp)v;
  if (!rc && a->radii && !(rc = pick(cmd, "--radii", a->radii, radii_name, 0, 2, &v)))
    rs->lut_radii = v;
  if (!rc && a->model) rc = scene_args_model(cmd, a->model, &rs->model);
  if (!rc && a->have_slab) {
    if (!(a->slab_spacing > 0)) rc = cli_error(cmd, "--slab-spacing: must be > 0, got %g", a->slab_spacing);
    rs->slab_spacing = a->slab_spacing;
  }
  if (!rc && a->have_d1) {
    if (!(a->d1 > 0)) rc = cli_error(cmd, "--d1: must be > 0, got %g", a->d1);
    rs->d1 = a->d1;
  }
  if (a->have_seed) rs->seed = a->seed;
  if (a->dense) rs->dense = 1;
  if (rc) {
    ics_scene_destroy(*s);
    *s = NULL;
    return rc;
  }
  memset(po, 0, sizeof *po);
  po->settings = rs;
  po->width = a->res[0];
  po->height = a->res[1];
  po->threads = a->threads;
  return 0;
}
int scene_args_check_outputs(const char *cmd, const ics_scene *s, const cli_path *extra,
                             int nextra, const cli_path *out, int nout) {
  int nf = ics_scene_file_count(s);
  cli_path *in = malloc(sizeof *in * (size_t)(nf + nextra ? nf + nextra : 1));
  if (!in) return cli_failure(cmd, "out of memory");
  for (int k = 0; k < nf; k++)
    in[k] = (cli_path){k == 0 && !strcmp(ics_scene_file(s, 0), ics_scene_name(s)) ? "scene file"
                                                                                 : "scene's input",
                       ics_scene_file(s, k)};
  for (int k = 0; k < nextra; k++) in[nf + k] = extra[k];
  int rc = cli_check_outputs(cmd, in, nf + nextra, out, nout);
  free(in);
  return rc;
}
#endif
