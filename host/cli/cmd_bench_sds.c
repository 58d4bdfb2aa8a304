/* `sessile bench sds`: the SDS physics step (forces and integration) on the
 * device against its plain-C reference in the same run, at about 1 k, 10 k
 * and 100 k cells.  Figures, never pass/fail. */
#include <stdio.h>
#include <string.h>
#include "cli.h"
#include "sessile/bench.h"
#include "sessile/sds.h"

static const char *help =
    "usage: sessile bench sds [--device D]\n"
    "\n"
    "Times the SDS physics step (edge and volume springs, damping, integration)\n"
    "for complexes of about 1 k, 10 k and 100 k cells (TetGen imports of a\n"
    "sphere): milliseconds per step on the device and by the plain-C reference,\n"
    "and their ratio, after the machine's load average.  The Figure 9 model's\n"
    "time against the paper's 5.7 minutes is not measured yet (docs/sds.md).\n"
    "Figures are for the record (docs/performance.md), never pass/fail.\n";

int cmd_bench_sds(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    int r = cli_gpu_option("bench sds", argc, argv, &i, &go);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error("bench sds", "unknown option '%.60s'", argv[i]);
  }
  double load[3];
  sessile_load_average(load);
  printf("load average: %.2f %.2f %.2f\n", load[0], load[1], load[2]);
  sessile_gpu *g = NULL;
  sessile_status s = cli_gpu_create(&go, &g);
  if (s == SESSILE_OK) s = sessile_sds_bench_physics(g, stdout);
  sessile_gpu_destroy(g);
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
