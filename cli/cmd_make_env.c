/* cmd_make_env.c — `icshadow make-env [--lights FILE|SPEC] [--sky R,G,B] --size WxH
 * [--supersample N] [--half] -o ENV.exr`: a synthetic latitude-longitude environment map
 * (OpenEXR) drawn from Gaussian lights on the virtual light plane (ics_envmap_render), for
 * tests and demos. The output is written atomically (temporary name, then rename). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"
#include "icshadow.h"
#include "lightsfile.h"

/* the map (3 floats a pixel) and ics_exr_write's planar copy (3 more): 24 bytes a pixel, at most
 * 2 GiB together */
#define MAX_PIXELS ((long)((1UL << 31) / 24))

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow make-env [--lights FILE|SPEC] [--sky R,G,B] --size WxH "
          "[--supersample N] [--half] [--progress] -o ENV.exr\n"
          "Draws Gaussian lights on the virtual light plane into a latitude-longitude OpenEXR\n"
          "environment map (DESIGN.md frames: the image centre is +z, behind the viewer).\n"
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
          "Exit status: 0 ok, 1 cannot write, 2 bad input.\n", MAX_PIXELS);
}

typedef struct prog {
  int tty;
  double t_last;
} prog;

static void on_rows(void *ctx, int done, int rows) {
  prog *p = ctx;
  double t = cli_now_s();
  if (done < rows && t - p->t_last < 0.5) return;
  p->t_last = t;
  if (p->tty)
    fprintf(stderr, "\rmake-env: row %d/%d   %s", done, rows, done == rows ? "\n" : "");
  else
    fprintf(stderr, "make-env: row %d/%d\n", done, rows);
}

int cmd_make_env(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  const char *lights_arg = NULL, *outp = NULL;
  double sky[3] = {0, 0, 0};
  int have_sky = 0, w = 0, h = 0, ss = 4, half = 0, force_progress = 0;
  for (int a = 1; a < argc; a++) {
    const char *o = argv[a];
    int needs = !strcmp(o, "--lights") || !strcmp(o, "--sky") || !strcmp(o, "--size") ||
                !strcmp(o, "--supersample") || !strcmp(o, "-o");
    if (needs && a + 1 >= argc) {
      fprintf(stderr, "icshadow make-env: %s: missing value\n", o);
      return 2;
    }
    if (!strcmp(o, "--lights")) {
      lights_arg = argv[++a];
    } else if (!strcmp(o, "--sky")) {
      const char *v = argv[++a];
      char buf[3][64];
      if (sscanf(v, "%63[^,],%63[^,],%63s", buf[0], buf[1], buf[2]) != 3 ||
          cli_parse_double(buf[0], &sky[0]) || cli_parse_double(buf[1], &sky[1]) ||
          cli_parse_double(buf[2], &sky[2]) || !(sky[0] >= 0 && sky[1] >= 0 && sky[2] >= 0) ||
          sky[0] + sky[1] + sky[2] > 1e30) {
        fprintf(stderr, "icshadow make-env: --sky: expected R,G,B finite and >= 0, got '%s'\n", v);
        return 2;
      }
      have_sky = 1;
    } else if (!strcmp(o, "--size")) {
      const char *v = argv[++a];
      char bw[32], bh[32];
      if (sscanf(v, "%31[0-9]x%31[0-9]", bw, bh) != 2 || cli_parse_int(bw, 4, 16384, &w) ||
          cli_parse_int(bh, 4, 16384, &h) || strlen(v) != strlen(bw) + strlen(bh) + 1) {
        fprintf(stderr, "icshadow make-env: --size: expected WxH with W, H in 4..16384, got '%s'\n",
                v);
        return 2;
      }
      if ((long)w * h > MAX_PIXELS) {
        fprintf(stderr, "icshadow make-env: --size %s: %ld pixels would need %.3g GiB (24 bytes "
                "a pixel); at most %ld pixels (2 GiB), e.g. 8192x4096\n", v, (long)w * h,
                (double)w * h * 24 / (1UL << 30), MAX_PIXELS);
        return 2;
      }
    } else if (!strcmp(o, "--supersample")) {
      if (cli_parse_int(argv[++a], 1, 16, &ss)) {
        fprintf(stderr, "icshadow make-env: --supersample: expected an integer in 1..16\n");
        return 2;
      }
    } else if (!strcmp(o, "--half")) {
      half = 1;
    } else if (!strcmp(o, "--progress")) {
      force_progress = 1;
    } else if (!strcmp(o, "-o")) {
      outp = argv[++a];
    } else {
      fprintf(stderr, "icshadow make-env: unknown option '%s' (see --help)\n", o);
      return 2;
    }
  }
  if (!w) {
    fprintf(stderr, "icshadow make-env: --size is required\n");
    return 2;
  }
  if (!outp || !strcmp(outp, "-")) {
    fprintf(stderr, "icshadow make-env: -o FILE is required (an EXR file, not stdout)\n");
    return 2;
  }
  if (!lights_arg && !have_sky) {
    fprintf(stderr, "icshadow make-env: nothing to draw: give --lights and/or --sky\n");
    return 2;
  }
  if (!ics_exr_available()) {
    fprintf(stderr, "icshadow make-env: cannot write OpenEXR: OpenEXR was not found when "
            "icshadow was built\n");
    return 1;
  }
  ics_light *lights = NULL;
  int n = 0;
  char err[CLI_MSG_MAX];
  if (lights_arg) {
    int rc = lights_load(lights_arg, &lights, &n, err, sizeof err);
    if (rc) {
      fprintf(stderr, "icshadow make-env: --lights: %s\n", err);
      return 2;
    }
  }
  ics_image env;
  prog pg = {isatty(2), cli_now_s()};
  int show = force_progress || (pg.tty && (long)w * h * ss * ss >= (4L << 20));
  ics_status st = ics_image_init(&env, w, h, 3);
  if (st == ICS_OK)
    st = ics_envmap_render_progress(&env, sky, lights, n, ss, show ? on_rows : NULL, &pg);
  if (st == ICS_ERR_RANGE) {
    /* which light overflows float on its own (drawn alone into a map of the same size) */
    int bad = -1;
    for (int k = 0; k < n && bad < 0; k++)
      if (ics_envmap_render(&env, NULL, &lights[k], 1, ss) == ICS_ERR_RANGE) bad = k;
    if (bad >= 0)
      fprintf(stderr, "icshadow make-env: light %d (weight %g, colour %g,%g,%g) is too bright to "
              "draw: its radiance overflows float at %dx%d\n", bad + 1, lights[bad].weight,
              lights[bad].color[0], lights[bad].color[1], lights[bad].color[2], w, h);
    else
      fprintf(stderr, "icshadow make-env: the lights and sky together are too bright to draw: "
              "the radiance overflows float at %dx%d\n", w, h);
  } else if (st != ICS_OK) {
    fprintf(stderr, "icshadow make-env: cannot draw the map: %s\n", ics_status_str(st));
  }
  free(lights);
  if (st != ICS_OK) {
    ics_image_free(&env);
    return st == ICS_ERR_NOMEM ? 1 : 2;
  }
  cli_output out;
  if (cli_output_open(&out, "make-env", outp) != 0) {
    ics_image_free(&env);
    return 1;
  }
  st = ics_exr_write(out.write_path, &env, half ? ICS_EXR_HALF : ICS_EXR_FLOAT, err, sizeof err);
  ics_image_free(&env);
  if (st != ICS_OK) {
    fprintf(stderr, "icshadow make-env: cannot write %s: %s\n", outp, err);
    cli_output_abort(&out);
    return st == ICS_ERR_INVALID_ARG ? 2 : 1;
  }
  return cli_output_commit(&out) ? 1 : 0;
}
