/* cliutil.c — helpers shared by the icshadow subcommands: one-line error reports naming the
 * subcommand, strict number parsing (also of option values), the table-driven option parser,
 * --help detection, a monotonic clock for timings, splitmix64 for benchmark data, progress
 * lines, and atomic output files (temporary name + rename). */
#define _XOPEN_SOURCE 700 /* realpath, mkstemp, fchmod */
#include "commands.h"

#include "icshadow.h"

#include <ctype.h>
#include <stdarg.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

int cli_report(int status, const char *cmd, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "icshadow%s%s: ", cmd ? " " : "", cmd ? cmd : "");
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return status;
}

int cli_parse_double(const char *s, double *out) {
  if (!s) return -1;
  while (isspace((unsigned char)*s)) s++;
  if (!*s) return -1;
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (end == s) return -1;
  while (isspace((unsigned char)*end)) end++;
  if (*end) return -1;
  *out = v; /* overflow gives +-inf, underflow a subnormal or 0: both are honest values */
  return 0;
}

int cli_parse_int(const char *s, long lo, long hi, int *out) {
  if (!s) return -1;
  char *end;
  errno = 0;
  long v = strtol(s, &end, 10);
  if (end == s || errno) return -1;
  while (isspace((unsigned char)*end)) end++;
  if (*end || v < lo || v > hi) return -1;
  *out = (int)v;
  return 0;
}

int cli_option_double(const char *cmd, const char *opt, const char *s, int variance, double *out) {
  double v;
  int bad = 1;
  if (cli_parse_double(s, &v) != 0)
    cli_error(cmd, "%s: not a number: '%s'", opt, s);
  else if (isnan(v))
    cli_error(cmd, "%s: NaN is not allowed", opt);
  else if (variance && v < 0)
    cli_error(cmd, "%s: negative variance %s (must be >= 0)", opt, s);
  else if (isinf(v))
    cli_error(cmd, "%s: must be finite, got '%s'", opt, s);
  else
    bad = 0;
  if (bad) return -1;
  *out = v;
  return 0;
}

int cli_parse_numbers(const char *cmd, const char *opt, const char *spec, const char *s,
                      const char *end, int n, double *v) {
  if (!end) end = s + strlen(s);
  const char *p = s;
  for (int i = 0; i < n; i++) {
    const char *q = p;
    while (q < end && *q != ',') q++;
    if (i < n - 1 && q >= end) {
      cli_error(cmd, "%s: expected %d comma-separated numbers at position %d of '%s'", opt, n,
                (int)(p - spec) + 1, spec);
      return -1;
    }
    if (i == n - 1 && q < end) {
      cli_error(cmd, "%s: too many numbers at position %d of '%s'", opt, (int)(q - spec) + 1,
                spec);
      return -1;
    }
    char buf[128];
    size_t len = (size_t)(q - p);
    if (len == 0 || len >= sizeof buf || (memcpy(buf, p, len), buf[len] = 0, 0) ||
        cli_parse_double(buf, &v[i]) != 0) {
      cli_error(cmd, "%s: not a number at position %d of '%s'", opt, (int)(p - spec) + 1, spec);
      return -1;
    }
    if (!isfinite(v[i])) {
      cli_error(cmd, "%s: %s at position %d of '%s' (must be finite)", opt,
                isnan(v[i]) ? "NaN" : "infinite number", (int)(p - spec) + 1, spec);
      return -1;
    }
    p = q + 1;
  }
  return 0;
}

int cli_parse_cl_device(const char *cmd, const char *opt, const char *value, void *dest) {
  (void)dest;
  if (!*value) return cli_error(cmd, "%s: expected a device index or name, got ''", opt);
  if (setenv("ICS_CL_DEVICE", value, 1))
    return cli_error(cmd, "%s: cannot set ICS_CL_DEVICE: %s", opt, strerror(errno));
  return 0;
}

double cli_now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

uint64_t cli_splitmix64(uint64_t *state) {
  uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double cli_splitmix_unit(uint64_t *state) {
  return (double)(cli_splitmix64(state) >> 11) * 0x1p-53;
}

void cli_progress_init(cli_progress *p, const char *who, int forced) {
  p->who = who;
  p->tty = isatty(2);
  p->on = forced || p->tty;
}

void cli_progress_say(const cli_progress *p, const char *fmt, ...) {
  if (!p->on) return;
  va_list ap;
  va_start(ap, fmt);
  fprintf(stderr, "%s%s: ", p->tty ? "\r" : "", p->who);
  vfprintf(stderr, fmt, ap);
  fputs(p->tty ? "\033[K" : "\n", stderr);
  va_end(ap);
}

void cli_progress_done(const cli_progress *p) {
  if (p->on && p->tty) fputs("\r\033[K", stderr);
}

int cli_stdout_failed(const char *cmd) {
  errno = 0;
  if (fflush(stdout) == 0 && !ferror(stdout)) return 0;
  if (!errno) /* an earlier write failed, and stdio keeps no cause */
    return cli_failure(cmd, "cannot write stdout: a write before the last flush failed");
  return cli_failure(cmd, "cannot write stdout: %s", strerror(errno));
}

int cli_wants_help(int argc, char **argv) {
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) return 1;
  return 0;
}

/* (commands.h) a loop: 40 levels, the kernel's limit */
char *cli_link_destination(const char *path) {
  char *cur = strdup(path);
  for (int depth = 0; cur && depth < 40; depth++) {
    struct stat st;
    if (lstat(cur, &st) != 0) return cur; /* nothing there: the name to create */
    char buf[4096];
    ssize_t n = S_ISLNK(st.st_mode) ? readlink(cur, buf, sizeof buf - 1) : -1;
    if (n < 0) break;
    buf[n] = 0;
    const char *slash = strrchr(cur, '/');
    int dirlen = buf[0] == '/' || !slash ? 0 : (int)(slash - cur) + 1;
    char *next = malloc((size_t)dirlen + (size_t)n + 1);
    if (next) snprintf(next, (size_t)dirlen + (size_t)n + 1, "%.*s%s", dirlen, cur, buf);
    free(cur);
    cur = next;
  }
  free(cur);
  return NULL;
}

int cli_output_open(cli_output *out, const char *cmd, const char *path) {
  out->fp = NULL;
  out->cmd = cmd;
  out->tmp_path = NULL;
  out->copy_path = NULL;
  out->target = NULL;
  out->path = path;
  out->write_path = path;
  if (!path || !strcmp(path, "-")) {
    out->fp = stdout;
    return 0;
  }
  struct stat st;
  if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) {
    out->target = realpath(path, NULL);
    /* a link to nothing yet: the file it names is created (through a temporary, as any) */
    if (!out->target && !(out->target = cli_link_destination(path))) {
      cli_failure(cmd, "cannot write %s: a symbolic link that cannot be followed", path);
      return -1;
    }
  }
  if (!out->target) out->target = strdup(path);
  if (!out->target) return -1;
  if (stat(out->target, &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) {
      cli_failure(cmd, "cannot write %s: it is a directory", path);
      cli_output_abort(out);
      return -1;
    }
    out->fp = fopen(out->target, "w"); /* device or FIFO: in place */
    if (!out->fp) {
      cli_failure(cmd, "cannot open %s: %s", path, strerror(errno));
      cli_output_abort(out);
      return -1;
    }
    const char *td = getenv("TMPDIR");
    size_t n = strlen(td && *td ? td : "/tmp") + 32;
    out->copy_path = malloc(n);
    if (!out->copy_path) {
      cli_output_abort(out);
      return -1;
    }
    snprintf(out->copy_path, n, "%s/icshadow-out.XXXXXX", td && *td ? td : "/tmp");
    int fd = mkstemp(out->copy_path);
    if (fd < 0) {
      cli_failure(cmd, "cannot create a temporary file for %s in %s: %s", path,
                  td && *td ? td : "/tmp", strerror(errno));
      free(out->copy_path);
      out->copy_path = NULL;
      cli_output_abort(out);
      return -1;
    }
    close(fd);
    cli_temp_register(out->copy_path);
    out->write_path = out->copy_path;
    return 0;
  }
  size_t n = strlen(out->target) + 16;
  out->tmp_path = malloc(n);
  if (!out->tmp_path) {
    cli_output_abort(out);
    return -1;
  }
  snprintf(out->tmp_path, n, "%s.tmpXXXXXX", out->target);
  int fd = mkstemp(out->tmp_path);
  if (fd < 0 && errno == ENAMETOOLONG) {
    /* a target name within 10 bytes of NAME_MAX (255) cannot take ".tmpXXXXXX": the same
     * directory (rename stays on one file system), the name's first 64 bytes */
    const char *slash = strrchr(out->target, '/');
    int dirlen = slash ? (int)(slash - out->target) + 1 : 0;
    snprintf(out->tmp_path, n, "%.*s%.64s.tmpXXXXXX", dirlen, out->target, out->target + dirlen);
    fd = mkstemp(out->tmp_path);
  }
  if (fd < 0) {
    cli_failure(cmd, "cannot create %s: %s", path, strerror(errno));
    free(out->tmp_path);
    out->tmp_path = NULL;
    cli_output_abort(out);
    return -1;
  }
  /* mkstemp creates mode 0600: give the file the mode a plain fopen would have */
  mode_t mask = umask(0);
  umask(mask);
  if (fchmod(fd, 0666 & ~mask) != 0)
    cli_warning(cmd, "cannot set the mode of %s: %s", path, strerror(errno));
  cli_temp_register(out->tmp_path);
  out->fp = fdopen(fd, "w");
  if (!out->fp) {
    close(fd);
    cli_output_abort(out);
    return -1;
  }
  out->write_path = out->tmp_path;
  return 0;
}

void cli_output_abort(cli_output *out) {
  if (out->fp && out->fp != stdout) fclose(out->fp);
  if (out->tmp_path) {
    remove(out->tmp_path);
    cli_temp_forget(out->tmp_path);
    free(out->tmp_path);
  }
  if (out->copy_path) {
    remove(out->copy_path);
    cli_temp_forget(out->copy_path);
    free(out->copy_path);
  }
  free(out->target);
  out->fp = NULL;
  out->tmp_path = NULL;
  out->copy_path = NULL;
  out->target = NULL;
}

/* copies the file at `from` to the end of fp; 0, or -1 with errno */
static int copy_into(const char *from, FILE *fp) {
  FILE *in = fopen(from, "rb");
  if (!in) return -1;
  char buf[65536];
  size_t n;
  int bad = 0;
  while (!bad && (n = fread(buf, 1, sizeof buf, in)) > 0) bad = fwrite(buf, 1, n, fp) != n;
  int saved = errno;
  bad |= ferror(in);
  fclose(in);
  errno = saved;
  return bad ? -1 : 0;
}

/* Phase 1 of a commit: the bytes complete (stdout flushed; an in-place target gets its copy; the
 * file closed; a temporary flushed to the disk with fsync). 0, or -1 with errno. The temporary
 * (tmp_path) is left for phase 2, the rename. */
static int finish(cli_output *out) {
  if (out->fp == stdout) {
    out->fp = NULL;
    return fflush(stdout) || ferror(stdout) ? -1 : 0;
  }
  int bad = 0;
  if (out->copy_path) {
    bad = out->fp && copy_into(out->copy_path, out->fp) != 0;
    int saved = errno;
    remove(out->copy_path);
    cli_temp_forget(out->copy_path);
    free(out->copy_path);
    out->copy_path = NULL;
    errno = saved;
  }
  if (out->fp) {
    int saved = errno;
    bad |= ferror(out->fp);
    bad |= fclose(out->fp) != 0;
    if (bad && !errno) errno = saved ? saved : EIO;
    out->fp = NULL;
  }
  if (!bad && out->tmp_path) { /* the bytes on the disk before the rename names them */
    int fd = open(out->tmp_path, O_RDONLY);
    bad = fd < 0 || fsync(fd) != 0;
    int saved = errno;
    if (fd >= 0) close(fd);
    errno = saved;
  }
  return bad ? -1 : 0;
}

static void release(cli_output *out) {
  if (out->tmp_path) {
    remove(out->tmp_path); /* after a rename: gone already */
    cli_temp_forget(out->tmp_path);
  }
  free(out->tmp_path);
  free(out->target);
  out->tmp_path = NULL;
  out->target = NULL;
}

int cli_outputs_commit(cli_output *const *outs, int n) {
  int failed = -1, err = 0;
  for (int i = 0; i < n; i++) {
    errno = 0;
    if (finish(outs[i]) != 0 && failed < 0) failed = i, err = errno ? errno : EIO;
  }
  if (failed >= 0) { /* none of them: every temporary removed */
    const char *name = outs[failed]->path && strcmp(outs[failed]->path, "-") ? outs[failed]->path : "stdout";
    cli_failure(outs[failed]->cmd, "cannot write %s: %s", name, strerror(err));
    for (int i = 0; i < n; i++) release(outs[i]);
    return -1;
  }
  int bad = 0;
  for (int i = 0; i < n; i++) {
    if (outs[i]->tmp_path && rename(outs[i]->tmp_path, outs[i]->target) != 0) {
      cli_failure(outs[i]->cmd, "cannot write %s: %s", outs[i]->path, strerror(errno));
      bad = 1;
    }
    release(outs[i]);
  }
  return bad ? -1 : 0;
}

int cli_output_commit(cli_output *out) { return cli_outputs_commit(&out, 1); }

const char *cli_output_reason(const cli_output *out, const char *msg) {
  size_t n = out->write_path ? strlen(out->write_path) : 0;
  if (n && !strncmp(msg, out->write_path, n) && msg[n] == ':' && msg[n + 1] == ' ') return msg + n + 2;
  return msg;
}

int cli_parse_seed(const char *s, uint64_t *out) {
  if (!s || !*s) return -1;
  for (const char *p = s; *p; p++)
    if (*p < '0' || *p > '9') return -1; /* decimal digits only: no sign, blanks, 1e3, 0x */
  char *end;
  errno = 0;
  unsigned long long v = strtoull(s, &end, 10);
  if (errno || *end || v > UINT64_MAX) return -1; /* ERANGE beyond 2^64 - 1 */
  *out = (uint64_t)v;
  return 0;
}

int cli_parse_comp(const char *s, int allow_integer, ics_comp_mode *mode) {
  if (!strcmp(s, "none"))
    *mode = ICS_COMP_NONE;
  else if (!strcmp(s, "nonneg"))
    *mode = ICS_COMP_NONNEG;
  else if (!strcmp(s, "signed"))
    *mode = ICS_COMP_SIGNED;
  else if (allow_integer && !strcmp(s, "integer"))
    *mode = ICS_COMP_INTEGER;
  else
    return -1;
  return 0;
}

/* the value of option o, given as `opt`: 0, or the exit status after the message */
static int option_value(const char *cmd, const cli_option *o, const char *opt, const char *v) {
  switch (o->kind) {
  case CLI_FLAG:
    *(int *)o->dest = 1;
    return 0;
  case CLI_FILE:
    if (!*v) return cli_error(cmd, "%s: empty file name", opt);
    /* fall through */
  case CLI_STRING:
    *(const char **)o->dest = v;
    return 0;
  case CLI_FINITE:
  case CLI_VARIANCE:
    return cli_option_double(cmd, opt, v, o->kind == CLI_VARIANCE, o->dest) ? 2 : 0;
  case CLI_INT:
    return cli_parse_int(v, o->lo, o->hi, o->dest)
               ? cli_error(cmd, "%s: expected an integer in %ld..%ld, got '%s'", opt, o->lo, o->hi,
                           v)
               : 0;
  case CLI_SEED:
    return cli_parse_seed(v, o->dest)
               ? cli_error(cmd, "%s: expected " CLI_SEED_RANGE ", got '%s'", opt, v)
               : 0;
  case CLI_CALL:
    return o->parse(cmd, opt, v, o->dest);
  }
  return cli_error(cmd, "%s: unknown option kind %d", opt, (int)o->kind);
}

static const cli_option *find_option(const cli_option *opts, int nopts, const char *arg) {
  for (int k = 0; k < nopts; k++) {
    const cli_option *o = &opts[k];
    if (o->name && (!strcmp(arg, o->name) || (o->alias && !strcmp(arg, o->alias)))) return o;
  }
  return NULL;
}

int cli_parse_options(const char *cmd, int argc, char **argv, int first, const cli_option *opts,
                      int nopts) {
  const cli_option *positional = NULL;
  for (int k = 0; k < nopts; k++)
    if (!opts[k].name) positional = &opts[k];
  unsigned char seen[256] = {0}; /* options given so far, by table index */
  for (int i = first; i < argc; i++) {
    const char *arg = argv[i], *opt = arg, *value = arg;
    const cli_option *o = find_option(opts, nopts, arg);
    if (!o) {
      if (arg[0] == '-' && arg[1])
        return cli_error(cmd, "unknown option '%s' (see icshadow %s --help)", arg, cmd);
      if (!positional)
        return cli_error(cmd, "unexpected argument '%s' (see icshadow %s --help)", arg, cmd);
      o = positional;
      opt = NULL;
    } else if (o->kind != CLI_FLAG) {
      if (i + 1 >= argc) return cli_error(cmd, "%s: missing value", arg);
      value = argv[++i];
    }
    if (opt && o - opts < (long)sizeof seen && seen[o - opts]++)
      return cli_error(cmd, "%s given twice: give each option once", arg);
    if (o->given) ++*o->given;
    int rc = option_value(cmd, o, opt, value);
    if (rc) return rc;
  }
  return 0;
}
