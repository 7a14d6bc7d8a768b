/* distinct_paths.c — a command's outputs checked, before any work, against its inputs and
 * against each other (cli_check_outputs). Two names are the same file when they reach the same
 * device and inode (hard links, symbolic links, "./" and "../" forms) or, for an output that
 * does not exist yet, when they resolve to the same name (its folder through realpath, a link to
 * nothing followed to the name it would create). Writing to an input would replace it (outputs
 * are renamed into place); two outputs on one path would keep only the last, and two on stdout
 * ("-") would be interleaved. A device such as
 * /dev/null may take several outputs: nothing is renamed over it and nothing is lost. */
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "commands.h"

typedef struct {
  int exists, device; /* stat found it; a character device (several outputs may go there) */
  dev_t dev;
  ino_t ino;
  char *name;         /* the canonical name (malloc'd), or NULL */
} file_id;

/* realpath of the folder, then the last component: a name that need not exist yet */
static char *canonical_name(const char *path) {
  char *full = realpath(path, NULL);
  if (full) return full;
  const char *slash = strrchr(path, '/');
  char *dir = slash ? strndup(path, slash == path ? 1 : (size_t)(slash - path)) : strdup(".");
  char *rdir = dir ? realpath(dir, NULL) : NULL;
  free(dir);
  if (!rdir) return strdup(path);
  const char *base = slash ? slash + 1 : path;
  size_t n = strlen(rdir) + strlen(base) + 2;
  char *out = malloc(n);
  if (out) snprintf(out, n, "%s%s%s", rdir, strcmp(rdir, "/") ? "/" : "", base);
  free(rdir);
  return out;
}

static void identify(const char *path, file_id *id) {
  struct stat st;
  memset(id, 0, sizeof *id);
  if (stat(path, &st) == 0) {
    id->exists = 1;
    id->device = S_ISCHR(st.st_mode);
    id->dev = st.st_dev;
    id->ino = st.st_ino;
  }
  char *dest = id->exists ? NULL : cli_link_destination(path); /* a link to nothing */
  id->name = canonical_name(dest ? dest : path);
  free(dest);
}

static int same(const file_id *a, const file_id *b) {
  if (a->exists && b->exists) return a->dev == b->dev && a->ino == b->ino;
  return a->name && b->name && !strcmp(a->name, b->name);
}

static int named(const cli_path *p) { return p->path && strcmp(p->path, "-"); }
static int is_stdout(const cli_path *p) { return p->path && !strcmp(p->path, "-"); }

int cli_check_outputs(const char *cmd, const cli_path *in, int nin, const cli_path *out, int nout) {
  int rc = 0;
  file_id *ids = calloc((size_t)(nin + nout ? nin + nout : 1), sizeof *ids);
  if (!ids) return cli_failure(cmd, "out of memory");
  for (int i = 0; i < nin; i++)
    if (named(&in[i])) identify(in[i].path, &ids[i]);
  for (int k = 0; k < nout && !rc; k++) {
    for (int j = 0; j < k && !rc && is_stdout(&out[k]); j++)
      if (is_stdout(&out[j]))
        rc = cli_error(cmd, "%s and %s both write to stdout: give one of them a file", out[j].what,
                       out[k].what);
    if (!named(&out[k])) continue;
    file_id *o = &ids[nin + k];
    identify(out[k].path, o);
    for (int i = 0; i < nin && !rc; i++)
      if (named(&in[i]) && ids[i].exists && same(o, &ids[i]))
        rc = cli_error(cmd, "%s %s: that is the %s (%s); refusing to overwrite an input: give "
                       "another output name", out[k].what, out[k].path, in[i].what, in[i].path);
    for (int j = 0; j < k && !rc; j++)
      if (named(&out[j]) && !(o->device && ids[nin + j].device) && same(o, &ids[nin + j]))
        rc = cli_error(cmd, "%s %s and %s %s name the same file: one of the two outputs would be "
                       "lost; give each its own name", out[j].what, out[j].path, out[k].what,
                       out[k].path);
  }
  for (int i = 0; i < nin + nout; i++) free(ids[i].name);
  free(ids);
  return rc;
}
