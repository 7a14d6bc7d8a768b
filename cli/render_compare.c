/* render_compare.c — the render against a reference image (see render_compare.h). */
#include "render_compare.h"

#ifdef ICS_HAVE_RENDER
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"

/* a number member of our own summary JSON ("\"key\": value"), or NAN */
static double summary_number(const char *info, const char *key) {
  char pat[64];
  snprintf(pat, sizeof pat, "\"%s\": ", key);
  const char *p = info ? strstr(info, pat) : NULL;
  if (!p) return NAN;
  char *end;
  double v = strtod(p + strlen(pat), &end);
  return end == p + strlen(pat) ? NAN : v;
}

static void summary_string(const char *info, const char *key, char *out, size_t n) {
  char pat[64];
  snprintf(pat, sizeof pat, "\"%s\": \"", key);
  const char *p = info ? strstr(info, pat) : NULL;
  out[0] = 0;
  if (!p) return;
  p += strlen(pat);
  size_t k = 0;
  while (p[k] && p[k] != '"' && k + 1 < n) k++;
  memcpy(out, p, k);
  out[k] = 0;
}

static void init(render_comparison *c, const char *ref) {
  memset(c, 0, sizeof *c);
  c->reference = ref;
  c->ms_reference = NAN;
  c->ref_noise = NAN;
}

int render_compare_file(const char *cmd, const char *path, const ics_image *img,
                        render_comparison *out) {
  init(out, path);
  ics_exr_channels *ch = NULL;
  char msg[CLI_MSG_MAX];
  ics_status st = ics_exr_read_channels(path, &ch, msg, sizeof msg);
  if (st != ICS_OK) return cli_status_error(cmd, st, "--compare: %s", msg);
  int k[3] = {ics_exr_channel_index(ch, "R"), ics_exr_channel_index(ch, "G"),
              ics_exr_channel_index(ch, "B")};
  int e[3] = {ics_exr_channel_index(ch, "stderr.R"), ics_exr_channel_index(ch, "stderr.G"),
              ics_exr_channel_index(ch, "stderr.B")};
  int rc = 0;
  ics_image *ref = NULL;
  if (k[0] < 0 || k[1] < 0 || k[2] < 0) {
    rc = cli_error(cmd, "--compare: %s has no R, G, B channels", path);
  } else if (ch->width != img->width || ch->height != img->height) {
    rc = cli_error(cmd, "--compare: %s is %dx%d, the render %dx%d", path, ch->width, ch->height,
                   img->width, img->height);
  } else if (ics_image_create(&ref, ch->width, ch->height, 3) != ICS_OK) {
    rc = cli_failure(cmd, "--compare: out of memory");
  } else {
    size_t npx = (size_t)ch->width * ch->height;
    double ss = 0;
    for (size_t p = 0; p < npx; p++)
      for (int c = 0; c < 3; c++) {
        ref->data[p * 3 + c] = ch->data[p * ch->count + k[c]];
        if (e[0] >= 0 && e[1] >= 0 && e[2] >= 0) {
          double s = ch->data[p * ch->count + e[c]];
          ss += s * s;
        }
      }
    if (e[0] >= 0 && e[1] >= 0 && e[2] >= 0) out->ref_noise = sqrt(ss / (3.0 * npx));
    ics_image_diff_rgb(img, ref, &out->d);
    out->ref = ref, ref = NULL;
    summary_string(ch->info, "backend", out->ref_backend, sizeof out->ref_backend);
    summary_string(ch->info, "device", out->ref_device, sizeof out->ref_device);
    out->ms_reference = summary_number(ch->info, "ms_render");
    double spp = summary_number(ch->info, "spp");
    out->ref_spp = isfinite(spp) ? (int)spp : 0;
  }
  ics_image_destroy(ref);
  ics_exr_channels_destroy(ch);
  return rc;
}

int render_compare_mc(const char *cmd, const ics_plan *plan, int spp, int threads,
                      const char *mc_mesh, void (*progress)(void *, int, int), void *progress_ctx,
                      const ics_image *img, render_comparison *out) {
  init(out, "mc");
  char msg[CLI_MSG_MAX] = "";
  ics_render_opts ro = {.backend = "mc", .threads = threads, .spp = spp, .progress = progress,
                        .progress_ctx = progress_ctx, .mc_mesh = mc_mesh};
  ics_renderer *r;
  ics_image *ref = NULL;
  ics_render_stats st;
  ics_status s = ics_renderer_create(&r, &ro, msg, sizeof msg);
  if (s == ICS_OK) {
    s = ics_renderer_render(r, plan, &ref, &st, msg, sizeof msg);
    ics_renderer_destroy(r);
  }
  if (s != ICS_OK) return cli_status_error(cmd, s, "--reference: %s", msg);
  ics_image_diff_rgb(img, ref, &out->d);
  snprintf(out->ref_backend, sizeof out->ref_backend, "mc");
  snprintf(out->ref_device, sizeof out->ref_device, "%s", st.device);
  out->ref_spp = st.spp;
  out->ms_reference = st.ms_total;
  out->ref_noise = st.noise;
  out->ref = ref;
  return 0;
}

void render_comparison_release(render_comparison *c) {
  ics_image_destroy(c->ref);
  c->ref = NULL;
}

ics_image *render_difference_image(const ics_image *img, const ics_image *ref, double scale) {
  ics_image *o;
  if (ics_image_create(&o, img->width, img->height, 3) != ICS_OK) return NULL;
  for (size_t p = 0; p < (size_t)img->width * img->height; p++) {
    double d = 0;
    for (int c = 0; c < 3; c++) d += img->data[p * img->channels + c] - ref->data[p * ref->channels + c];
    d *= scale / 3;
    o->data[p * 3] = (float)fmin(1, fmax(0, d));
    o->data[p * 3 + 2] = (float)fmin(1, fmax(0, -d));
  }
  return o;
}

static void number(FILE *f, const char *key, double v) {
  if (isfinite(v))
    fprintf(f, ", \"%s\": %.17g", key, v);
  else
    fprintf(f, ", \"%s\": null", key);
}

void render_comparison_json(FILE *f, const render_comparison *c) {
  fputs("{\"reference\": ", f);
  ics_json_write_string(f, c->reference);
  if (c->ref_backend[0]) fprintf(f, ", \"reference_backend\": \"%s\"", c->ref_backend);
  if (c->ref_device[0]) fputs(", \"reference_device\": ", f), ics_json_write_string(f, c->ref_device);
  if (c->ref_spp) fprintf(f, ", \"reference_spp\": %d", c->ref_spp);
  number(f, "ms_reference", c->ms_reference);
  number(f, "reference_noise", c->ref_noise);
  number(f, "rmse", c->d.rmse);
  /* E[rmse^2] = error^2 + noise^2 for a reference with independent noise: the render's own
   * error with the reference's noise taken out (0 when the noise explains it all) */
  if (isfinite(c->ref_noise))
    number(f, "rmse_beyond_noise", sqrt(fmax(0, c->d.rmse * c->d.rmse - c->ref_noise * c->ref_noise)));
  number(f, "max_error", c->d.max_abs);
  fprintf(f, ", \"max_at\": [%d, %d]", c->d.max_x, c->d.max_y);
  number(f, "psnr_db", c->d.psnr);
  fputc('}', f);
}
#endif
