/* commands.h — the icshadow subcommands (one file each) and the helpers they share. */
#ifndef ICS_CLI_COMMANDS_H
#define ICS_CLI_COMMANDS_H

#include <stdint.h>
#include <stdio.h>

#include "icshadow.h"

/* Each subcommand gets argv[0] = its own name; returns the process exit status
 * (0 ok, 1 runtime failure, 2 usage / bad input). */
int cmd_eval(int argc, char **argv);
int cmd_kernel(int argc, char **argv);
int cmd_lut(int argc, char **argv);
int cmd_isoline(int argc, char **argv);
int cmd_clt(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_iterate(int argc, char **argv);
int cmd_kernel_table(int argc, char **argv);
int cmd_make_env(int argc, char **argv);
int cmd_fit_light(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_plan(int argc, char **argv);

/* `icshadow bench KIND`: one function per peer primitive (bench_<kind>.c), argv[0] = KIND. */
int bench_sat2d(int argc, char **argv);
int bench_sat3d(int argc, char **argv);
int bench_minmax(int argc, char **argv);
int bench_occtex(int argc, char **argv);
int bench_slab(int argc, char **argv);
int bench_frame(int argc, char **argv);

/* Reports on stderr, one line each: "icshadow CMD: message" (cmd: the subcommand as typed after
 * "icshadow", e.g. "make-env" or "bench sat2d"; NULL for the tool itself: "icshadow: message").
 * cli_report returns `status`, so a command can end with `return cli_error(...)`:
 *   cli_error         2, bad input / usage
 *   cli_failure       1, a runtime failure
 *   cli_status_error  1 when st is ICS_ERR_NOMEM, else 2 (a library call failed with st)
 *   cli_warning       "icshadow CMD: warning: message" (the format must be a string literal) */
#if defined(__GNUC__)
#define CLI_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CLI_PRINTF(f, a)
#endif
int cli_report(int status, const char *cmd, const char *fmt, ...) CLI_PRINTF(3, 4);
#define cli_error(cmd, ...) cli_report(2, cmd, __VA_ARGS__)
#define cli_failure(cmd, ...) cli_report(1, cmd, __VA_ARGS__)
#define cli_status_error(cmd, st, ...) cli_report((st) == ICS_ERR_NOMEM ? 1 : 2, cmd, __VA_ARGS__)
#define cli_warning(cmd, ...) ((void)cli_report(0, cmd, "warning: " __VA_ARGS__))
/* a command of the renderer in a build without it */
#define cli_no_renderer(cmd)                                                                       \
  cli_failure(cmd, "the renderer was not built (it needs jansson: install libjansson-dev and "     \
                   "rebuild)")

/* Strict number parsing: the whole string must be a number (leading/trailing blanks allowed).
 * Return 0 on success, -1 otherwise. */
int cli_parse_double(const char *s, double *out);
int cli_parse_int(const char *s, long lo, long hi, int *out);
/* A seed: a decimal integer in 0..2^64 - 1 (digits only; overflow is an error). 0 or -1. */
int cli_parse_seed(const char *s, uint64_t *out);
#define CLI_SEED_RANGE "a non-negative integer in 0..18446744073709551615 (decimal digits)"

/* Size of an error-message buffer that names a file: a PATH_MAX (4096) path, a JSON location
 * and the explanation fit without truncation. */
#define CLI_MSG_MAX 8192

/* An option's number for subcommand `cmd`: finite, and >= 0 when `variance` is set. Returns 0,
 * or -1 after "icshadow CMD: OPT: not a number: 'S'" (or "NaN is not allowed", "negative
 * variance S (must be >= 0)", "must be finite, got 'S'", checked in that order) on stderr. */
int cli_option_double(const char *cmd, const char *opt, const char *s, int variance, double *out);

/* Exactly n comma-separated finite numbers in [s, end) (end NULL: to the end of s), a part of
 * the option value `spec` (positions in messages count from spec's first character, 1-based).
 * Returns 0, or -1 after "icshadow CMD: OPT: " + "expected N comma-separated numbers at position
 * P of 'SPEC'" / "too many numbers at position P of 'SPEC'" / "not a number at position P of
 * 'SPEC'" / "NaN (or: infinite number) at position P of 'SPEC' (must be finite)" on stderr. */
int cli_parse_numbers(const char *cmd, const char *opt, const char *spec, const char *s,
                      const char *end, int n, double *v);

/* An interpolation-variance compensation mode by name: "none", "nonneg", "signed", and
 * "integer" when allow_integer is set. Returns 0, or -1 for an unknown name (the caller
 * reports it). */
int cli_parse_comp(const char *s, int allow_integer, ics_comp_mode *mode);

/* Table-driven options. Each command declares its options as a cli_option table and hands it
 * with argv to cli_parse_options, which reads argv[first..argc-1] in order: an argument that
 * is an option's name (or alias) takes the next argument as its value (CLI_FLAG takes none);
 * an argument that is no option (it does not start with '-', or is "-") goes to the table's
 * positional entry, the one with name NULL. Every problem is reported with the same wording:
 *   icshadow CMD: unknown option '--bogus' (see icshadow CMD --help)
 *   icshadow CMD: unexpected argument 'x' (see icshadow CMD --help)   (no positional entry)
 *   icshadow CMD: --varx: missing value
 *   icshadow CMD: --varx: not a number: 'abc'   (and the kinds' messages below)
 * A value is parsed as soon as it is read, so the first bad argument is the one reported. */
typedef enum cli_kind {
  CLI_FLAG,     /* no value: *(int *)dest = 1 */
  CLI_STRING,   /* *(const char **)dest = the value as given */
  CLI_FILE,     /* the same, a file name: "OPT: empty file name" when it is empty */
  CLI_FINITE,   /* *(double *)dest: finite (cli_option_double) */
  CLI_VARIANCE, /* *(double *)dest: finite and >= 0 (cli_option_double) */
  CLI_INT,      /* *(int *)dest in lo..hi: "OPT: expected an integer in LO..HI, got 'V'" */
  CLI_SEED,     /* *(uint64_t *)dest (cli_parse_seed): "OPT: expected " CLI_SEED_RANGE ... */
  CLI_CALL      /* parse(cmd, opt, value, dest): 0, or the exit status after its message */
} cli_kind;

typedef struct cli_option {
  const char *name;  /* "--varx"; NULL: the positional entry (CLI_STRING or CLI_CALL, opt NULL) */
  const char *alias; /* another spelling ("-o" beside "--output"), or NULL */
  cli_kind kind;
  void *dest;
  long lo, hi; /* CLI_INT: the accepted range */
  int (*parse)(const char *cmd, const char *opt, const char *value, void *dest); /* CLI_CALL */
  int *given;  /* optional: counts the times the option (or a positional argument) is given */
} cli_option;

/* Returns 0, or the exit status (2) after the message on stderr. */
int cli_parse_options(const char *cmd, int argc, char **argv, int first, const cli_option *opts,
                      int nopts);
#define CLI_NOPTS(table) ((int)(sizeof(table) / sizeof(table)[0]))

/* --cl-device D (a CLI_CALL parser) of the OpenCL primitives' benchmarks (bench sat, bench
 * minmax): their device, as ICS_CL_DEVICE (an index or a substring of "platform: device"),
 * which it sets for this process; an empty D is refused. The renderer's backends take theirs
 * as options (backend_options.h). */
int cli_parse_cl_device(const char *cmd, const char *opt, const char *value, void *dest);
#define CLI_CL_DEVICE_HELP \
  "  --cl-device D       OpenCL device: an index or part of \"platform: device\" (as ICS_CL_DEVICE)\n"

/* Seconds on the monotonic clock (CLOCK_MONOTONIC), for elapsed times. */
double cli_now_s(void);

/* splitmix64 (Steele, Lea, Flood 2014) on a caller's state: reproducible benchmark data.
 * cli_splitmix_unit: uniform in [0, 1) from the top 53 bits of the next word. */
uint64_t cli_splitmix64(uint64_t *state);
double cli_splitmix_unit(uint64_t *state);

/* Progress on stderr (docs/architecture.md "Contracts"): shown on a terminal (one line that
 * rewrites itself) or when asked for (--progress: one line per update), silent otherwise. */
typedef struct cli_progress {
  const char *who; /* e.g. "icshadow bench minmax" */
  int on, tty;
} cli_progress;
void cli_progress_init(cli_progress *p, const char *who, int forced);
void cli_progress_say(const cli_progress *p, const char *fmt, ...);
void cli_progress_done(const cli_progress *p);

/* Flush stdout; on failure print "icshadow CMD: cannot write stdout: <reason>" (cmd as for
 * cli_error) and return 1, else 0. */
int cli_stdout_failed(const char *cmd);

/* True when argv holds -h or --help. */
int cli_wants_help(int argc, char **argv);

/* Atomic output: write to a temporary file beside `path`, then rename on commit; abort (or a
 * failed commit) removes the temporary file, so no partial output is ever left behind.
 * path "-" means stdout (commit just flushes). A symbolic link is resolved first, so the file it
 * points to is replaced, not the link; a link to nothing gets the file it names created, through
 * a temporary file like any other. An existing target that is not a regular file (a device,
 * a FIFO) is written in place: renaming over it would replace it.
 * Writers that need a file name rather than a FILE * write to `write_path`: the temporary file,
 * or for an in-place target a private temporary file under $TMPDIR (or /tmp) whose bytes commit
 * copies into the target (so a library writer never opens a device or FIFO itself). */
typedef struct cli_output {
  FILE *fp;
  const char *cmd;        /* the subcommand, for messages (cli_error) */
  char *tmp_path;         /* the temporary file; NULL for stdout and for in-place targets */
  char *copy_path;        /* in-place targets: the private file copied in on commit, or NULL */
  char *target;           /* owned: where the result ends up (symbolic links resolved) */
  const char *path;       /* as given, for messages */
  const char *write_path; /* where the bytes go now: tmp_path, or the target itself */
} cli_output;
int cli_output_open(cli_output *out, const char *cmd, const char *path);
/* The name a chain of symbolic links ending nowhere leads to (each relative link resolved
 * against its own folder), malloc'd; NULL for a loop or a read error; path itself (a copy) when
 * nothing is there. */
char *cli_link_destination(const char *path);
/* A command's inputs and outputs by what they are ("the scene file", "-o") and path (NULL or
 * "-": none, or stdout). cli_check_outputs refuses (exit status 2, a message naming both) an
 * output that is the same file as an input (hard and symbolic links, other spellings) or as
 * another output, and two outputs on stdout (list what a command prints there as "-"); call it
 * before any work (cli/distinct_paths.c). */
typedef struct cli_path {
  const char *what, *path;
} cli_path;
int cli_check_outputs(const char *cmd, const cli_path *in, int nin, const cli_path *out, int nout);
/* A by-name writer's message (it starts with the path it was given, out->write_path: the
 * output's temporary file) without that prefix, for a message that names out->path instead. */
const char *cli_output_reason(const cli_output *out, const char *msg);
/* Temporary files removed if SIGINT, SIGTERM, SIGHUP or SIGQUIT ends the process
 * (cli/tempfiles.c); cli_output registers its own. forget also drops the names derived from path. */
void cli_temp_register(const char *path);
void cli_temp_forget(const char *path);
int cli_output_commit(cli_output *out); /* 0 on success; reports errors on stderr */
/* Commits several outputs of one command together: each is completed first (flushed, closed,
 * copied into an in-place target), and only when all are complete are the temporaries renamed
 * into place; when one cannot be completed, every temporary is removed and no file is replaced.
 * Put stdout first when a command prints too, so a failed stdout commits no file. */
int cli_outputs_commit(cli_output *const *outs, int n);
void cli_output_abort(cli_output *out);

#endif
