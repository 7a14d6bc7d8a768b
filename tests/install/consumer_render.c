/* consumer_render.c — a program that renders from C against an installed libicshadow_render
 * (pkg-config icshadow-render and find_package(icshadow COMPONENTS render)), built by
 * tests/install/run.sh: the embedded default scene at 64 x 48 on the cpu backend, written to
 * the EXR given as argv[1]. Exits 0 when the image is there and lit. */
#include <icshadow/render.h>
#include <stdio.h>

int main(int argc, char **argv) {
  if (argc != 2) return 2;
  char msg[1024] = "";
  ics_scene *scene = NULL;
  ics_plan *plan = NULL;
  ics_renderer *r = NULL;
  ics_image *img = NULL;
  ics_render_stats stats;
  ics_plan_opts po = {.width = 64, .height = 48};
  ics_render_opts ro = {.backend = "cpu"};
  ics_status st = ics_scene_create_default(&scene);
  if (st == ICS_OK) st = ics_plan_create(&plan, scene, &po, msg, sizeof msg);
  if (st == ICS_OK) st = ics_renderer_create(&r, &ro, msg, sizeof msg);
  if (st == ICS_OK) st = ics_renderer_render(r, plan, &img, &stats, msg, sizeof msg);
  if (st == ICS_OK) st = ics_exr_write(argv[1], img, ICS_EXR_FLOAT, msg, sizeof msg);
  double sum = 0;
  for (int i = 0; st == ICS_OK && i < img->width * img->height * img->channels; i++) sum += img->data[i];
  printf("rendered %dx%d on %s (%s) in %.1f ms, %d slabs, mean %.4f: %s %s\n", img ? img->width : 0,
         img ? img->height : 0, stats.backend, stats.device, stats.ms_total, stats.slabs,
         img ? sum / (img->width * img->height * img->channels) : 0.0, ics_status_str(st), msg);
  int ok = st == ICS_OK && sum > 0;
  ics_image_destroy(img);
  ics_renderer_destroy(r);
  ics_plan_destroy(plan);
  ics_scene_destroy(scene);
  return ok ? 0 : 1;
}
