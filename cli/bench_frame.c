/* bench_frame.c — `icshadow bench frame [SCENE] [options]`: whole frames of a scene (the embedded
 * default scene without one), side by side in one run: the slab renderer on the cpu backend
 * skipping the work a frame does not need (work "skip"), the same with render.dense ("dense"),
 * and the Monte-Carlo reference at --spp samples per pixel ("mc"), their repetitions interleaved
 * after a warm-up round, so that all see the same machine; each work renders on one renderer kept
 * across its frames, as an application keeps it (the warm-up is reported apart: at the first
 * resolution it is the renderer's first frame, in fresh memory). A slab frame is its plan (with the
 * geometry pass) plus its render, as a user waits for it; an mc frame is its render (its plan,
 * the same geometry pass, is not what it spends its time on; docs/results.md times it so). CSV,
 * one row per resolution and work, with the processor's name and the vector path. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_stats.h"
#include "commands.h"

static const char CMD[] = "bench frame";

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow bench frame [SCENE] [--resolution WxH,...] [--threads T] [--reps R]\n"
          "       [--spp N] [--work W,...] [--model M] [--slab-spacing E] [--progress]\n"
          "       [--allow-outside-paths]\n"
          "Whole frames of a scene (none: the embedded default scene), side by side in one run,\n"
          "repetitions interleaved after a warm-up round, as CSV:\n"
          "  scene,width,height,work,model,threads,simd,cpu,ms_frame,ms_min,ms_max,ms_first,\n"
          "  ms_plan,ms_render,ms_convolution,ms_shading,ms_detail,active,vs_mc\n"
          "work: skip (the slab renderer on the cpu backend leaving out what the frame does not\n"
          "need), dense (render.dense) or mc (the Monte-Carlo reference at --spp samples per\n"
          "pixel), each work on one renderer kept across its frames, as an application keeps\n"
          "it. ms_frame: plan (with the geometry pass) plus render for skip and dense, the\n"
          "render for mc; the median over the repetitions with min and max; ms_first: the\n"
          "warm-up frame before them (at the first resolution, the renderer's first frame:\n"
          "fresh memory; at each resolution, the lights' slab kernels resolved, which the\n"
          "frames after it keep); the other ms columns are medians of the summary's. active:\n"
          "channel-pixel updates made over the dense count.\n"
          "vs_mc: ms_frame over mc's in the same run. model: the render.model rendered (\"-\" for\n"
          "mc, which ignores it). cpu: the processor's model name; simd: the cpu backend's\n"
          "vector path (ICS_SIMD=auto|scalar|sse2|avx2|avx512|neon).\n\n"
          "options:\n"
          "  --resolution L    WxH,... (default: the scene's)\n"
          "  --threads T       threads (default 0: all cores)\n"
          "  --reps R          repetitions (default 5; 1..50)\n"
          "  --spp N           mc samples per pixel (default 16: where it reaches the error of\n"
          "                    Patel's model on the default scene at e = 0.015; the default\n"
          "                    as it ships, auto at e = 0.045, needs about 86: docs/results.md)\n"
          "  --work W,...      of skip, dense, mc (default all three)\n"
          "  --model M         render.model (default: the scene's; auto, patel, solid,\n"
          "                    surface, blocker)\n"
          "  --slab-spacing E  render.slab_spacing (> 0; default: the scene's)\n"
          "  --progress        progress on stderr even when it is not a terminal\n"
          "  --allow-outside-paths  let the scene read files outside its own folder\n");
}

#ifdef ICS_HAVE_RENDER
#include "icshadow/render.h"
#include "scene_args.h"

enum { WORK_SKIP, WORK_DENSE, WORK_MC, WORKS };
static const char *const work_names[WORKS] = {"skip", "dense", "mc"};
enum { COL_FRAME, COL_PLAN, COL_RENDER, COL_CONV, COL_SHADE, COL_DETAIL, COLS };

/* the processor's model name (Linux /proc/cpuinfo), commas dropped for the CSV; "-" elsewhere */
static void cpu_model(char *out, size_t n) {
  snprintf(out, n, "-");
  FILE *f = fopen("/proc/cpuinfo", "r");
  if (!f) return;
  char line[512];
  while (fgets(line, sizeof line, f))
    if (!strncmp(line, "model name", 10) && strchr(line, ':')) {
      const char *v = strchr(line, ':') + 1;
      while (*v == ' ' || *v == '\t') v++;
      snprintf(out, n, "%s", v);
      for (char *c = out; *c; c++)
        if (*c == ',' || *c == '\n' || *c == '"') *c = *c == '\n' ? 0 : ' ';
      break;
    }
  fclose(f);
}

typedef struct {
  double ms[COLS][50];
  double first_ms; /* the warm-up frame at this resolution */
  double active;
  char simd[16], model[16];
} work_times;

/* one frame of work w: its plan and render, the times into t at index rep - 1 (rep 0 is the
 * warm-up); ICS_OK or the error with msg */
static ics_status frame(ics_renderer *r, const ics_scene *s, const ics_render_settings *rs0, int w,
                        int width, int height, int threads, int rep, work_times *t, char *msg,
                        size_t msg_size) {
  ics_render_settings rs = *rs0;
  rs.dense = w == WORK_DENSE;
  ics_plan *p = NULL;
  ics_image *img = NULL;
  ics_render_stats st;
  memset(&st, 0, sizeof st);
  /* the plan for the renderer: it resolves render.model auto for its backend */
  ics_plan_opts po = {.settings = &rs, .width = width, .height = height, .threads = threads,
                      .renderer = r};
  double t0 = cli_now_s();
  ics_status status = ics_plan_create(&p, s, &po, msg, msg_size);
  double t1 = cli_now_s();
  if (status == ICS_OK) status = ics_renderer_render(r, p, &img, &st, msg, msg_size);
  double plan_ms = 1e3 * (t1 - t0), frame_ms = w == WORK_MC ? st.ms_total : plan_ms + st.ms_total;
  if (status == ICS_OK && rep == 0) t->first_ms = frame_ms;
  if (status == ICS_OK && rep > 0) {
    const double v[COLS] = {frame_ms, plan_ms, st.ms_total, st.ms_convolution, st.ms_shading,
                            st.ms_detail};
    for (int c = 0; c < COLS; c++) t->ms[c][rep - 1] = v[c];
    t->active = st.updates_dense > 0 ? st.updates_active / st.updates_dense : 1;
    snprintf(t->simd, sizeof t->simd, "%s", st.simd[0] ? st.simd : "-");
    snprintf(t->model, sizeof t->model, "%s", w == WORK_MC ? "-" : st.model);
  }
  ics_image_destroy(img);
  ics_plan_destroy(p);
  return status;
}

/* one renderer per work, kept across its frames as an application keeps it */
static ics_status renderers(ics_renderer **r, const int *use, int threads, int spp, char *msg,
                            size_t msg_size) {
  for (int w = 0; w < WORKS; w++) {
    ics_render_opts ro = {.backend = w == WORK_MC ? "mc" : "cpu", .threads = threads,
                          .spp = w == WORK_MC ? spp : 0};
    ics_status st = use[w] ? ics_renderer_create(&r[w], &ro, msg, msg_size) : ICS_OK;
    if (st != ICS_OK) return st;
  }
  return ICS_OK;
}

static int parse_works(const char *v, int *use) {
  char buf[64];
  if (strlen(v) >= sizeof buf) return -1;
  snprintf(buf, sizeof buf, "%s", v);
  int n = 0;
  for (char *q = buf, *end; q; q = end) {
    end = strchr(q, ',');
    if (end) *end++ = 0;
    int k = -1;
    for (int i = 0; i < WORKS; i++)
      if (!strcmp(q, work_names[i])) k = i;
    if (k < 0 || use[k]) return -1;
    use[k] = 1, n++;
  }
  return n;
}

/* --resolution WxH,...: up to 8 sizes in 1..ICS_SCENE_MAX_RES */
static int parse_sizes(const char *v, int wh[8][2]) {
  int n = 0;
  for (const char *q = v; *q && n < 8;) {
    char bw[32], bh[32];
    int len = 0;
    if (sscanf(q, "%31[0-9]x%31[0-9]%n", bw, bh, &len) != 2 ||
        cli_parse_int(bw, 1, ICS_SCENE_MAX_RES, &wh[n][0]) ||
        cli_parse_int(bh, 1, ICS_SCENE_MAX_RES, &wh[n][1]))
      return -1;
    n++;
    q += len;
    if (*q == ',') q++;
    else if (*q) return -1;
  }
  return n;
}
#endif

int bench_frame(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
#ifndef ICS_HAVE_RENDER
  (void)argc, (void)argv;
  return cli_no_renderer(CMD);
#else
  const char *scene_path = NULL, *res_s = NULL, *works_s = "skip,dense,mc", *model = NULL;
  int threads = 0, reps = 5, spp = 16, force = 0, scenes = 0, outside = 0, have_e = 0;
  double e = 0;
  const cli_option opts[] = {
      {NULL, .kind = CLI_STRING, .dest = &scene_path, .given = &scenes},
      {"--resolution", .kind = CLI_STRING, .dest = &res_s},
      {"--threads", .kind = CLI_INT, .dest = &threads, .lo = 0, .hi = 256},
      {"--reps", .kind = CLI_INT, .dest = &reps, .lo = 1, .hi = 50},
      {"--spp", .kind = CLI_INT, .dest = &spp, .lo = 1, .hi = 1 << 16},
      {"--work", .kind = CLI_STRING, .dest = &works_s},
      {"--model", .kind = CLI_STRING, .dest = &model},
      {"--slab-spacing", .kind = CLI_FINITE, .dest = &e, .given = &have_e},
      {"--progress", .kind = CLI_FLAG, .dest = &force},
      {"--allow-outside-paths", .kind = CLI_FLAG, .dest = &outside},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (scenes > 1) return cli_error(CMD, "give one SCENE (got %d)", scenes);
  int use[WORKS] = {0, 0, 0}, sizes[8][2] = {{0, 0}}, nsizes = 1;
  if (parse_works(works_s, use) <= 0)
    return cli_error(CMD, "--work: expected some of skip, dense, mc (comma-separated, each once), got '%s'", works_s);
  if (res_s && (nsizes = parse_sizes(res_s, sizes)) <= 0)
    return cli_error(CMD, "--resolution: expected WxH,... (up to 8, W and H in 1..%d), got '%s'",
                     ICS_SCENE_MAX_RES, res_s);
  if (have_e && !(e > 0)) return cli_error(CMD, "--slab-spacing: must be > 0, got %g", e);
  ics_render_model m = ICS_MODEL_AUTO;
  if (model && (rc = scene_args_model(CMD, model, &m))) return rc;
  char msg[CLI_MSG_MAX] = "", cpu[128];
  ics_scene *s = NULL;
  ics_scene_opts so = {.allow_outside_paths = outside};
  ics_status st = scene_path ? ics_scene_create_file_opts(&s, scene_path, &so, msg, sizeof msg)
                             : ics_scene_create_default(&s);
  if (st != ICS_OK)
    return cli_status_error(CMD, st, "%s", scene_path ? msg : ics_status_str(st));
  ics_render_settings rs = *ics_scene_settings(s);
  if (model) rs.model = m;
  if (have_e) rs.slab_spacing = e;
  cpu_model(cpu, sizeof cpu);
  cli_progress prog;
  cli_progress_init(&prog, "icshadow bench frame", force);
  int busy = 0, header = 0; /* the header with the first rows: a refused frame writes nothing */
  work_times *t = calloc(WORKS, sizeof *t);
  ics_renderer *r[WORKS] = {NULL, NULL, NULL};
  if (!t) st = ICS_ERR_NOMEM;
  else st = renderers(r, use, threads, spp, msg, sizeof msg);
  for (int si = 0; si < nsizes && st == ICS_OK; si++) {
    int width = sizes[si][0], height = sizes[si][1];
    for (int rep = 0; rep <= reps && st == ICS_OK; rep++)
      for (int w = 0; w < WORKS && st == ICS_OK; w++) {
        if (!use[w]) continue;
        cli_progress_say(&prog, "%s, round %d of %d", work_names[w], rep, reps);
        st = frame(r[w], s, &rs, w, width, height, threads, rep, &t[w], msg, sizeof msg);
      }
    if (st != ICS_OK) break;
    if (!header++)
      printf("scene,width,height,work,model,threads,simd,cpu,ms_frame,ms_min,ms_max,ms_first,"
             "ms_plan,ms_render,ms_convolution,ms_shading,ms_detail,active,vs_mc\n");
    double mc = use[WORK_MC] ? cli_spread_of(t[WORK_MC].ms[COL_FRAME], reps).median : 0;
    for (int w = 0; w < WORKS; w++) {
      if (!use[w]) continue;
      cli_spread f = cli_spread_of(t[w].ms[COL_FRAME], reps);
      if (reps > 1 && cli_spread_busy(f)) busy = 1;
      int W = width, H = height;
      if (!W) W = ics_scene_camera(s)->width, H = ics_scene_camera(s)->height_px;
      printf("%s,%d,%d,%s,%s,%d,%s,%s,%.4g,%.4g,%.4g,%.4g", scene_path ? scene_path : "default",
             W, H, work_names[w], t[w].model, threads, t[w].simd, cpu, f.median, f.min, f.max,
             t[w].first_ms);
      for (int c = COL_PLAN; c < COLS; c++)
        printf(",%.4g", w == WORK_MC && c != COL_RENDER ? 0 : cli_spread_of(t[w].ms[c], reps).median);
      printf(",%.4g,", w == WORK_MC ? 0 : t[w].active);
      if (mc > 0) printf("%.4g\n", f.median / mc);
      else printf("-\n");
    }
    if (cli_stdout_failed(CMD)) st = ICS_ERR_IO;
  }
  cli_progress_done(&prog);
  for (int w = 0; w < WORKS; w++) ics_renderer_destroy(r[w]);
  free(t);
  ics_scene_destroy(s);
  if (st == ICS_ERR_IO) return 1;
  if (st != ICS_OK) return cli_status_error(CMD, st, "%s", msg[0] ? msg : ics_status_str(st));
  if (busy) cli_warn_busy(CMD, "ms_min vs ms_max");
  return 0;
#endif
}
