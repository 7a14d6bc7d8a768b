/* bench_stats.c — the benchmarks' repetition statistics and busy-machine rule (bench_stats.h). */
#include "bench_stats.h"

#include <stdlib.h>

#include "commands.h"

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

cli_spread cli_spread_of(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]); /* even n: the mean of two */
  return (cli_spread){v[0], median, v[n - 1]};
}

int cli_spread_busy(cli_spread s) { return s.max > 1.3 * s.min; }

void cli_warn_busy(const char *cmd, const char *columns) {
  cli_warning(cmd, "some repetitions differ by more than 30%% (%s): the machine was busy; rerun, "
              "or compare ratios measured in one run", columns);
}
