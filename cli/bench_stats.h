/* bench_stats.h — what every benchmark of the CLI reports of its repetitions (bench_stats.c):
 * the median with the minimum and the maximum, and the busy-machine rule (a spread of more than
 * 30 % between them), with one warning text. */
#ifndef ICS_CLI_BENCH_STATS_H
#define ICS_CLI_BENCH_STATS_H

typedef struct cli_spread {
  double min, median, max;
} cli_spread;

/* of the n > 0 values v (sorted in place) */
cli_spread cli_spread_of(double *v, int n);
/* 1 when the spread says the machine was busy: max > 1.3 min */
int cli_spread_busy(cli_spread s);
/* the warning on stderr, naming the columns compared (e.g. "ns_min vs ns_max") */
void cli_warn_busy(const char *cmd, const char *columns);

#endif
