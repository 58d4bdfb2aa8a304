/* The machine's load averages and processor, printed beside every
 * benchmark's figures: timings on a shared machine are comparable only at
 * similar load and on the same processor. */
#include <stdio.h>
#include <string.h>
#include <unistd.h>
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

/* The value of a "key<tabs>: value" line of /proc/cpuinfo, newline cut. */
static int cpuinfo_value(const char *line, const char *key, char *val, size_t n) {
  size_t k = strlen(key);
  if (strncmp(line, key, k) != 0) return 0;
  const char *p = line + k;
  while (*p == ' ' || *p == '\t') p++;
  if (*p != ':') return 0;
  for (p++; *p == ' '; p++) {}
  snprintf(val, n, "%s", p);
  val[strcspn(val, "\n")] = 0;
  return 1;
}

char *sessile_cpu_describe(char *out, size_t n) {
  char name[128] = "", family[16] = "", model[16] = "", line[512];
  FILE *f = fopen("/proc/cpuinfo", "r");
  /* the first processor's block: every core of these machines is alike */
  while (f && fgets(line, sizeof line, f) && line[0] != '\n') {
    if (!name[0]) cpuinfo_value(line, "model name", name, sizeof name);
    if (!family[0]) cpuinfo_value(line, "cpu family", family, sizeof family);
    if (!model[0]) cpuinfo_value(line, "model", model, sizeof model);
  }
  if (f) fclose(f);
  long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  if (name[0] && family[0] && model[0])
    snprintf(out, n, "%s (cpu family %s, model %s), %ld CPUs online", name, family, model, cpus);
  else if (name[0])
    snprintf(out, n, "%s, %ld CPUs online", name, cpus);
  else
    snprintf(out, n, "unknown processor, %ld CPUs online", cpus);
  return out;
}
