/* bench_slab.c — `icshadow bench slab [options]`: the propagation of one light buffer through
 * the slabs, for each kernel member, sizes, thread counts and backends (side by side), as CSV. Each run renders,
 * through the public renderer API, a scene made for it: an edge occluder in the first slab and a
 * receiver after `slabs` slabs, world units = pixels (so the per-slab kernel class is the given
 * mean and covariance in pixels), no padding; the error is taken on the receiver's visible half
 * (x > 0; the other half shows the occluder). The time per pixel per slab is the renderer's own
 * convolution time (stats.ms_convolution) over (buffer pixels x slabs); the memcpy floor is the
 * time to copy a buffer of the same size, measured between the repetitions of the same run
 * (interleaved, so both see the same machine); error is the largest deviation of the receiver
 * from the exact propagation of the edge, Phi((x - n m_x) / sqrt(n C_xx + 1/12)) (the class's
 * CLT limit after n slabs; 1/12: the point-sampled edge). Median over --reps repetitions with
 * min and max; a warning on stderr when the spread says the machine was busy. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend_options.h"
#include "bench_stats.h"
#include "commands.h"

static const char CMD[] = "bench slab";

#ifdef ICS_HAVE_RENDER
#include "icshadow/render.h"

typedef struct {
  const char *label;
  const char *kernel;
  int samples;
  const char *comp;
  int run;       /* render.rotation_run */
  int rotations; /* render.pixel_rotations (0: the default) */
} member_t;

static const member_t members[] = {
    {"ellipse2", "ellipse", 2, "expected", 1, 0},         {"ellipse2-rot4", "ellipse", 2, "expected", 1, 4},
    {"ellipse2-run16", "ellipse", 2, "expected", 16, 0},
    {"ellipse3", "ellipse", 3, "expected", 1, 0},         {"poisson8", "poisson", 8, "expected", 1, 0},
    {"poisson16", "poisson", 16, "expected", 1, 0},       {"gauss19", "gauss", 19, "nonneg", 1, 0},
    {"tophat5", "tophat", 5, "nonneg", 1, 0},             {"ellipse2-signed", "ellipse", 2, "signed", 1, 0},
    {"integer", "gauss", 3, "integer", 1, 0},
};
#define NMEMBERS ((int)(sizeof members / sizeof *members))
#endif

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow bench slab [--sizes N,N,...] [--slabs K] [--threads T,T,...]\n"
          "       [--kernels K,K,...] [--backend B,...] [--cov CXX,CXY,CYY] [--mean MX,MY] [--reps R]\n"
          "       [--work dense|skip|dense,skip] [--occluder edge|stripes]\n"
          "Light-buffer propagation through K slabs per kernel member, side by side with the\n"
          "memcpy floor measured between the repetitions, as CSV:\n"
          "  backend,kernel,samples,mode,width,height,slabs,threads,ns_per_px_slab,ns_min,ns_max,\n"
          "  floor_ns_per_px,floor_ratio,error,reps,simd,work,occluder,active,ms_render,\n"
          "  ms_render_min,ms_render_max\n"
          "(ns_per_px_slab: the convolution time over buffer pixels x slabs, skipped or not;\n"
          "floor_ratio = floor / ns: 1 would be memory speed; error: max deviation of the\n"
          "propagated edge from the class's exact limit (- for stripes); simd: the cpu backend's\n"
          "vector path, chosen by ICS_SIMD=auto|scalar|sse2|avx2|avx512|neon, - for other\n"
          "backends; work: dense (render.dense) or skip (active regions, constant tiles); active:\n"
          "the channel-pixel updates made over the dense count; ms_render: the whole render).\n\n"
          "options:\n"
          "  --sizes N,...     square buffer sides (default 512,768; 16..4096)\n"
          "  --slabs K         slabs (default 256; 1..4096)\n"
          "  --threads T,...   thread counts (default 1,2)\n"
          "  --kernels K,...   members (default all): ellipse2 (2 rotations per pixel, the\n"
          "                    default) ellipse2-rot4 ellipse2-run16 ellipse3 poisson8\n"
          "                    poisson16 gauss19 tophat5 ellipse2-signed integer\n"
          "  --backend B,...   cpu (default) and/or other backends of `icshadow render --backends`,\n"
          "                    run side by side for each member and size (a device backend\n"
          "                    such as cl runs once, threads 0)\n"
          "  --cov C,C,C       per-slab covariance in px^2 (default 2,0.5,1)\n"
          "  --mean MX,MY      per-slab mean in px (default 0.3,-0.2)\n"
          "  --reps R          repetitions, median reported (default 3; 1..50)\n"
          "  --work W          dense (default), skip, or dense,skip: both, their repetitions\n"
          "                    interleaved\n"
          "  --occluder O      edge (default: a half-plane in the first slab) or stripes (4 px\n"
          "                    bars every 8 px over the whole buffer: nothing to skip)\n"
          "  --progress        progress on stderr even when it is not a terminal\n");
#ifdef ICS_HAVE_RENDER
  backend_options_help(f); /* --cl-device, --gl-context, ...: from the backend table */
#endif
}

#ifdef ICS_HAVE_RENDER
static int parse_list(const char *cmd, const char *opt, const char *v, int lo, int hi, int *out,
                      int max) {
  int n = 0;
  const char *p = v;
  while (*p) {
    char buf[32];
    size_t len = strcspn(p, ",");
    if (len == 0 || len >= sizeof buf || n == max)
      return cli_error(cmd, "%s: expected up to %d comma-separated integers, got '%s'", opt, max, v), -1;
    memcpy(buf, p, len);
    buf[len] = 0;
    if (cli_parse_int(buf, lo, hi, &out[n]))
      return cli_error(cmd, "%s: expected integers in %d..%d, got '%s'", opt, lo, hi, buf), -1;
    n++;
    p += len;
    if (*p == ',') p++;
  }
  return n;
}

static double now_floor_ns(size_t npx, int slabs, float *a, float *b) {
  double t0 = cli_now_s();
  for (int k = 0; k < slabs; k++) {
    memcpy(b, a, npx * sizeof *a);
    float *t = a;
    a = b, b = t;
  }
  return 1e9 * (cli_now_s() - t0) / ((double)npx * slabs);
}

/* One member, size, backend and thread count: the scene (an edge or stripes occluder in the first
 * slab, a receiver after `slabs`), planned dense and with skipping as asked, rendered reps
 * times with the works interleaved (after a warm-up each) and the memcpy floor between them. */
typedef struct {
  const member_t *m;
  const char *backend;
  int n, threads, slabs, reps;
  double mean[2], cov[3];
  int stripes, dense, skip;
  const char *const *options; /* the backend options (backend_options_list) */
} config_t;

static int bench_config(const config_t *c, cli_progress *prog, int *busy, int *cpu_threads) {
  const member_t *m = c->m;
  int n = c->n, nw = 0, works[2];
  if (c->dense) works[nw++] = 1;
  if (c->skip) works[nw++] = 0;
  size_t npx = (size_t)n * n;
  float *fa = malloc(npx * sizeof *fa), *fb = malloc(npx * sizeof *fb);
  ics_scene *s[2] = {NULL, NULL};
  ics_plan *p[2] = {NULL, NULL};
  ics_renderer *r = NULL;
  char msg[CLI_MSG_MAX] = "";
  ics_status st = fa && fb ? ICS_OK : ICS_ERR_NOMEM;
  for (size_t i = 0; fa && i < npx; i++) fa[i] = (float)(i % 7);
  for (int w = 0; w < nw && st == ICS_OK; w++) {
    /* world units = pixels: height n, slab spacing 1, d1 1; light mean -mean (Eq. 7), the row
     * axis pointing down (y components change sign). The occluder: a half-plane (its edge at
     * x = 0), or vertical stripes 4 px wide every 8 px over the whole buffer, which no tile
     * ever sees constant */
    char occ[512], json[2048], rot[48] = "";
    if (m->rotations) snprintf(rot, sizeof rot, " \"pixel_rotations\": %d,", m->rotations);
    if (c->stripes)
      snprintf(occ, sizeof occ, "{\"shape\": \"fence\", \"center\": [0, %d, 0], \"poles\": %d, "
               "\"pole_size\": [4, %d, 0.5], \"spacing\": 8, \"bar_size\": [1, 0.5], \"material\": \"black\"}", -n, n / 8 + 1, 2 * n);
    else
      snprintf(occ, sizeof occ, "{\"shape\": \"rect\", \"center\": [%.17g, 0, 0], \"normal\": [0, 0, 1], "
               "\"size\": [%d, %d], \"material\": \"black\"}", -0.25 * n, n / 2, 2 * n);
    snprintf(json, sizeof json,
             "{\"camera\": {\"eye\": [0, 0, 1], \"target\": [0, 0, 0], \"height\": %d, \"resolution\": [%d, %d]},"
             " \"render\": {\"model\": \"patel\", \"slab_spacing\": 1, \"d1\": 1, \"kernel\": \"%s\", \"samples\": %d,"
             " \"compensate\": \"%s\", \"max_pad\": 0, \"seed\": 1, \"rotation_run\": %d,%s \"dense\": %s},"
             " \"lights\": [{\"mean\": [%.17g, %.17g], \"cov\": [[%.17g, %.17g], [%.17g, %.17g]]}],"
             " \"materials\": {\"black\": {\"color\": [0, 0, 0]}, \"white\": {}},"
             " \"objects\": [%s,"
             "  {\"shape\": \"rect\", \"center\": [0, 0, %d], \"normal\": [0, 0, 1], \"size\": [%d, %d], \"material\": \"white\"}]}",
             n, n, n, m->kernel, m->samples, m->comp, m->run, rot, works[w] ? "true" : "false",
             -c->mean[0], c->mean[1], c->cov[0], -c->cov[1], -c->cov[1], c->cov[2], occ, -c->slabs,
             2 * n, 2 * n);
    ics_plan_opts po = {.threads = c->threads};
    st = ics_scene_create_json(&s[w], json, "bench", NULL, msg, sizeof msg);
    if (st == ICS_OK) st = ics_plan_create(&p[w], s[w], &po, msg, sizeof msg);
  }
  ics_render_opts ro = {.backend = c->backend, .threads = c->threads, .options = c->options};
  if (st == ICS_OK) st = ics_renderer_create(&r, &ro, msg, sizeof msg);
  double t[2][50], ms[2][50], fl[2][50], err[2] = {0, 0}, active[2] = {1, 1};
  char simd[16] = "";
  int K = p[0] ? ics_plan_slabs(p[0]) - 1 : 0;
  for (int rep = 0; rep <= c->reps && st == ICS_OK; rep++) /* rep 0: warm-up */
    for (int w = 0; w < nw && st == ICS_OK; w++) {
      ics_image *img;
      ics_render_stats stats;
      st = ics_renderer_render(r, p[w], &img, &stats, msg, sizeof msg);
      if (st != ICS_OK) break;
      *cpu_threads = stats.threads > 0; /* a device backend: one row, threads 0 */
      snprintf(simd, sizeof simd, "%s", stats.simd);
      double floor_ns = now_floor_ns(npx, K, fa, fb);
      if (rep > 0) t[w][rep - 1] = stats.ns_per_px_slab, fl[w][rep - 1] = floor_ns, ms[w][rep - 1] = stats.ms_total;
      if (stats.updates_dense > 0) active[w] = stats.updates_active / stats.updates_dense;
      if (rep == c->reps && !c->stripes) {
        /* the receiver against Phi((x - K m_x) / sqrt(K C_xx + 1/12)), edge at x = 0 */
        double sd = sqrt(K * c->cov[0] + 1.0 / 12);
        for (int j = 0; j < n; j++)
          for (int i = n / 2; i < n; i++) { /* x < 0 shows the occluder itself */
            double x = i + 0.5 - n / 2.0;
            double ref = ics_normal_cdf((x - K * c->mean[0]) / sd);
            err[w] = fmax(err[w], fabs(img->data[((size_t)j * n + i) * 4] - ref));
          }
      }
      ics_image_destroy(img);
      cli_progress_say(prog, "%s %dx%d %d thread(s): rep %d/%d", m->label, n, n, c->threads, rep, c->reps);
    }
  char mode[64] = "";
  for (int i = 0; p[0] && i < ics_plan_pass_count(p[0]); i++) {
    const ics_plan_pass *q = ics_plan_pass_at(p[0], i);
    if (q->light == 0) sscanf(q->detail, "%*s %*s %63[a-z]", mode);
  }
  int bw = 0, bh = 0;
  if (p[0]) ics_plan_sizes(p[0], NULL, NULL, &bw, &bh);
  for (int w = 0; w < nw && st == ICS_OK; w++) {
    cli_spread sp = cli_spread_of(t[w], c->reps), fsp = cli_spread_of(fl[w], c->reps);
    cli_spread msp = cli_spread_of(ms[w], c->reps);
    if (c->reps > 1 && cli_spread_busy(sp)) *busy = 1;
    printf("%s,%s,%d,%s,%d,%d,%d,%d,%.4g,%.4g,%.4g,%.4g,%.4g,", c->backend, m->label, m->samples, mode,
           bw, bh, K, *cpu_threads ? c->threads : 0, sp.median, sp.min, sp.max, fsp.median,
           fsp.median / sp.median);
    if (c->stripes)
      printf("-,");
    else
      printf("%.3g,", err[w]);
    printf("%d,%s,%s,%s,%.4g,%.4g,%.4g,%.4g\n", c->reps, *simd ? simd : "-", works[w] ? "dense" : "skip",
           c->stripes ? "stripes" : "edge", active[w], msp.median, msp.min, msp.max);
  }
  if (r) ics_renderer_destroy(r);
  for (int w = 0; w < 2; w++) ics_plan_destroy(p[w]), ics_scene_destroy(s[w]);
  free(fa), free(fb);
  if (st != ICS_OK)
    return st == ICS_ERR_NOMEM && !msg[0] ? cli_failure(CMD, "out of memory for %dx%d buffers", n, n)
                                          : cli_status_error(CMD, st, "%s %dx%d: %s", m->label, n, n, msg);
  return cli_stdout_failed(CMD); /* stop at the first row that fails, with its cause */
}
#endif

int bench_slab(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
#ifndef ICS_HAVE_RENDER
  (void)argc, (void)argv;
  return cli_no_renderer(CMD);
#else
  const char *sizes_s = "512,768", *threads_s = "1,2", *kernels_s = NULL, *backend_s = "cpu";
  const char *cov_s = "2,0.5,1", *mean_s = "0.3,-0.2";
  const char *work_s = "dense", *occluder_s = "edge";
  int slabs = 256, reps = 3, force = 0;
  const cli_option mine[] = {
      {"--sizes", .kind = CLI_STRING, .dest = &sizes_s},
      {"--slabs", .kind = CLI_INT, .dest = &slabs, .lo = 1, .hi = 4096},
      {"--threads", .kind = CLI_STRING, .dest = &threads_s},
      {"--kernels", .kind = CLI_STRING, .dest = &kernels_s},
      {"--backend", .kind = CLI_STRING, .dest = &backend_s},
      {"--cov", .kind = CLI_STRING, .dest = &cov_s},
      {"--mean", .kind = CLI_STRING, .dest = &mean_s},
      {"--reps", .kind = CLI_INT, .dest = &reps, .lo = 1, .hi = 50},
      {"--progress", .kind = CLI_FLAG, .dest = &force},
      {"--work", .kind = CLI_STRING, .dest = &work_s},
      {"--occluder", .kind = CLI_STRING, .dest = &occluder_s},
  };
  cli_option opts[CLI_NOPTS(mine) + BACKEND_OPTIONS_MAX];
  memcpy(opts, mine, sizeof mine);
  backend_options bo;
  int nopts = CLI_NOPTS(mine) + backend_options_table(&bo, opts + CLI_NOPTS(mine));
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, nopts);
  if (rc) return rc;
  int sizes[8], threads[8], ns, nt;
  if ((ns = parse_list(CMD, "--sizes", sizes_s, 16, 4096, sizes, 8)) < 0) return 2;
  if ((nt = parse_list(CMD, "--threads", threads_s, 1, 256, threads, 8)) < 0) return 2;
  double cov[3], mean[2];
  if (cli_parse_numbers(CMD, "--cov", cov_s, cov_s, NULL, 3, cov) ||
      cli_parse_numbers(CMD, "--mean", mean_s, mean_s, NULL, 2, mean))
    return 2;
  if (cov[0] < 0 || cov[2] < 0 || cov[0] * cov[2] < cov[1] * cov[1])
    return cli_error(CMD, "--cov: not positive semidefinite: %s", cov_s);
  int dense = !strcmp(work_s, "dense") || !strcmp(work_s, "dense,skip") || !strcmp(work_s, "skip,dense");
  int skip = !strcmp(work_s, "skip") || !strcmp(work_s, "dense,skip") || !strcmp(work_s, "skip,dense");
  if (!dense && !skip) return cli_error(CMD, "--work: expected dense, skip or dense,skip, got '%s'", work_s);
  int stripes = !strcmp(occluder_s, "stripes");
  if (!stripes && strcmp(occluder_s, "edge"))
    return cli_error(CMD, "--occluder: expected edge or stripes, got '%s'", occluder_s);
  int use[NMEMBERS], nuse = 0;
  if (kernels_s) {
    const char *p = kernels_s;
    while (*p) {
      size_t len = strcspn(p, ",");
      int k = -1;
      for (int i = 0; i < NMEMBERS; i++)
        if (strlen(members[i].label) == len && !strncmp(p, members[i].label, len)) k = i;
      if (k < 0 || nuse == NMEMBERS)
        return cli_error(CMD, "--kernels: unknown member '%.*s' (see --help)", (int)len, p);
      use[nuse++] = k;
      p += len;
      if (*p == ',') p++;
    }
  } else {
    for (int i = 0; i < NMEMBERS; i++) use[nuse++] = i;
  }
  /* --backend: one or several, run side by side for each member and size */
  char blist[256], *backends[4];
  int nb = 0;
  if (strlen(backend_s) >= sizeof blist) return cli_error(CMD, "--backend: too long");
  snprintf(blist, sizeof blist, "%s", backend_s);
  for (char *q = blist, *end; q; q = end) {
    end = strchr(q, ',');
    if (end) *end++ = 0;
    if (!*q) return cli_error(CMD, "--backend: an empty name in '%s'", backend_s);
    if (nb == 4) return cli_error(CMD, "--backend: at most 4 backends");
    char why[1024];
    if (!ics_backend_available(q, why, sizeof why)) return cli_error(CMD, "--backend: %s: %s", q, why);
    backends[nb++] = q;
  }
  cli_progress prog;
  cli_progress_init(&prog, "bench slab", force);
  printf("backend,kernel,samples,mode,width,height,slabs,threads,ns_per_px_slab,ns_min,ns_max,"
         "floor_ns_per_px,floor_ratio,error,reps,simd,work,occluder,active,ms_render,"
         "ms_render_min,ms_render_max\n");
  int busy = 0;
  for (int si = 0; si < ns; si++)
    for (int ki = 0; ki < nuse; ki++)
      for (int bi = 0; bi < nb; bi++)
        for (int ti = 0, cpu_threads = 1; ti < nt && cpu_threads; ti++) {
          config_t c = {&members[use[ki]], backends[bi], sizes[si], threads[ti], slabs, reps,
                        {mean[0], mean[1]}, {cov[0], cov[1], cov[2]}, stripes, dense, skip,
                        backend_options_list(&bo)};
          rc = bench_config(&c, &prog, &busy, &cpu_threads);
          if (rc) {
            cli_progress_done(&prog);
            return rc;
          }
        }
  cli_progress_done(&prog);
  if (busy) cli_warn_busy(CMD, "ns_min vs ns_max");
  return cli_stdout_failed(CMD);
#endif
}
