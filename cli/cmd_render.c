/* cmd_render.c — `icshadow render [SCENE] [-o out.exr] [--png out.png] [--backend B]
 * [--threads N] ...`: plans and renders a scene (the embedded default scene without SCENE) with
 * the slab renderer (libicshadow_render), writes a float RGBA OpenEXR (with AOVs when asked)
 * and/or an sRGB PNG preview (atomically, both or neither), and prints a JSON summary with the time per pass. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "scene_args.h"

static const char CMD[] = "render";

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow render [SCENE] [-o OUT.exr] [--png OUT.png] [--backend B] [options]\n"
          "Renders a scene with the slab renderer (Patel et al. 2013, Sec. 4; docs/renderer.md):\n"
          "the embedded default scene when no SCENE is given. Prints a JSON summary on stdout\n"
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
          "                      comma-separated, or all. 0 where a pixel has no surface\n"
          "  --backend B         auto (default) or a backend of `icshadow render --backends`\n"
          "  --backends          list the backends built into this binary and exit\n"
          "  --progress          show progress on stderr even when it is not a terminal\n"
          "Output files are written to a temporary name and renamed once both are complete.\n"
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

static void json_str(FILE *f, const char *s) {
  fputc('"', f);
  for (; *s; s++) {
    if (*s == '"' || *s == '\\') fputc('\\', f);
    if ((unsigned char)*s < 0x20)
      fprintf(f, "\\u%04x", (unsigned char)*s);
    else
      fputc(*s, f);
  }
  fputc('"', f);
}

/* --aov: "visibility", "depth", "all", comma-separated; 0 and *bits set, or -1 */
static int parse_aovs(const char *list, unsigned *bits) {
  *bits = 0;
  const char *p = list;
  for (;;) {
    size_t n = strcspn(p, ",");
    if (n == 10 && !strncmp(p, "visibility", n))
      *bits |= ICS_AOV_VISIBILITY;
    else if (n == 5 && !strncmp(p, "depth", n))
      *bits |= ICS_AOV_DEPTH;
    else if (n == 3 && !strncmp(p, "all", n))
      *bits |= ICS_AOV_VISIBILITY | ICS_AOV_DEPTH;
    else
      return cli_error(CMD, "--aov %s: '%.*s' is not an AOV (visibility, depth, all)", list, (int)n, p);
    if (!p[n]) return 0;
    p += n + 1;
  }
}

/* the image's R, G, B, A and the AOV channels as one float EXR */
static ics_status write_exr(const char *path, const ics_image *img, const ics_exr_channels *aov,
                            char *msg, size_t msg_size) {
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
  ics_exr_channels ch = {img->width, img->height, n, names, data};
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
  const char *exr = NULL, *png = NULL, *backend = NULL, *aov_list = NULL;
  int force_progress = 0, backends = 0;
  cli_option opts[SCENE_ARGS_NOPTS + 6];
  scene_args_options(&a, opts);
  const cli_option mine[] = {
      {"-o", .kind = CLI_FILE, .dest = &exr},
      {"--png", .kind = CLI_FILE, .dest = &png},
      {"--aov", .kind = CLI_STRING, .dest = &aov_list},
      {"--backend", .kind = CLI_STRING, .dest = &backend},
      {"--backends", .kind = CLI_FLAG, .dest = &backends},
      {"--progress", .kind = CLI_FLAG, .dest = &force_progress},
  };
  memcpy(opts + SCENE_ARGS_NOPTS, mine, sizeof mine);
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (backends) return list_backends();
  if (!exr && !png) return cli_error(CMD, "nothing to write: give -o OUT.exr and/or --png OUT.png");
  size_t ne = exr ? strlen(exr) : 0;
  if (ne >= 4 && !strcmp(exr + ne - 4, ".png"))
    return cli_error(CMD, "-o %s: -o writes OpenEXR; give the PNG preview with --png", exr);
  if ((exr && !strcmp(exr, "-")) || (png && !strcmp(png, "-")))
    return cli_error(CMD, "images are written to files, not to stdout (the summary goes there)");
  unsigned aovs = 0;
  if (aov_list && parse_aovs(aov_list, &aovs)) return 2;
  if (aovs && !exr) return cli_error(CMD, "--aov: AOVs go into the EXR; give -o OUT.exr");
  if (exr && !ics_exr_available())
    return cli_failure(CMD, "cannot write OpenEXR: OpenEXR was not found when icshadow was built");
  if (png && !ics_output_png_available())
    return cli_failure(CMD, "cannot write PNG: libpng was not found when the renderer was built");
  if (backend && strcmp(backend, "auto")) {
    char why[256];
    if (!ics_backend_available(backend, why, sizeof why)) return cli_error(CMD, "--backend: %s", why);
  }
  ics_scene *s;
  ics_render_settings rs;
  ics_plan_opts po;
  if ((rc = scene_args_load(CMD, &a, &s, &rs, &po))) return rc;
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
  ics_render_opts ro = {.backend = backend, .threads = a.threads};
  if (sp.p.on) ro.progress = on_slab, ro.progress_ctx = &sp;
  ics_renderer *r;
  ics_image *img = NULL;
  ics_exr_channels *aov = NULL;
  ics_render_stats stats;
  st = ics_renderer_create(&r, &ro, msg, sizeof msg);
  if (st == ICS_OK) {
    st = ics_renderer_render_aovs(r, plan, aovs, &img, aovs ? &aov : NULL, &stats, msg, sizeof msg);
    ics_renderer_destroy(r);
  }
  if (sp.p.on) cli_progress_done(&sp.p);
  rc = 0;
  if (st != ICS_OK) {
    rc = cli_status_error(CMD, st, "%s", msg);
    goto done;
  }
  /* both files complete before either is renamed into place */
  cli_output oe = {0}, op = {0};
  int have_e = 0, have_p = 0;
  if (exr) {
    if (cli_output_open(&oe, CMD, exr) != 0) {
      rc = 1;
      goto done;
    }
    have_e = 1;
    st = write_exr(oe.write_path, img, aov, msg, sizeof msg);
    if (st != ICS_OK) {
      rc = st == ICS_ERR_IO || st == ICS_ERR_NOMEM ? cli_failure(CMD, "cannot write %s: %s", exr, msg)
                                                   : cli_error(CMD, "cannot write %s: %s", exr, msg);
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
      rc = st == ICS_ERR_IO || st == ICS_ERR_NOMEM ? cli_failure(CMD, "cannot write %s: %s", png, msg)
                                                   : cli_error(CMD, "cannot write %s: %s", png, msg);
      goto abort;
    }
  }
  if ((have_e && cli_output_commit(&oe) != 0) || (have_p && cli_output_commit(&op) != 0)) {
    rc = 1;
    goto done;
  }
  {
    int W, H, bw, bh;
    ics_plan_sizes(plan, &W, &H, &bw, &bh);
    printf("{\"scene\": ");
    json_str(stdout, a.scene ? a.scene : "default");
    printf(", \"backend\": \"%s\", \"device\": ", stats.backend);
    json_str(stdout, stats.device);
    printf(", \"threads\": %d, \"resolution\": [%d, %d], \"light_buffer\": [%d, %d], \"slabs\": %d,"
           " \"kernel\": \"%s\", \"samples\": %d, \"seed\": %llu,"
           " \"ms_plan\": %.17g, \"ms_geometry\": %.17g, \"ms_render\": %.17g,"
           " \"ms_convolution\": %.17g, \"ms_shading\": %.17g, \"ms_detail\": %.17g,"
           " \"ns_per_px_slab\": %.17g, \"memory_bytes\": %zu",
           stats.threads, W, H, bw, bh, stats.slabs, ics_render_kernel_name(rs.kernel), rs.samples,
           (unsigned long long)rs.seed, 1e3 * t_plan, 1e3 * ics_plan_geometry_seconds(plan),
           stats.ms_total, stats.ms_convolution, stats.ms_shading, stats.ms_detail,
           stats.ns_per_px_slab, ics_plan_memory_bytes(plan));
    if (exr) printf(", \"exr\": "), json_str(stdout, exr);
    if (png) printf(", \"png\": "), json_str(stdout, png);
    if (aov) {
      printf(", \"aovs\": [");
      for (int c = 0; c < aov->count; c++) printf("%s", c ? ", " : ""), json_str(stdout, aov->names[c]);
      printf("]");
    }
    printf("}\n");
  }
  goto done;
abort:
  if (have_e) cli_output_abort(&oe);
  if (have_p) cli_output_abort(&op);
done:
  ics_image_destroy(img);
  ics_exr_channels_destroy(aov);
  ics_plan_destroy(plan);
  ics_scene_destroy(s);
  return rc;
#endif
}
