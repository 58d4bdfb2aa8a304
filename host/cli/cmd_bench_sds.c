/* `sessile bench sds`: the SDS physics step (forces, contacts, integration)
 * on the device against its plain-C reference at icosphere levels 2-5, and
 * the Figure 9 model (rock) through the loop against the paper's 5.7
 * minutes.  Figures, never pass/fail. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "sessile/bench.h"
#include "sessile/sds.h"

static const char *help =
    "usage: sessile bench sds [--rock-t T] [--no-physics] [--device D]\n"
    "\n"
    "Times the SDS physics step (edge and volume springs, damping, contacts\n"
    "through per-cell lists, integration) for TetGen imports of icosphere\n"
    "levels 2-5 and for the Figure 9 body over its rock: milliseconds per step\n"
    "on the device (a plain step, and the loop's step with the stable-step\n"
    "bound computed in its submission) and by the plain-C reference, their\n"
    "ratio, the contacts' share and one build of the contact lists (medians of\n"
    "5 repeats).  Then\n"
    "runs the Figure 9 model (rock, Porter & McCormack: 5.7 minutes on a\n"
    "dual-core 2 GHz PC) through the loop, frames on, into a temporary run\n"
    "directory, to simulated time T (default 1; 400 is the model's whole run,\n"
    "about 7 minutes on lavapipe with 2 cores); short of 400 the time of the\n"
    "whole run is extrapolated, and labelled so.  The load average is printed\n"
    "before.  Figures are for the record (docs/performance.md), never pass/fail.\n"
    "\n"
    "  --rock-t T      simulated time of the rock run, 0 < T <= 400 (0: skip it)\n"
    "  --no-physics    skip the per-step table\n";

int cmd_bench_sds(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  double rock_t = 1;
  int physics = 1;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    if (!strcmp(argv[i], "--no-physics")) {
      physics = 0;
      continue;
    }
    if (!strcmp(argv[i], "--rock-t")) {
      char *end = NULL;
      if (i + 1 >= argc) return cli_usage_error("bench sds", "--rock-t needs a value");
      rock_t = strtod(argv[++i], &end);
      if (!end || *end || !(rock_t >= 0 && rock_t <= 400))
        return cli_usage_error("bench sds", "--rock-t must be a number in 0..400 (got '%.60s')", argv[i]);
      continue;
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
  if (s == SESSILE_OK && physics) s = sessile_sds_bench_physics(g, stdout);
  if (s == SESSILE_OK && rock_t > 0) s = sessile_sds_bench_rock(g, rock_t, stdout);
  sessile_gpu_destroy(g);
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
