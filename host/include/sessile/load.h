/* sessile — the machine's load averages, printed beside every benchmark's
 * figures (host/load.c; the base, below every layer). */
#ifndef SESSILE_LOAD_H
#define SESSILE_LOAD_H
/* The 1, 5 and 15 minute load averages (/proc/loadavg); -1s when
 * unavailable. */
int sessile_load_average(double load[3]);
#endif
