/* render_summary.c — the render summary's members (icshadow/renderer.h): what ran, on which
 * device, and the time of each pass, as the CLI's `render` prints them and the Python package
 * returns them. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "icshadow/renderer.h"
#include "icshadow/json_text.h"
#include "plan_internal.h"

void ics_render_summary_write(FILE *f, const ics_plan *plan, const ics_render_settings *rs,
                              const ics_render_stats *stats, double ms_plan) {
  int mc = !strcmp(stats->backend, "mc"), W, H, bw, bh;
  ics_plan_sizes(plan, &W, &H, &bw, &bh);
  fprintf(f, "\"backend\": \"%s\", \"device\": ", stats->backend);
  ics_json_write_string(f, stats->device);
  fprintf(f, ", \"threads\": %d, \"resolution\": [%d, %d]", stats->threads, W, H);
  if (!mc)
    fprintf(f, ", \"light_buffer\": [%d, %d], \"slabs\": %d, \"kernel\": \"%s\", \"samples\": %d, "
            "\"model\": \"%s\", \"model_auto\": %s", bw, bh, stats->slabs,
            ics_render_kernel_name(rs->kernel), rs->samples, stats->model,
            plan->model_auto ? "true" : "false");
  fprintf(f, ", \"seed\": %llu, \"ms_plan\": %.17g, \"ms_geometry\": %.17g, \"ms_render\": %.17g",
          (unsigned long long)rs->seed, ms_plan, 1e3 * ics_plan_geometry_seconds(plan),
          stats->ms_total);
  if (!mc)
    fprintf(f, ", \"ms_convolution\": %.17g, \"ms_shading\": %.17g, \"ms_detail\": %.17g,"
            " \"ns_per_px_slab\": %.17g, \"memory_bytes\": %zu", stats->ms_convolution,
            stats->ms_shading, stats->ms_detail, stats->ns_per_px_slab, ics_plan_memory_bytes(plan));
  if (stats->updates_dense > 0)
    fprintf(f, ", \"updates_dense\": %.17g, \"updates_active\": %.17g", stats->updates_dense,
            stats->updates_active);
  if (stats->ms_geometry_device > 0)
    fprintf(f, ", \"ms_geometry_device\": %.17g", stats->ms_geometry_device);
  if (mc) {
    fprintf(f, ", \"spp\": %d, \"noise\": ", stats->spp);
    if (isfinite(stats->noise))
      fprintf(f, "%.17g", stats->noise);
    else
      fprintf(f, "null");
  }
}
