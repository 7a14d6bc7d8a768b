/* cmd_plan.c — `icshadow plan [SCENE] [options] [-o PLAN.json]`: the render plan of a scene as
 * JSON (docs/renderer.md "Work that a scene does not need is not done"): the passes with their
 * bytes, taps and kernels, what is left out and why, the slab count and the memory figure. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "scene_args.h"

static const char CMD[] = "plan";

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow plan [SCENE] [options] [-o PLAN.json]\n"
          "Prints the render plan of a scene as JSON: \"passes\" (name, bytes; light, taps, kernel\n"
          "and mode for convolutions), \"omitted\" (name, reason), \"slabs\", \"memory_bytes\",\n"
          "the light-buffer size and padding. Planning runs the geometry pass (the layered depth\n"
          "image), so the figures are exact; nothing is rendered. The embedded default scene\n"
          "when no SCENE is given.\n\n"
          "options:\n");
#ifdef ICS_HAVE_RENDER
  scene_args_help(f);
#endif
  fprintf(f,
          "  -o PLAN.json        write the plan to a file (default: stdout)\n"
          "  --print-scene       print the scene file of the default scene instead and exit\n"
          "Exit status: 0 ok, 1 cannot write or out of memory, 2 bad input.\n");
}

int cmd_plan(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
#ifndef ICS_HAVE_RENDER
  (void)argc, (void)argv;
  return cli_no_renderer(CMD);
#else
  scene_args a;
  memset(&a, 0, sizeof a);
  const char *outp = "-";
  int print_scene = 0;
  cli_option opts[SCENE_ARGS_NOPTS + 2];
  scene_args_options(&a, opts);
  const cli_option mine[] = {
      {"-o", .kind = CLI_FILE, .dest = &outp},
      {"--print-scene", .kind = CLI_FLAG, .dest = &print_scene},
  };
  memcpy(opts + SCENE_ARGS_NOPTS, mine, sizeof mine);
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  cli_output out;
  if (print_scene) {
    if (a.scene) return cli_error(CMD, "--print-scene prints the default scene: give no SCENE");
    if (cli_output_open(&out, CMD, outp) != 0) return 1;
    fputs(ics_scene_default_json(), out.fp);
    return cli_output_commit(&out) ? 1 : 0;
  }
  const cli_path in = {"scene file", a.scene}, o = {"-o", outp};
  if ((rc = cli_check_outputs(CMD, &in, 1, &o, 1))) return rc;
  ics_scene *s;
  ics_render_settings rs;
  ics_plan_opts po;
  if ((rc = scene_args_load(CMD, &a, &s, &rs, &po))) return rc;
  if ((rc = scene_args_check_outputs(CMD, s, NULL, 0, &o, 1))) {
    ics_scene_destroy(s);
    return rc;
  }
  char msg[CLI_MSG_MAX] = "";
  ics_plan *p;
  ics_status st = ics_plan_create(&p, s, &po, msg, sizeof msg);
  if (st != ICS_OK) {
    ics_scene_destroy(s);
    return cli_status_error(CMD, st, "%s", msg);
  }
  rc = 0;
  if (cli_output_open(&out, CMD, outp) != 0) {
    rc = 1;
  } else if (ics_plan_write_json(p, out.fp) != ICS_OK) {
    cli_output_abort(&out);
    rc = cli_failure(CMD, "cannot write %s", outp);
  } else if (cli_output_commit(&out) != 0) {
    rc = 1;
  }
  ics_plan_destroy(p);
  ics_scene_destroy(s);
  return rc;
#endif
}
