/* `sessile bench coral`: the coral and particle-sponge generators' heavy
 * steps, each on the device and by its plain-C reference in the same run
 * (ratios), with the machine's load.  Figures, never pass/fail. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "sessile/bench.h"

static const char *help =
    "usage: sessile bench coral [lsystem|weld|venation|particles]... [--quick] [--device D]\n"
    "\n"
    "Times, each beside its plain-C reference in the same run:\n"
    "  lsystem    1 M turtle modules derived, interpreted and meshed as tubes\n"
    "  weld       the welded surface of a 10 k-segment coral on a 256^3 grid\n"
    "  venation   one venation iteration: nearest vein node for 10 k auxins among 100 k nodes\n"
    "  particles  one particle-sponge iteration with 100 k particles\n"
    "With no names, all four.  --quick: small sizes (a smoke run).\n"
    "Figures are for the record (docs/performance.md), never pass/fail.\n";

int cmd_bench_coral(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  bench_coral_opts o = {0};
  int want[4] = {0, 0, 0, 0}, any = 0;
  static const char *names[4] = {"lsystem", "weld", "venation", "particles"};
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    int r = cli_gpu_option("bench coral", argc, argv, &i, &go);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (!strcmp(argv[i], "--quick")) {
      o.quick = 1;
      continue;
    }
    int k = 0;
    while (k < 4 && strcmp(argv[i], names[k])) k++;
    if (k == 4) return cli_usage_error("bench coral", "unknown option or section '%.60s'", argv[i]);
    want[k] = any = 1;
  }
  if (!any) want[0] = want[1] = want[2] = want[3] = 1;
  double load[3];
  sessile_load_average(load);
  printf("load average: %.2f %.2f %.2f\n", load[0], load[1], load[2]);
  sessile_gpu *g = NULL;
  sessile_status s = cli_gpu_create(&go, &g);
  sessile_status (*fn[4])(sessile_gpu *, const bench_coral_opts *, FILE *) = {
      bench_coral_lsystem, bench_coral_weld, bench_coral_venation, bench_coral_particles};
  for (int k = 0; k < 4 && s == SESSILE_OK; k++)
    if (want[k]) s = fn[k](g, &o, stdout);
  sessile_gpu_destroy(g);
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
