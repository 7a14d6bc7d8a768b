/* tempfiles.c — temporary files removed when the process is interrupted: cli_output registers
 * each temporary it creates (and the names the EXR writer derives from it), and SIGINT, SIGTERM,
 * SIGHUP and SIGQUIT unlink every registered name before the signal takes its default course (a
 * signal the caller ignores stays ignored). The handler calls only unlink, signal and raise
 * (async-signal-safe); the names are copied into fixed slots when registered. */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"

#define SLOTS 64
#define NAME 4352

static char names[SLOTS][NAME];
static volatile sig_atomic_t used[SLOTS];
static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

static void on_signal(int sig) {
  for (int i = 0; i < SLOTS; i++)
    if (used[i]) unlink(names[i]);
  signal(sig, SIG_DFL);
  raise(sig);
}

static void install(void) {
  static int done;
  if (done) return;
  done = 1;
  for (size_t k = 0; k < sizeof sigs / sizeof *sigs; k++) {
    struct sigaction old, sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    if (sigaction(sigs[k], NULL, &old) == 0 && old.sa_handler != SIG_IGN) sigaction(sigs[k], &sa, NULL);
  }
}

static void add(const char *path) {
  if (strlen(path) >= NAME) return;
  for (int i = 0; i < SLOTS; i++)
    if (!used[i]) {
      memcpy(names[i], path, strlen(path) + 1);
      used[i] = 1;
      return;
    }
}

void cli_temp_register(const char *path) {
  install();
  add(path);
  /* the EXR writer's own temporaries for this file (libicshadow/src/exr.c: TARGET.tmpPID-N) */
  char derived[NAME];
  for (unsigned n = 0; n < 4; n++)
    if (snprintf(derived, sizeof derived, "%s.tmp%ld-%u", path, (long)getpid(), n) < NAME) add(derived);
}

void cli_temp_forget(const char *path) {
  size_t n = strlen(path);
  for (int i = 0; i < SLOTS; i++)
    if (used[i] && !strncmp(names[i], path, n) && (names[i][n] == 0 || names[i][n] == '.')) used[i] = 0;
}
