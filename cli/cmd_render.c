/* cmd_render.c — `icshadow render [SCENE] [-o out.exr] [--png out.png] [--backend B]
 * [--threads N] ...`: plans and renders a scene (the embedded default scene without SCENE) with
 * the slab renderer (libicshadow_render), writes a float RGBA OpenEXR (with AOVs when asked)
 * and/or an sRGB PNG preview (atomically, both or neither), and prints a JSON summary with the time per pass. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "backend_options.h"
#include "commands.h"
#include "render_compare.h"
#include "scene_args.h"

static const char CMD[] = "render";

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow render [SCENE] [-o OUT.exr] [--png OUT.png] [--backend B] [options]\n"
          "Renders a scene with the slab renderer (Patel et al. 2013, Sec. 4; docs/renderer.md), or\n"
          "with the Monte-Carlo reference (--backend mc; docs/reference.md): the embedded default\n"
          "scene when no SCENE is given. Prints a JSON summary on stdout\n"
          "(backend, threads, slabs, ms per frame and per pass, memory); progress on stderr.\n\n"
          "options:\n");
#ifdef ICS_HAVE_RENDER
  scene_args_help(f);
#endif
  fprintf(f,
          "  -o OUT.exr          float RGBA OpenEXR, row 0 at the top (RGB over the background,\n"
          "                      A = opacity)\n"
          "  --png OUT.png       8-bit sRGB preview\n"
          "  --aov LIST          AOVs in the EXR beside R, G, B, A, at each pixel's first surface:\n"
          "                      visibility (lightL.V, or lightL.R/G/B with coloured transport:\n"
          "                      the fraction of light L reaching it), depth (Z, view depth);\n"
          "                      stderr (--backend mc: standard errors, stderr.R ...);\n"
          "                      comma-separated, or all. 0 where a pixel has no surface\n"
          "  --backend B         auto (default) or a backend of `icshadow render --backends`\n"
          "  --backends          list the backends built into this binary, with their options, and\n"
          "                      the modules with whether they load, and exit\n");
#ifdef ICS_HAVE_RENDER
  backend_options_help(f); /* --cl-device, --gl-context, ...: from the backend table */
#endif
  fprintf(f,
          "  --spp N             mc: samples per pixel (1..16777216; default 64 when no other stop)\n"
          "  --time S            mc: stop after S seconds (checked inside the paths too: the samples\n"
          "                      every pixel finished by then)\n"
          "  --noise E           mc: stop once the RMS standard error of R, G, B is at most E\n"
          "                      (the first of --spp, --time, --noise that is reached stops; a time\n"
          "                      or noise stop takes 2 samples at least where the time allows;\n"
          "                      bound --noise with --time)\n"
          "  --mc-mesh M         mc (and --reference): mesh crossings through embree (Embree 3)\n"
          "                      or bvh (the renderer's own BVH); auto (default): Embree when\n"
          "                      built in. The summary's device (with --reference: its\n"
          "                      compare.reference_device) says which ran\n"
          "  --compare REF.exr   compare R, G, B with a reference image (e.g. an mc render): RMSE,\n"
          "                      max error, PSNR, the reference's time and noise, in the summary\n"
          "  --reference N       the same against the Monte-Carlo reference rendered here with N\n"
          "                      samples per pixel (1..16777216)\n"
          "  --diff-png FILE     with --compare / --reference: render minus reference, x4, as a\n"
          "                      picture (red: brighter, blue: darker than the reference)\n"
          "  --progress          show progress on stderr even when it is not a terminal\n"
          "  --verbose           say on stderr why --backend auto passed over a backend (also\n"
          "                      shown on a terminal, or when a backend option was given)\n"
          "With only --compare or --reference and no output, the summary alone is printed.\n"
          "ICS_SIMD=auto|scalar|sse2|avx2|avx512|neon in the environment forces the cpu backend's\n"
          "vector path (default auto: the widest this processor has); the summary's device names it.\n"
          "Output files are written to a temporary name and renamed once all are complete.\n"
          "Exit status: 0 ok, 1 cannot write or out of memory, 2 bad input.\n");
}

#ifdef ICS_HAVE_RENDER
typedef struct {
  cli_progress p;
  double t_last;
} slab_progress;

static void on_slab(void *ctx, int k, int n) {
  slab_progress *sp = ctx;
  double t = cli_now_s();
  if (k < n && t - sp->t_last < 0.25) return;
  sp->t_last = t;
  cli_progress_say(&sp->p, "slab %d/%d", k, n);
}

/* mc: samples per pixel so far (of n, or open-ended when n = 0) */
static void on_sample(void *ctx, int k, int n) {
  slab_progress *sp = ctx;
  double t = cli_now_s();
  if ((n == 0 || k < n) && t - sp->t_last < 0.25) return;
  sp->t_last = t;
  if (n)
    cli_progress_say(&sp->p, "sample %d/%d", k, n);
  else
    cli_progress_say(&sp->p, "sample %d", k);
}

/* --aov: "visibility", "depth", "stderr", "all" (with all_extra: the backend's further AOVs),
 * comma-separated; 0 and *bits set, or the exit status after the message */
static int parse_aovs(const char *list, unsigned all_extra, unsigned *bits) {
  *bits = 0;
  const char *p = list;
  for (;;) {
    size_t n = strcspn(p, ",");
    if (n == 10 && !strncmp(p, "visibility", n))
      *bits |= ICS_AOV_VISIBILITY;
    else if (n == 5 && !strncmp(p, "depth", n))
      *bits |= ICS_AOV_DEPTH;
    else if (n == 6 && !strncmp(p, "stderr", n))
      *bits |= ICS_AOV_STDERR;
    else if (n == 3 && !strncmp(p, "all", n))
      *bits |= ICS_AOV_VISIBILITY | ICS_AOV_DEPTH | all_extra;
    else
      return cli_error(CMD, "--aov %s: '%.*s' is not an AOV (visibility, depth, stderr, all)", list,
                       (int)n, p);
    if (!p[n]) return 0;
    p += n + 1;
  }
}

/* the image's R, G, B, A and the AOV channels as one float EXR, with the summary as its info */
static ics_status write_exr(const char *path, const ics_image *img, const ics_exr_channels *aov,
                            const char *info, char *msg, size_t msg_size) {
  static const char *const rgba[4] = {"R", "G", "B", "A"};
  int na = aov ? aov->count : 0, n = 4 + na;
  size_t npx = (size_t)img->width * img->height;
  const char **names = malloc(sizeof *names * (size_t)n);
  float *data = malloc(sizeof *data * npx * (size_t)n);
  if (!names || !data) {
    free(names), free(data);
    snprintf(msg, msg_size, "out of memory");
    return ICS_ERR_NOMEM;
  }
  for (int c = 0; c < n; c++) names[c] = c < 4 ? rgba[c] : aov->names[c - 4];
  for (size_t p = 0; p < npx; p++)
    for (int c = 0; c < n; c++)
      data[p * n + c] = c < 4 ? img->data[p * 4 + c] : aov->data[p * na + c - 4];
  ics_exr_channels ch = {img->width, img->height, n, names, data, info};
  ics_status st = ics_exr_write_channels(path, &ch, ICS_EXR_FLOAT, 0, msg, msg_size);
  free(names), free(data);
  return st;
}

static int list_backends(void) {
  for (int i = 0; i < ics_backend_count(); i++) {
    char why[256] = "";
    int ok = ics_backend_available(ics_backend_name(i), why, sizeof why);
    printf("%-6s %s%s%s\n", ics_backend_name(i), ics_backend_description(i), ok ? "" : " -- not available: ",
           ok ? "" : why);
    for (int j = 0; j < ics_backend_option_count(i); j++) { /* its options, as flags */
      const char *values = ics_backend_option_values(i, j), *env = ics_backend_option_env(i, j);
      printf("       --%s-%s %s%s%s%s\n", ics_backend_name(i), ics_backend_option_name(i, j),
             values ? values : "VALUE", env ? " (default: $" : "", env ? env : "", env ? ")" : "");
    }
  }
  printf("modules (loaded on first use; ICS_MODULE_DIR overrides where):\n");
  for (int i = 0; i < ics_render_module_count(); i++) {
    char why[1024] = "";
    int ok = ics_render_module_loads(ics_render_module_name(i), why, sizeof why);
    printf("  %-7s %s: %s%s\n", ics_render_module_name(i), ics_render_module_purpose(i),
           ok ? "loads" : "does not load: ", ok ? "" : why);
  }
  return 0;
}

/* the command line of `render` */
typedef struct render_args {
  scene_args a;
  const char *exr, *png, *backend, *aov_list, *compare, *diff_png, *mc_mesh;
  int force_progress, verbose, backends, spp, ref_spp, given_ref, mc;
  double time_s, noise;
  int given_spp, given_time, given_noise;
  unsigned aovs;
  backend_options bo;
} render_args;

/* the options that only make sense together, and the components the outputs need */
static int check_args(render_args *r) {
  int rc;
  if (!r->exr && !r->png && !r->diff_png && !r->compare && !r->given_ref)
    return cli_error(CMD, "nothing to write: give -o OUT.exr and/or --png OUT.png (or only "
                     "measure: --compare REF.exr or --reference N)");
  size_t ne = r->exr ? strlen(r->exr) : 0;
  if (ne >= 4 && !strcmp(r->exr + ne - 4, ".png"))
    return cli_error(CMD, "-o %s: -o writes OpenEXR; give the PNG preview with --png", r->exr);
  if ((r->exr && !strcmp(r->exr, "-")) || (r->png && !strcmp(r->png, "-")) ||
      (r->diff_png && !strcmp(r->diff_png, "-")))
    return cli_error(CMD, "images are written to files, not to stdout (the summary goes there)");
  r->mc = r->backend && !strcmp(r->backend, "mc");
  if ((r->given_spp || r->given_time || r->given_noise) && !r->mc)
    return cli_error(CMD, "%s: only the Monte-Carlo reference takes a stop (give --backend mc)",
                     r->given_spp ? "--spp" : r->given_time ? "--time" : "--noise");
  if (r->given_time && !(r->time_s > 0)) return cli_error(CMD, "--time: must be > 0 seconds");
  if (r->given_noise && !(r->noise > 0)) return cli_error(CMD, "--noise: must be > 0");
  if (r->mc_mesh && strcmp(r->mc_mesh, "auto") && strcmp(r->mc_mesh, "embree") &&
      strcmp(r->mc_mesh, "bvh"))
    return cli_error(CMD, "--mc-mesh %s: expected auto, embree or bvh", r->mc_mesh);
  if (r->mc_mesh && !r->mc && !r->given_ref)
    return cli_error(CMD, "--mc-mesh: only the Monte-Carlo reference takes it (give --backend mc "
                     "or --reference N)");
  if (r->compare && r->given_ref) return cli_error(CMD, "give --compare or --reference, not both");
  if (r->given_ref && r->mc)
    return cli_error(CMD, "--reference: this render is the Monte-Carlo reference itself (same seed, "
                     "same samples); compare two mc renders with --compare REF.exr and another --seed");
  if (r->diff_png && !r->compare && !r->given_ref)
    return cli_error(CMD, "--diff-png: give --compare REF.exr or --reference N");
  if (r->diff_png && !ics_output_png_available())
    return cli_failure(CMD, "cannot write PNG: libpng was not found when the renderer was built");
  if (r->compare && !ics_exr_available())
    return cli_failure(CMD, "--compare: OpenEXR was not found when icshadow was built");
  if (r->aov_list && (rc = parse_aovs(r->aov_list, r->mc ? ICS_AOV_STDERR : 0, &r->aovs))) return rc;
  if (r->aovs && !r->exr) return cli_error(CMD, "--aov: AOVs go into the EXR; give -o OUT.exr");
  if (r->exr && !ics_exr_available())
    return cli_failure(CMD, "cannot write OpenEXR: OpenEXR was not found when icshadow was built");
  if (r->png && !ics_output_png_available())
    return cli_failure(CMD, "cannot write PNG: libpng was not found when the renderer was built");
  if (r->backend && strcmp(r->backend, "auto")) {
    char why[256];
    ics_render_opts ro = {.options = backend_options_list(&r->bo)};
    if (!ics_backend_available_opts(r->backend, &ro, why, sizeof why))
      return cli_error(CMD, "--backend: %s", why);
  }
  return 0;
}

/* parses and checks the command line; 0, or the exit status (`--backends` lists and exits 0
 * through *listed) */
static int parse_args(render_args *r, int argc, char **argv, int *listed) {
  memset(r, 0, sizeof *r);
  *listed = 0;
  const cli_option mine[] = {
      {"-o", .kind = CLI_FILE, .dest = &r->exr},
      {"--png", .kind = CLI_FILE, .dest = &r->png},
      {"--aov", .kind = CLI_STRING, .dest = &r->aov_list},
      {"--backend", .kind = CLI_STRING, .dest = &r->backend},
      {"--backends", .kind = CLI_FLAG, .dest = &r->backends},
      {"--progress", .kind = CLI_FLAG, .dest = &r->force_progress},
      {"--verbose", .kind = CLI_FLAG, .dest = &r->verbose},
      {"--spp", .kind = CLI_INT, .dest = &r->spp, .lo = 1, .hi = 1 << 24, .given = &r->given_spp},
      {"--time", .kind = CLI_FINITE, .dest = &r->time_s, .given = &r->given_time},
      {"--noise", .kind = CLI_FINITE, .dest = &r->noise, .given = &r->given_noise},
      {"--compare", .kind = CLI_FILE, .dest = &r->compare},
      {"--diff-png", .kind = CLI_FILE, .dest = &r->diff_png},
      {"--reference", .kind = CLI_INT, .dest = &r->ref_spp, .lo = 1, .hi = 1 << 24, .given = &r->given_ref},
      {"--mc-mesh", .kind = CLI_STRING, .dest = &r->mc_mesh},
  };
  cli_option opts[SCENE_ARGS_NOPTS + CLI_NOPTS(mine) + BACKEND_OPTIONS_MAX];
  scene_args_options(&r->a, opts);
  memcpy(opts + SCENE_ARGS_NOPTS, mine, sizeof mine);
  int nopts = SCENE_ARGS_NOPTS + CLI_NOPTS(mine);
  nopts += backend_options_table(&r->bo, opts + nopts);
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, nopts);
  if (rc) return rc;
  if (r->backends) {
    *listed = 1;
    return list_backends();
  }
  return check_args(r);
}

/* the renderer of the backend asked for, its progress into *sp (the backend options' warnings);
 * 0, or the exit status after the message */
static int open_renderer(render_args *r, slab_progress *sp, ics_renderer **rd) {
  char msg[CLI_MSG_MAX] = "";
  sp->t_last = cli_now_s();
  cli_progress_init(&sp->p, "render", r->force_progress);
  ics_render_opts ro = {.backend = r->backend, .threads = r->a.threads, .spp = r->spp,
                        .time_s = r->time_s, .noise = r->noise, .mc_mesh = r->mc_mesh,
                        .options = backend_options_list(&r->bo)};
  if (sp->p.on) ro.progress = r->mc ? on_sample : on_slab, ro.progress_ctx = sp;
  ics_status st = ics_renderer_create(rd, &ro, msg, sizeof msg);
  if (st != ICS_OK) return cli_status_error(CMD, st, "%s", msg);
  backend_options_warn(&r->bo, CMD, ics_renderer_backend(*rd), ics_renderer_note(*rd));
  return 0;
}

/* the render on renderer rd (progress sp, the auto note); 0, or the exit status after the
 * message */
static int render_image(render_args *r, ics_renderer *rd, slab_progress *sp, const ics_plan *plan,
                        ics_image **img, ics_exr_channels **aov, ics_render_stats *stats) {
  char msg[CLI_MSG_MAX] = "";
  ics_status st = ics_renderer_render_aovs(rd, plan, r->aovs, img, r->aovs ? aov : NULL, stats,
                                           msg, sizeof msg);
  /* quiet by default: the note is for a user who may care (a terminal, --verbose, a backend
   * option) */
  if (*ics_renderer_note(rd) && (r->verbose || backend_options_any(&r->bo) || isatty(2)))
    fprintf(stderr, "icshadow render: note: %s\n", ics_renderer_note(rd));
  if (sp->p.on) cli_progress_done(&sp->p);
  return st == ICS_OK ? 0 : cli_status_error(CMD, st, "%s", msg);
}

/* --compare or --reference; 0, or the exit status after the message */
static int compare_image(const render_args *r, const ics_plan *plan, const ics_image *img,
                         render_comparison *cmp) {
  if (r->compare) return render_compare_file(CMD, r->compare, img, cmp);
  if (!r->given_ref) return 0;
  slab_progress sp = {.t_last = cli_now_s()};
  cli_progress_init(&sp.p, "reference", r->force_progress);
  int rc = render_compare_mc(CMD, plan, r->ref_spp, r->a.threads, r->mc_mesh,
                             sp.p.on ? on_sample : NULL, &sp, img, cmp);
  if (sp.p.on) cli_progress_done(&sp.p);
  return rc;
}

/* the summary, printed last and kept in the EXR (malloc'ed; NULL when out of memory) */
static char *summary_text(const render_args *r, const ics_plan *plan,
                          const ics_render_settings *rs, const ics_render_stats *stats,
                          double t_plan, const ics_exr_channels *aov,
                          const render_comparison *cmp) {
  char *summary = NULL;
  size_t summary_len = 0;
  FILE *sf = open_memstream(&summary, &summary_len);
  if (!sf) return NULL;
  fprintf(sf, "{\"scene\": ");
  ics_json_write_string(sf, r->a.scene ? r->a.scene : "default");
  fprintf(sf, ", ");
  ics_render_summary_write(sf, plan, rs, stats, 1e3 * t_plan);
  if (r->exr) fprintf(sf, ", \"exr\": "), ics_json_write_string(sf, r->exr);
  if (r->png) fprintf(sf, ", \"png\": "), ics_json_write_string(sf, r->png);
  if (r->diff_png) fprintf(sf, ", \"diff_png\": "), ics_json_write_string(sf, r->diff_png);
  if (aov) {
    fprintf(sf, ", \"aovs\": [");
    for (int c = 0; c < aov->count; c++)
      fprintf(sf, "%s", c ? ", " : ""), ics_json_write_string(sf, aov->names[c]);
    fprintf(sf, "]");
  }
  if (r->compare || r->given_ref) fprintf(sf, ", \"compare\": "), render_comparison_json(sf, cmp);
  fprintf(sf, "}");
  if (fclose(sf) != 0 || !summary) {
    free(summary);
    return NULL;
  }
  return summary;
}

/* status st of writing `path` as the exit status after the message: 1 for a write that failed,
 * 2 for what the input made impossible */
static int write_failure(ics_status st, const char *path, cli_output *o, const char *msg) {
  return st == ICS_ERR_IO || st == ICS_ERR_NOMEM
             ? cli_failure(CMD, "cannot write %s: %s", path, cli_output_reason(o, msg))
             : cli_error(CMD, "cannot write %s: %s", path, cli_output_reason(o, msg));
}

/* the files and the summary, all or none: each file complete before any is renamed into place,
 * the summary first (when one cannot be completed, a full disk or a closed stdout, no file is
 * replaced); 0 or the exit status */
static int write_outputs(const render_args *r, const ics_image *img, const ics_exr_channels *aov,
                         const render_comparison *cmp, const char *summary) {
  char msg[CLI_MSG_MAX] = "";
  cli_output out[3] = {{0}}; /* -o, --png, --diff-png */
  cli_output *all[4];
  int n = 0, rc = 0;
  if (r->exr) {
    if (cli_output_open(&out[0], CMD, r->exr) != 0) return 1;
    all[1 + n++] = &out[0];
    ics_status st = write_exr(out[0].write_path, img, aov, summary, msg, sizeof msg);
    if (st != ICS_OK) rc = write_failure(st, r->exr, &out[0], msg);
  }
  if (!rc && r->png) {
    if (cli_output_open(&out[1], CMD, r->png) != 0) rc = 1;
    else {
      all[1 + n++] = &out[1];
      ics_status st = ics_output_png(img, out[1].write_path, msg, sizeof msg);
      if (st != ICS_OK) rc = write_failure(st, r->png, &out[1], msg);
    }
  }
  if (!rc && r->diff_png) {
    if (cli_output_open(&out[2], CMD, r->diff_png) != 0) rc = 1;
    else {
      all[1 + n++] = &out[2];
      ics_image *dimg = render_difference_image(img, cmp->ref, 4);
      ics_status st = dimg ? ics_output_png(dimg, out[2].write_path, msg, sizeof msg) : ICS_ERR_NOMEM;
      if (!dimg) snprintf(msg, sizeof msg, "out of memory");
      ics_image_destroy(dimg);
      if (st != ICS_OK) rc = cli_failure(CMD, "cannot write %s: %s", r->diff_png, cli_output_reason(&out[2], msg));
    }
  }
  if (rc) {
    for (int i = 0; i < n; i++) cli_output_abort(all[1 + i]);
    return rc;
  }
  cli_output os;
  cli_output_open(&os, CMD, "-");
  fprintf(os.fp, "%s\n", summary);
  all[0] = &os;
  return cli_outputs_commit(all, 1 + n) != 0 ? 1 : 0;
}
#endif

int cmd_render(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
#ifndef ICS_HAVE_RENDER
  (void)argc, (void)argv;
  return cli_no_renderer(CMD);
#else
  render_args r;
  int listed, rc = parse_args(&r, argc, argv, &listed);
  if (rc || listed) return rc;
  const cli_path ins[] = {{"scene file", r.a.scene}, {"--compare reference", r.compare}};
  const cli_path outs[] = {{"-o", r.exr}, {"--png", r.png}, {"--diff-png", r.diff_png}};
  if ((rc = cli_check_outputs(CMD, ins, 2, outs, 3))) return rc;
  ics_scene *s;
  ics_render_settings rs;
  ics_plan_opts po;
  if ((rc = scene_args_load(CMD, &r.a, &s, &rs, &po))) return rc;
  if ((rc = scene_args_check_outputs(CMD, s, ins + 1, 1, outs, 3))) {
    ics_scene_destroy(s);
    return rc;
  }
  /* the renderer first: the plan resolves render.model auto for its backend */
  slab_progress sp = {0};
  ics_renderer *rd;
  if ((rc = open_renderer(&r, &sp, &rd))) {
    ics_scene_destroy(s);
    return rc;
  }
  po.renderer = rd;
  char msg[CLI_MSG_MAX] = "";
  double t0 = cli_now_s();
  ics_plan *plan;
  ics_status st = ics_plan_create(&plan, s, &po, msg, sizeof msg);
  if (st != ICS_OK) {
    ics_renderer_destroy(rd);
    ics_scene_destroy(s);
    return cli_status_error(CMD, st, "%s", msg);
  }
  double t_plan = cli_now_s() - t0;
  ics_image *img = NULL;
  ics_exr_channels *aov = NULL;
  ics_render_stats stats;
  render_comparison cmp = {0};
  char *summary = NULL;
  rc = render_image(&r, rd, &sp, plan, &img, &aov, &stats);
  ics_renderer_destroy(rd);
  if (!rc && !(rc = compare_image(&r, plan, img, &cmp))) {
    summary = summary_text(&r, plan, &rs, &stats, t_plan, aov, &cmp);
    rc = summary ? write_outputs(&r, img, aov, &cmp, summary) : cli_failure(CMD, "out of memory");
  }
  free(summary);
  ics_image_destroy(img);
  ics_exr_channels_destroy(aov);
  render_comparison_release(&cmp);
  ics_plan_destroy(plan);
  ics_scene_destroy(s);
  return rc;
#endif
}
