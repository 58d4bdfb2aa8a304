/* sessile — the machine's load averages and its processor, printed beside
 * every benchmark's figures (host/load.c; the base, below every layer). */
#ifndef SESSILE_LOAD_H
#define SESSILE_LOAD_H
#include <stddef.h>
/* The 1, 5 and 15 minute load averages (/proc/loadavg); -1s when
 * unavailable. */
int sessile_load_average(double load[3]);
/* The processor: "<model name> (cpu family F, model M), N CPUs online"
 * from /proc/cpuinfo, or "unknown processor, N CPUs online" where it says
 * nothing.  Two machines of one name can differ twofold in a benchmark's wall
 * time (docs/sds.md, "Benchmark"); the family and model tell them apart.
 * Writes at most n bytes (n > 0) and returns out. */
char *sessile_cpu_describe(char *out, size_t n);
#endif
