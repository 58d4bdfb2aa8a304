/* The machine's load averages, printed beside every benchmark's figures:
 * timings on a shared machine are comparable only at similar load. */
#include <stdio.h>
#include "sessile/load.h"

int sessile_load_average(double load[3]) {
  load[0] = load[1] = load[2] = -1;
  FILE *f = fopen("/proc/loadavg", "r");
  if (!f) return 0;
  int ok = fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) == 3;
  fclose(f);
  if (!ok) load[0] = load[1] = load[2] = -1;
  return ok;
}
