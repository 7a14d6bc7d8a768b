/* scene_internal.h — the scene object behind the opaque ics_scene (private to
 * libicshadow_render): the model arrays and what they own (mesh BVHs, detail grids). */
#ifndef ICS_RENDER_SCENE_INTERNAL_H
#define ICS_RENDER_SCENE_INTERNAL_H

#include "icshadow/scene.h"

struct ics_scene {
  char name[512];
  ics_camera camera;
  ics_render_settings settings;
  int nlights;
  ics_light lights[ICS_SCENE_MAX_LIGHTS];
  int nmaterials;
  ics_material *materials; /* nmaterials */
  int nobjects;
  ics_object *objects;     /* nobjects */
  int nmeshes;
  ics_mesh **meshes;       /* owned */
  int nfiles;
  char **files;            /* owned: every file read (ics_scene_file) */
};

/* Adds path to the scene's files (ics_scene_file); ICS_ERR_NOMEM when it cannot. */
ics_status ics_scene_note_file(ics_scene *s, const char *path);

/* Fills the derived camera frame (r, u, f) from eye, target, up. ICS_ERR_RANGE when eye ==
 * target or up is parallel to the view direction (msg names which). */
ics_status ics_camera_derive(ics_camera *c, char *msg, size_t msg_size);

/* Default render settings (what a scene file's "render" block starts from). */
void ics_render_settings_defaults(ics_render_settings *s);

/* Releases what the scene owns (used by ics_scene_destroy and by failed readers). */
void ics_scene_free_parts(ics_scene *s);

#endif
