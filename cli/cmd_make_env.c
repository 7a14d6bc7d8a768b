/* cmd_make_env.c — `icshadow make-env [--lights FILE|SPEC] [--sky R,G,B] --size WxH
 * [--supersample N] [--half] -o ENV.exr`: a synthetic latitude-longitude environment map
 * (OpenEXR) drawn from Gaussian lights on the virtual light plane (ics_envmap_render), for
 * tests and demos. The output is written atomically (temporary name, then rename). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"
#include "lightsfile.h"

/* the map (3 floats a pixel) and ics_exr_write's planar copy (3 more): 24 bytes a pixel, at most
 * 2 GiB together; the readers' bound too, so every map make-env writes can be read back */
#define MAX_PIXELS ICS_EXR_MAX_PIXELS
/* light evaluations (lights x pixels x supersamples): about a minute on a 2-core VM at ~4 ns
 * each (64 lights at 1024x512, 16 samples a pixel: 5.4e8 in 2.4 s) */
#define WORK_BUDGET 1.5e10

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow make-env [--lights FILE|SPEC] [--sky R,G,B] --size WxH "
          "[--supersample N] [--half] [--progress] -o ENV.exr\n"
          "Draws Gaussian lights on the virtual light plane into a latitude-longitude OpenEXR\n"
          "environment map (docs/architecture.md: the image centre is +z, behind the viewer).\n"
          "Light k has radiance weight*color*g(x; mean, cov)*(1 + |x|^2)^(3/2) at the direction\n"
          "of plane point x, so its luminance power is weight for colours of luminance 1.\n"
          "Lights narrower than a quarter pixel are drawn into one pixel (a sun).\n\n"
          "options:\n"
          "  --lights FILE|SPEC  a lights file (JSON, docs/lights_format.md) or a SPEC: lights\n"
          "                      separated by ':', each mx,my,varx,vary[,angle_deg[,weight[,r,g,b]]]\n"
          "  --sky R,G,B         constant radiance added everywhere (default 0,0,0)\n"
          "  --size WxH          map size, W, H in 4..16384 and W*H <= %ld pixels (the float\n"
          "                      image and the writer's copy take 24 bytes a pixel: 2 GiB)\n"
          "  --supersample N     N x N samples per pixel, 1..16 (default 4)\n"
          "  --half              write half floats (default float)\n"
          "  --progress          show progress on stderr even when it is not a terminal (it is\n"
          "                      shown on a terminal for maps of 4M pixels and more)\n"
          "  -o ENV.exr          output file (required)\n"
          "Work budget: maps whose work (lights x pixels x N^2) exceeds %.1e light evaluations\n"
          "(about a minute here) are refused with exit 2 before drawing.\n"
          "Exit status: 0 ok, 1 cannot write, 2 bad input.\n", MAX_PIXELS, WORK_BUDGET);
}

static const char CMD[] = "make-env";

/* progress of the rows: cli_progress, at most every 0.5 s (and the last row) */
typedef struct row_progress {
  cli_progress p;
  double t_last;
} row_progress;

static void on_rows(void *ctx, int done, int rows) {
  row_progress *rp = ctx;
  double t = cli_now_s();
  if (done < rows && t - rp->t_last < 0.5) return;
  rp->t_last = t;
  cli_progress_say(&rp->p, "row %d/%d", done, rows);
}

/* --sky R,G,B: finite and >= 0 */
static int parse_sky(const char *cmd, const char *opt, const char *v, void *dest) {
  double *sky = dest;
  char buf[3][64];
  if (sscanf(v, "%63[^,],%63[^,],%63s", buf[0], buf[1], buf[2]) != 3 ||
      cli_parse_double(buf[0], &sky[0]) || cli_parse_double(buf[1], &sky[1]) ||
      cli_parse_double(buf[2], &sky[2]) || !(sky[0] >= 0 && sky[1] >= 0 && sky[2] >= 0) ||
      sky[0] + sky[1] + sky[2] > 1e30)
    return cli_error(cmd, "%s: expected R,G,B finite and >= 0, got '%s'", opt, v);
  return 0;
}

/* --size WxH: W, H in 4..16384 and W * H <= MAX_PIXELS */
static int parse_size(const char *cmd, const char *opt, const char *v, void *dest) {
  int *wh = dest;
  char bw[32], bh[32];
  if (sscanf(v, "%31[0-9]x%31[0-9]", bw, bh) != 2 || cli_parse_int(bw, 4, 16384, &wh[0]) ||
      cli_parse_int(bh, 4, 16384, &wh[1]) || strlen(v) != strlen(bw) + strlen(bh) + 1)
    return cli_error(cmd, "%s: expected WxH with W, H in 4..16384, got '%s'", opt, v);
  long pixels = (long)wh[0] * wh[1];
  if (pixels > MAX_PIXELS)
    return cli_error(cmd, "%s %s: %ld pixels would need %.3g GiB (24 bytes a pixel); at most %ld "
                     "pixels (2 GiB), e.g. 8192x4096", opt, v, pixels,
                     (double)pixels * 24 / (1UL << 30), MAX_PIXELS);
  return 0;
}

int cmd_make_env(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  const char *lights_arg = NULL, *outp = NULL;
  double sky[3] = {0, 0, 0};
  int have_sky = 0, size[2] = {0, 0}, ss = 4, half = 0, force_progress = 0;
  const cli_option opts[] = {
      {"--lights", .kind = CLI_STRING, .dest = &lights_arg},
      {"--sky", .kind = CLI_CALL, .dest = sky, .parse = parse_sky, .given = &have_sky},
      {"--size", .kind = CLI_CALL, .dest = size, .parse = parse_size},
      {"--supersample", .kind = CLI_INT, .dest = &ss, .lo = 1, .hi = 16},
      {"--half", .kind = CLI_FLAG, .dest = &half},
      {"--progress", .kind = CLI_FLAG, .dest = &force_progress},
      {"-o", .kind = CLI_FILE, .dest = &outp},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  const int w = size[0], h = size[1];
  if (!w) return cli_error(CMD, "--size is required");
  if (!outp || !strcmp(outp, "-"))
    return cli_error(CMD, "-o FILE is required (an EXR file, not stdout)");
  if (!lights_arg && !have_sky)
    return cli_error(CMD, "nothing to draw: give --lights and/or --sky");
  if (!ics_exr_available())
    return cli_failure(CMD, "cannot write OpenEXR: OpenEXR was not found when icshadow was built");
  /* --lights is a file when one of that name exists (lights_load) */
  const cli_path in = {"--lights file", lights_arg}, o = {"-o", outp};
  rc = cli_check_outputs(CMD, &in, 1, &o, 1);
  if (rc) return rc;
  ics_light *lights = NULL;
  int n = 0;
  char err[CLI_MSG_MAX];
  if (lights_arg && lights_load(lights_arg, &lights, &n, err, sizeof err) != 0)
    return cli_error(CMD, "--lights: %s", err);
  double work = (double)n * w * h * ss * ss;
  if (work > WORK_BUDGET) {
    free(lights);
    return cli_error(CMD, "%d lights x %dx%d pixels x %d samples is %.3g light evaluations, above "
                     "the budget of %.1e (about a minute here): give fewer lights, a smaller "
                     "--size or a lower --supersample", n, w, h, ss * ss, work, WORK_BUDGET);
  }
  ics_image *env = NULL;
  row_progress rp = {.t_last = cli_now_s()};
  cli_progress_init(&rp.p, "make-env", force_progress);
  int show = force_progress || (rp.p.tty && (long)w * h * ss * ss >= (4L << 20));
  ics_status st = ics_image_create(&env, w, h, 3);
  if (st == ICS_OK)
    st = ics_envmap_render_progress(env, sky, lights, n, ss, show ? on_rows : NULL, &rp);
  if (show) cli_progress_done(&rp.p);
  if (st == ICS_ERR_RANGE) {
    /* which light overflows float on its own (drawn alone into a map of the same size) */
    int bad = -1;
    for (int k = 0; k < n && bad < 0; k++)
      if (ics_envmap_render(env, NULL, &lights[k], 1, ss) == ICS_ERR_RANGE) bad = k;
    if (bad >= 0)
      cli_error(CMD, "light %d (weight %g, colour %g,%g,%g) is too bright to draw: its radiance "
                "overflows float at %dx%d", bad + 1, lights[bad].weight, lights[bad].color[0],
                lights[bad].color[1], lights[bad].color[2], w, h);
    else
      cli_error(CMD, "the lights and sky together are too bright to draw: the radiance overflows "
                "float at %dx%d", w, h);
  } else if (st != ICS_OK) {
    cli_error(CMD, "cannot draw the map: %s", ics_status_str(st));
  }
  free(lights);
  if (st != ICS_OK) {
    ics_image_destroy(env);
    return st == ICS_ERR_NOMEM ? 1 : 2;
  }
  cli_output out;
  if (cli_output_open(&out, CMD, outp) != 0) {
    ics_image_destroy(env);
    return 1;
  }
  st = ics_exr_write(out.write_path, env, half ? ICS_EXR_HALF : ICS_EXR_FLOAT, err, sizeof err);
  ics_image_destroy(env);
  if (st != ICS_OK) {
    cli_error(CMD, "cannot write %s: %s", outp, cli_output_reason(&out, err));
    cli_output_abort(&out);
    return st == ICS_ERR_INVALID_ARG ? 2 : 1;
  }
  return cli_output_commit(&out) ? 1 : 0;
}
