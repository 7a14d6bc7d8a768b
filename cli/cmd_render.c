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
          "  --backends          list the backends built into this binary and exit\n");
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
  }
  return 0;
}
#endif

int cmd_render(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
#ifndef ICS_HAVE_RENDER
  (void)argc, (void)argv;
  return cli_failure(CMD, "the renderer was not built (it needs jansson: install libjansson-dev "
                     "and rebuild)");
#else
  scene_args a;
  memset(&a, 0, sizeof a);
  const char *exr = NULL, *png = NULL, *backend = NULL, *aov_list = NULL, *compare = NULL,
             *diff_png = NULL, *mc_mesh = NULL;
  int force_progress = 0, verbose = 0, backends = 0, spp = 0, ref_spp = 0, given_ref = 0;
  double time_s = 0, noise = 0;
  int given_spp = 0, given_time = 0, given_noise = 0;
  const cli_option mine[] = {
      {"-o", .kind = CLI_FILE, .dest = &exr},
      {"--png", .kind = CLI_FILE, .dest = &png},
      {"--aov", .kind = CLI_STRING, .dest = &aov_list},
      {"--backend", .kind = CLI_STRING, .dest = &backend},
      {"--backends", .kind = CLI_FLAG, .dest = &backends},
      {"--progress", .kind = CLI_FLAG, .dest = &force_progress},
      {"--verbose", .kind = CLI_FLAG, .dest = &verbose},
      {"--spp", .kind = CLI_INT, .dest = &spp, .lo = 1, .hi = 1 << 24, .given = &given_spp},
      {"--time", .kind = CLI_FINITE, .dest = &time_s, .given = &given_time},
      {"--noise", .kind = CLI_FINITE, .dest = &noise, .given = &given_noise},
      {"--compare", .kind = CLI_FILE, .dest = &compare},
      {"--diff-png", .kind = CLI_FILE, .dest = &diff_png},
      {"--reference", .kind = CLI_INT, .dest = &ref_spp, .lo = 1, .hi = 1 << 24, .given = &given_ref},
      {"--mc-mesh", .kind = CLI_STRING, .dest = &mc_mesh},
  };
  cli_option opts[SCENE_ARGS_NOPTS + CLI_NOPTS(mine) + BACKEND_OPTIONS_MAX];
  scene_args_options(&a, opts);
  memcpy(opts + SCENE_ARGS_NOPTS, mine, sizeof mine);
  backend_options bo;
  int nopts = SCENE_ARGS_NOPTS + CLI_NOPTS(mine);
  nopts += backend_options_table(&bo, opts + nopts);
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, nopts);
  if (rc) return rc;
  if (backends) return list_backends();
  if (!exr && !png && !diff_png && !compare && !given_ref)
    return cli_error(CMD, "nothing to write: give -o OUT.exr and/or --png OUT.png (or only "
                     "measure: --compare REF.exr or --reference N)");
  size_t ne = exr ? strlen(exr) : 0;
  if (ne >= 4 && !strcmp(exr + ne - 4, ".png"))
    return cli_error(CMD, "-o %s: -o writes OpenEXR; give the PNG preview with --png", exr);
  if ((exr && !strcmp(exr, "-")) || (png && !strcmp(png, "-")) || (diff_png && !strcmp(diff_png, "-")))
    return cli_error(CMD, "images are written to files, not to stdout (the summary goes there)");
  int mc = backend && !strcmp(backend, "mc");
  if ((given_spp || given_time || given_noise) && !mc)
    return cli_error(CMD, "%s: only the Monte-Carlo reference takes a stop (give --backend mc)",
                     given_spp ? "--spp" : given_time ? "--time" : "--noise");
  if (given_time && !(time_s > 0)) return cli_error(CMD, "--time: must be > 0 seconds");
  if (given_noise && !(noise > 0)) return cli_error(CMD, "--noise: must be > 0");
  if (mc_mesh && strcmp(mc_mesh, "auto") && strcmp(mc_mesh, "embree") && strcmp(mc_mesh, "bvh"))
    return cli_error(CMD, "--mc-mesh %s: expected auto, embree or bvh", mc_mesh);
  if (mc_mesh && !mc && !given_ref)
    return cli_error(CMD, "--mc-mesh: only the Monte-Carlo reference takes it (give --backend mc "
                     "or --reference N)");
  if (compare && given_ref) return cli_error(CMD, "give --compare or --reference, not both");
  if (given_ref && mc)
    return cli_error(CMD, "--reference: this render is the Monte-Carlo reference itself (same seed, "
                     "same samples); compare two mc renders with --compare REF.exr and another --seed");
  if (diff_png && !compare && !given_ref)
    return cli_error(CMD, "--diff-png: give --compare REF.exr or --reference N");
  if (diff_png && !ics_output_png_available())
    return cli_failure(CMD, "cannot write PNG: libpng was not found when the renderer was built");
  if (compare && !ics_exr_available())
    return cli_failure(CMD, "--compare: OpenEXR was not found when icshadow was built");
  unsigned aovs = 0;
  if (aov_list && (rc = parse_aovs(aov_list, mc ? ICS_AOV_STDERR : 0, &aovs))) return rc;
  if (aovs && !exr) return cli_error(CMD, "--aov: AOVs go into the EXR; give -o OUT.exr");
  if (exr && !ics_exr_available())
    return cli_failure(CMD, "cannot write OpenEXR: OpenEXR was not found when icshadow was built");
  if (png && !ics_output_png_available())
    return cli_failure(CMD, "cannot write PNG: libpng was not found when the renderer was built");
  if (backend && strcmp(backend, "auto")) {
    char why[256];
    if (!ics_backend_available(backend, why, sizeof why)) return cli_error(CMD, "--backend: %s", why);
  }
  const cli_path ins[] = {{"scene file", a.scene}, {"--compare reference", compare}};
  const cli_path outs[] = {{"-o", exr}, {"--png", png}, {"--diff-png", diff_png}};
  if ((rc = cli_check_outputs(CMD, ins, 2, outs, 3))) return rc;
  ics_scene *s;
  ics_render_settings rs;
  ics_plan_opts po;
  if ((rc = scene_args_load(CMD, &a, &s, &rs, &po))) return rc;
  if ((rc = scene_args_check_outputs(CMD, s, ins + 1, 1, outs, 3))) {
    ics_scene_destroy(s);
    return rc;
  }
  char msg[CLI_MSG_MAX] = "";
  double t0 = cli_now_s();
  ics_plan *plan;
  ics_status st = ics_plan_create(&plan, s, &po, msg, sizeof msg);
  if (st != ICS_OK) {
    ics_scene_destroy(s);
    return cli_status_error(CMD, st, "%s", msg);
  }
  double t_plan = cli_now_s() - t0;
  slab_progress sp = {.t_last = cli_now_s()};
  cli_progress_init(&sp.p, "render", force_progress);
  ics_render_opts ro = {.backend = backend, .threads = a.threads, .spp = spp, .time_s = time_s,
                        .noise = noise, .mc_mesh = mc_mesh,
                        .options = backend_options_list(&bo)};
  if (sp.p.on) ro.progress = mc ? on_sample : on_slab, ro.progress_ctx = &sp;
  ics_renderer *r;
  ics_image *img = NULL;
  ics_exr_channels *aov = NULL;
  ics_render_stats stats;
  render_comparison cmp = {0};
  st = ics_renderer_create(&r, &ro, msg, sizeof msg);
  if (st == ICS_OK) {
    backend_options_warn(&bo, CMD, ics_renderer_backend(r), ics_renderer_note(r));
    st = ics_renderer_render_aovs(r, plan, aovs, &img, aovs ? &aov : NULL, &stats, msg, sizeof msg);
    /* quiet by default: the note is for a user who may care (a terminal, --verbose, a backend
     * option) */
    if (*ics_renderer_note(r) && (verbose || backend_options_any(&bo) || isatty(2)))
      fprintf(stderr, "icshadow render: note: %s\n", ics_renderer_note(r));
    ics_renderer_destroy(r);
  }
  if (sp.p.on) cli_progress_done(&sp.p);
  rc = 0;
  if (st != ICS_OK) {
    rc = cli_status_error(CMD, st, "%s", msg);
    goto done;
  }
  int have_cmp = compare || given_ref;
  if (compare && (rc = render_compare_file(CMD, compare, img, &cmp))) goto done;
  if (given_ref) {
    cli_progress_init(&sp.p, "reference", force_progress);
    rc = render_compare_mc(CMD, plan, ref_spp, a.threads, mc_mesh, sp.p.on ? on_sample : NULL, &sp,
                           img, &cmp);
    if (sp.p.on) cli_progress_done(&sp.p);
    if (rc) goto done;
  }
  /* the summary, printed last and kept in the EXR */
  char *summary = NULL;
  size_t summary_len = 0;
  FILE *sf = open_memstream(&summary, &summary_len);
  if (!sf) {
    rc = cli_failure(CMD, "out of memory");
    goto done;
  }
  {
    fprintf(sf, "{\"scene\": ");
    cli_json_string(sf, a.scene ? a.scene : "default");
    fprintf(sf, ", ");
    ics_render_summary_write(sf, plan, &rs, &stats, 1e3 * t_plan);
    if (exr) fprintf(sf, ", \"exr\": "), cli_json_string(sf, exr);
    if (png) fprintf(sf, ", \"png\": "), cli_json_string(sf, png);
    if (diff_png) fprintf(sf, ", \"diff_png\": "), cli_json_string(sf, diff_png);
    if (aov) {
      fprintf(sf, ", \"aovs\": [");
      for (int c = 0; c < aov->count; c++)
        fprintf(sf, "%s", c ? ", " : ""), cli_json_string(sf, aov->names[c]);
      fprintf(sf, "]");
    }
    if (have_cmp) fprintf(sf, ", \"compare\": "), render_comparison_json(sf, &cmp);
    fprintf(sf, "}");
  }
  if (fclose(sf) != 0 || !summary) {
    free(summary);
    rc = cli_failure(CMD, "out of memory");
    goto done;
  }
  /* both files complete before either is renamed into place */
  cli_output oe = {0}, op = {0}, od = {0};
  int have_e = 0, have_p = 0, have_d = 0;
  if (exr) {
    if (cli_output_open(&oe, CMD, exr) != 0) {
      rc = 1;
      goto done_summary;
    }
    have_e = 1;
    st = write_exr(oe.write_path, img, aov, summary, msg, sizeof msg);
    if (st != ICS_OK) {
      rc = st == ICS_ERR_IO || st == ICS_ERR_NOMEM ? cli_failure(CMD, "cannot write %s: %s", exr, cli_output_reason(&oe, msg))
                                                   : cli_error(CMD, "cannot write %s: %s", exr, cli_output_reason(&oe, msg));
      goto abort;
    }
  }
  if (png) {
    if (cli_output_open(&op, CMD, png) != 0) {
      rc = 1;
      goto abort;
    }
    have_p = 1;
    st = ics_output_png(img, op.write_path, msg, sizeof msg);
    if (st != ICS_OK) {
      rc = st == ICS_ERR_IO || st == ICS_ERR_NOMEM ? cli_failure(CMD, "cannot write %s: %s", png, cli_output_reason(&op, msg))
                                                   : cli_error(CMD, "cannot write %s: %s", png, cli_output_reason(&op, msg));
      goto abort;
    }
  }
  if (diff_png) {
    if (cli_output_open(&od, CMD, diff_png) != 0) {
      rc = 1;
      goto abort;
    }
    have_d = 1;
    ics_image *dimg = render_difference_image(img, cmp.ref, 4);
    st = dimg ? ics_output_png(dimg, od.write_path, msg, sizeof msg) : ICS_ERR_NOMEM;
    if (!dimg) snprintf(msg, sizeof msg, "out of memory");
    ics_image_destroy(dimg);
    if (st != ICS_OK) {
      rc = cli_failure(CMD, "cannot write %s: %s", diff_png, cli_output_reason(&od, msg));
      goto abort;
    }
  }
  {
    /* the summary and every file together, the summary first: when one cannot be completed
     * (a full disk, a closed stdout), no file is replaced */
    cli_output os;
    cli_output_open(&os, CMD, "-");
    fprintf(os.fp, "%s\n", summary);
    cli_output *all[4] = {&os};
    int n = 1;
    if (have_e) all[n++] = &oe;
    if (have_p) all[n++] = &op;
    if (have_d) all[n++] = &od;
    if (cli_outputs_commit(all, n) != 0) rc = 1;
  }
  goto done_summary;
abort:
  if (have_e) cli_output_abort(&oe);
  if (have_p) cli_output_abort(&op);
  if (have_d) cli_output_abort(&od);
done_summary:
  free(summary);
  goto done;
done:
  ics_image_destroy(img);
  ics_exr_channels_destroy(aov);
  render_comparison_release(&cmp);
  ics_plan_destroy(plan);
  ics_scene_destroy(s);
  return rc;
#endif
}
