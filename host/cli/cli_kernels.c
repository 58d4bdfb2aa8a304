/* `--kernels` of the benchmarks: the device time of every kernel of what
 * ran under sessile_gpu_profile (timestamps around each dispatch), as a
 * table of calls, total, per call and share of the wall time. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"

/* Kernels by device time, dearest first. */
static int by_ms(const void *a, const void *b) {
  const sessile_kernel_time *p = a, *q = b;
  return (p->ms < q->ms) - (p->ms > q->ms);
}

void cli_print_kernels(sessile_gpu *g, const char *what, double wall_s) {
  const sessile_kernel_time *t = NULL;
  uint64_t untimed = 0;
  size_t n = sessile_gpu_profile_read(g, &t, &untimed);
  sessile_kernel_time *s = malloc((n ? n : 1) * sizeof *s);
  if (!s) return;
  memcpy(s, t, n * sizeof *s);
  qsort(s, n, sizeof *s, by_ms);
  double sum = 0;
  for (size_t i = 0; i < n; i++) sum += s[i].ms;
  printf("kernels of %s (device time from timestamps; wall %.1f s):\n", what, wall_s);
  printf("%-28s %10s %10s %10s %7s\n", "kernel", "calls", "total_s", "ms/call", "wall%");
  for (size_t i = 0; i < n; i++)
    printf("%-28s %10llu %10.2f %10.4f %6.1f%%\n", s[i].name, (unsigned long long)s[i].calls, 1e-3 * s[i].ms,
           s[i].calls ? s[i].ms / (double)s[i].calls : 0.0, wall_s > 0 ? 100 * 1e-3 * s[i].ms / wall_s : 0.0);
  printf("%-28s %10s %10.2f %10s %6.1f%%  (the rest: host work, transfers, submissions%s)\n", "all kernels", "",
         1e-3 * sum, "", wall_s > 0 ? 100 * 1e-3 * sum / wall_s : 0.0,
         untimed ? "; some dispatches untimed" : "");
  if (untimed)
    printf("(%llu dispatches past the %d timed per recording)\n", (unsigned long long)untimed, SESSILE_PROFILE_MAX);
  free(s);
}

