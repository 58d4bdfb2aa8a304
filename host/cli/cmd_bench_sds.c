/* `sessile bench sds`: the SDS physics step (forces, contacts, integration)
 * on the device against its plain-C reference at icosphere levels 2-5, and
 * the Figure 9 model (rock) through the loop against the paper's 5.7
 * minutes.  Figures, never pass/fail. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "sessile/bench/bench.h"
#include "sessile/sds/sds.h"

static const char *help =
    "usage: sessile bench sds [--rock-t T] [--repeat N] [--mass-scaling H] [--no-physics] [--kernels]\n"
    "                         [--device D]\n"
    "\n"
    "Times the SDS physics step (edge and volume springs, damping, contacts\n"
    "through per-cell lists, integration) for TetGen imports of icosphere\n"
    "levels 2-5 and for the Figure 9 body over its rock: milliseconds per step\n"
    "on the device (a plain step, and the loop's step with the stable-step\n"
    "bound computed in its submission) and by the plain-C reference, their\n"
    "ratio, the contacts' share and one build of the contact lists (medians of\n"
    "5 repeats).  Then\n"
    "runs the Figure 9 model (rock, Porter & McCormack: 5.7 minutes on a\n"
    "dual-core 2 GHz PC) twice, frames on, each into a temporary run\n"
    "directory, to simulated time T (default 1; 400 is the model's whole run,\n"
    "1-2.3 minutes a loop on lavapipe with 2 cores in 2026-12): through the\n"
    "host-driven loop, then through the loop on the device (device_loop: steps in\n"
    "batches, the rules too, with the generated rules kernel; the same steps), each\n"
    "with its wall time, ms per step, us per cell-step and submissions, then their\n"
    "ratio; short of 400 the time of the whole run is extrapolated, and labelled\n"
    "so.  The processor is printed first, the load before and after each.\n"
    "Figures are for the record (docs/performance.md), never pass/fail.\n"
    "\n"
    "  --rock-t T      simulated time of the rock run, 0 < T <= 400 (0: skip it)\n"
    "  --repeat N      make the rock runs N times (1-9, default 1), the loops alternating, then\n"
    "                  print each loop's median and minimum wall and the median of the ratios\n"
    "                  (this machine's speed drifts: one run's wall is one draw of it)\n"
    "  --mass-scaling H  a third rock run: the host-driven loop with mass_scaling_dt H (0 < H <= 1 s;\n"
    "                  another trajectory: its steps, cells and ratio to the run without;\n"
    "                  docs/sds.md, \"Mass scaling\")\n"
    "  --no-physics    skip the per-step table\n"
    "  --kernels       after the rock runs, the device time of each kernel in them (timestamps\n"
    "                  around every dispatch: calls, total, per call, share of the wall time);\n"
    "                  the rest of the wall time is the host's work and the submissions\n";

int cmd_bench_sds(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  double rock_t = 1, mass_dt = 0;
  int physics = 1, kernels = 0;
  unsigned repeat = 1;
  for (int i = 1; i < argc; i++) {
    if (cli_stray_value("bench sds", argv, i)) return EXIT_USAGE;
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    if (!strcmp(argv[i], "--no-physics")) {
      physics = 0;
      continue;
    }
    if (!strcmp(argv[i], "--kernels")) {
      kernels = 1;
      continue;
    }
    if (!strcmp(argv[i], "--rock-t")) {
      const char *v = cli_value("bench sds", argc, argv, &i);
      if (!v || cli_once("bench sds", "--rock-t", "--rock-t") || cli_parse_double("bench sds", "--rock-t", v, 0, 400, &rock_t))
        return EXIT_USAGE;
      continue;
    }
    if (!strcmp(argv[i], "--repeat")) {
      const char *v = cli_value("bench sds", argc, argv, &i);
      if (!v || cli_once("bench sds", "--repeat", "--repeat") ||
          cli_parse_uint("bench sds", "--repeat", v, 1, SESSILE_SDS_BENCH_REPEAT_MAX, &repeat))
        return EXIT_USAGE;
      continue;
    }
    if (!strcmp(argv[i], "--mass-scaling")) {
      const char *v = cli_value("bench sds", argc, argv, &i);
      if (!v || cli_once("bench sds", "--mass-scaling", "--mass-scaling") ||
          cli_parse_double("bench sds", "--mass-scaling", v, 0, 1, &mass_dt))
        return EXIT_USAGE;
      if (!(mass_dt > 0)) return cli_usage_error("bench sds", "--mass-scaling needs a step H > 0");
      continue;
    }
    int r = cli_gpu_option("bench sds", argc, argv, &i, &go);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error("bench sds", "unknown option '%.60s'", argv[i]);
  }
  if (mass_dt > 0 && !(rock_t > 0))
    return cli_usage_error("bench sds", "--mass-scaling adds a rock run: give --rock-t T > 0 with it");
  if (repeat > 1 && !(rock_t > 0))
    return cli_usage_error("bench sds", "--repeat repeats the rock runs: give --rock-t T > 0 with it");
  if (kernels && !(rock_t > 0))
    return cli_usage_error("bench sds", "--kernels times the rock run: give --rock-t T > 0 with it");
  char cpu[256];
  printf("machine: %s\n", sessile_cpu_describe(cpu, sizeof cpu));
  double load[3];
  sessile_load_average(load);
  printf("load average: %.2f %.2f %.2f\n", load[0], load[1], load[2]);
  sessile_gpu *g = NULL;
  sessile_status s = cli_gpu_create(&go, &g);
  if (s == SESSILE_OK && physics) s = sessile_sds_bench_physics(g, stdout);
  if (s == SESSILE_OK && kernels && rock_t > 0) s = sessile_gpu_profile(g, 1);
  double t0 = sessile_wall_seconds();
  /* SIGINT/SIGTERM: the rock run stops at its next step and its temporary folder goes */
  volatile sig_atomic_t *stop = cli_stop_flag_install();
  const char *tmp = getenv("TMPDIR"); /* the rock run's scratch folder */
  if (s == SESSILE_OK && rock_t > 0)
    s = sessile_sds_bench_rock(g, rock_t, mass_dt, repeat, tmp && *tmp ? tmp : "/tmp", stop, stdout);
  if (s == SESSILE_OK && kernels && rock_t > 0) cli_print_kernels(g, "the rock run", sessile_wall_seconds() - t0);
  sessile_gpu_destroy(g);
  if (s == SESSILE_ERR_INTERRUPTED) {
    fprintf(stderr, "sessile bench sds: interrupted (signal %d)\n", (int)*stop);
    return cli_signal_exit_code((int)*stop);
  }
  return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
}
