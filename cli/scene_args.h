/* scene_args.h — what `icshadow render` and `icshadow plan` share: the SCENE argument (a file,
 * or the embedded default scene when none is given) and the options that override the scene's
 * render settings and resolution, turned into a scene, settings and plan options. */
#ifndef ICS_CLI_SCENE_ARGS_H
#define ICS_CLI_SCENE_ARGS_H

#include <stdint.h>

#include "commands.h"

#ifdef ICS_HAVE_RENDER
#include "icshadow/render.h"

typedef struct scene_args {
  const char *scene; /* NULL: the default scene */
  int res[2];        /* --resolution WxH (0: the scene's) */
  const char *kernel, *compensate, *radii, *model;
  int samples;
  double slab_spacing, d1;
  uint64_t seed;
  int have_seed, have_slab, have_d1, have_samples;
  int dense;         /* --dense: render.dense */
  int outside;       /* --allow-outside-paths: the scene may read files outside its folder */
  int threads;       /* --threads (0: all cores) */
  int scenes;        /* SCENE arguments given */
} scene_args;

#define SCENE_ARGS_NOPTS 13
/* Writes the shared option entries into opts[0 .. SCENE_ARGS_NOPTS - 1]. */
void scene_args_options(scene_args *a, cli_option *opts);

/* --model V: the render.model named V into *model; 0, or the exit status after the message (the
 * names it takes) */
int scene_args_model(const char *cmd, const char *v, ics_render_model *model);

/* Reads the scene and applies the overrides into *rs and *po (po->settings points at rs).
 * Returns 0, or the exit status after the message. On success *s must be destroyed. */
int scene_args_load(const char *cmd, const scene_args *a, ics_scene **s, ics_render_settings *rs,
                    ics_plan_opts *po);

/* cli_check_outputs over the scene's files (ics_scene_file: the scene file, its lights_file,
 * grids and meshes) and `extra` inputs of the command's own. */
int scene_args_check_outputs(const char *cmd, const ics_scene *s, const cli_path *extra,
                             int nextra, const cli_path *out, int nout);

/* The shared lines of --help. */
void scene_args_help(FILE *f);
#endif

#endif
