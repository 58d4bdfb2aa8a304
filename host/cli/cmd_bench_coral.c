/* `sessile bench coral` and `sessile bench sponge`: the coral and
 * particle-sponge generators' heavy steps, each on the device and by its plain-C reference in the same run
 * (ratios), with the machine's load.  Figures, never pass/fail. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "sessile/bench/bench.h"

static const char *coral_help =
    "usage: sessile bench coral [lsystem|weld|venation]... [--quick] [--device D]\n"
    "\n"
    "Times, each beside its plain-C reference in the same run:\n"
    "  lsystem    1 M turtle modules derived, interpreted and meshed as tubes\n"
    "  weld       the welded surface of a 10 k-segment coral on a 256^3 grid\n"
    "  venation   one venation iteration: nearest vein node for 10 k auxins among 100 k nodes\n"
    "With no names, all three.  --quick: small sizes (a smoke run).\n"
    "Figures are for the record (docs/performance.md), never pass/fail.\n";

static const char *sponge_help =
    "usage: sessile bench sponge [particles] [--quick] [--device D]\n"
    "\n"
    "Times, beside its plain-C reference in the same run:\n"
    "  particles  one particle-sponge (sponge particles) collision pass with 100 k particles\n"
    "--quick: small sizes (a smoke run).\n"
    "Figures are for the record (docs/performance.md), never pass/fail.\n";

/* A benchmark of named sections: the names given (all when none), each a
 * function of the device, run in order; the load first. */
static int bench_sections(const char *cmd, const char *help, int n, const char *const *names,
                          bench_section_fn *const *fn, int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  bench_section_opts o = {0};
  int want[8] = {0}, any = 0;
  for (int i = 1; i < argc; i++) {
    if (cli_stray_value(cmd, argv, i)) return EXIT_USAGE;
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    int r = cli_gpu_option(cmd, argc, argv, &i, &go);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (!strcmp(argv[i], "--quick")) {
      o.quick = 1;
      continue;
    }
    int k = 0;
    while (k < n && strcmp(argv[i], names[k])) k++;
    if (k == n) return cli_usage_error(cmd, "unknown option or section '%.60s'", argv[i]);
    want[k] = any = 1;
  }
  for (int k = 0; k < n && !any; k++) want[k] = 1;
  char cpu[256];
  printf("machine: %s\n", sessile_cpu_describe(cpu, sizeof cpu));
  double load[3];
  sessile_load_average(load);
  printf("load average: %.2f %.2f %.2f\n", load[0], load[1], load[2]);
  sessile_gpu *g = NULL;
  sessile_status s = cli_gpu_create(&go, &g);
  for (int k = 0; k < n && s == SESSILE_OK; k++)
    if (want[k]) s = fn[k](g, &o, stdout);
  sessile_gpu_destroy(g);
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}

int cmd_bench_coral(int argc, char **argv, const cli_gpu_opts *global) {
  static const char *const names[] = {"lsystem", "weld", "venation"};
  static bench_section_fn *const fn[] = {bench_coral_lsystem, bench_coral_weld, bench_coral_venation};
  return bench_sections("bench coral", coral_help, 3, names, fn, argc, argv, global);
}

int cmd_bench_sponge(int argc, char **argv, const cli_gpu_opts *global) {
  static const char *const names[] = {"particles"};
  static bench_section_fn *const fn[] = {bench_sponge_particles};
  return bench_sections("bench sponge", sponge_help, 1, names, fn, argc, argv, global);
}
