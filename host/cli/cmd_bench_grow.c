/* `sessile bench grow`: runs N iterations of a preset without writing files,
 * once with the multigrid nutrient solve and once with Jacobi-PCG (the
 * baseline, in the same process), and prints the time of each stage, its
 * share of the total and the ratios. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "sessile/bench/bench.h"
#include "sessile/growth/grow.h"

static const char *help =
    "usage: sessile bench grow [--preset radiate|crella] [--iterations N] [--seed N]\n"
    "                          [--set KEY=VALUE]... [--device D]\n"
    "\n"
    "Runs N growth iterations (default 50) of a preset with no output files, twice:\n"
    "with the nutrient solved by multigrid-preconditioned CG (nutrient_pc_type = mg,\n"
    "the default) and by Jacobi-PCG (the baseline), and prints per stage (upload,\n"
    "classify, nutrient, growth, remesh) the total and per-iteration time and its\n"
    "share of the run, the box node count, the nutrient solver iterations, and the\n"
    "ratios multigrid / Jacobi-PCG.  The processor and load average are printed first.\n"
    "Figures are for the record (docs/performance.md), never pass/fail.\n";

int cmd_bench_grow(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  sessile_grow_options o;
  sessile_grow_options_default(&o);
  o.every = 0;
  o.slices = "";
  o.fields = 0;
  const char *preset = "crella";
  sessile_grow_params p;
  const char **sets = calloc((size_t)argc + 1, sizeof *sets);
  if (!sets) {
    fprintf(stderr, "sessile bench grow: error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int nsets = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    unsigned u;
    if (cli_stray_value("bench grow", argv, i)) { free(sets); return EXIT_USAGE; }
    int r = cli_gpu_option("bench grow", argc, argv, &i, &go);
    if (r < 0) { free(sets); return EXIT_USAGE; }
    if (r > 0) continue;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      fputs(help, stdout);
      free(sets);
      return EXIT_OK;
    }
    if (strcmp(a, "--preset") && strcmp(a, "--set") && strcmp(a, "--iterations") && strcmp(a, "--seed")) {
      free(sets);
      return cli_usage_error("bench grow", "unknown option '%.60s'", a);
    }
    const char *v = cli_value("bench grow", argc, argv, &i);
    if (!v || (strcmp(a, "--set") && cli_once("bench grow", a, a))) { free(sets); return EXIT_USAGE; }
    if (!strcmp(a, "--preset")) preset = v;
    else if (!strcmp(a, "--set")) sets[nsets++] = v;
    else {
      if (cli_parse_uint("bench grow", a, v, a[2] == 'i' ? 1 : 0, 100000000, &u)) { free(sets); return EXIT_USAGE; }
      if (a[2] == 'i') o.iterations = (int)u;
      else o.seed = u;
    }
  }
  sessile_status s = sessile_params_preset(&p, preset);
  for (int k = 0; s == SESSILE_OK && k < nsets; k++) s = cli_params_set_kv(&p, sets[k]);
  free(sets);
  if (s == SESSILE_OK) s = sessile_params_validate(&p);
  if (s != SESSILE_OK) return cli_fail(s);
  o.preset = preset;
  sessile_gpu *g = NULL;
  s = cli_gpu_create(&go, &g);
  sessile_grow_summary sum[2];
  static const char *const solver_name[2] = {"multigrid", "jacobi-pcg"};
  if (s == SESSILE_OK) {
    const sessile_gpu_info *gi = sessile_gpu_info_of(g);
    char cpu[256];
    printf("machine: %s\n", sessile_cpu_describe(cpu, sizeof cpu));
    double load[3];
    sessile_load_average(load);
    printf("sessile bench grow: device %s (%s), driver %s, fp%d; load average %.2f %.2f %.2f\n",
           gi->name, gi->type, gi->driver, gi->precision, load[0], load[1], load[2]);
    printf("preset %s, %d iterations, seed %llu\n", preset, o.iterations, (unsigned long long)o.seed);
    fflush(stdout);
    for (int k = 0; k < 2 && s == SESSILE_OK; k++) {
      p.nutrient_pc_type = k == 0 ? SESSILE_SOLVER_MG : SESSILE_SOLVER_JACOBI;
      s = sessile_grow_run(g, &p, &o, NULL, &sum[k]);
    }
  }
  sessile_gpu_destroy(g);
  if (s != SESSILE_OK) return cli_fail(s);
  for (int k = 0; k < 2; k++) {
    printf("\n%s: box nodes %u; final surface %u vertices, %u triangles; nutrient iterations %ld "
           "(worst true relres %.2e)\n", solver_name[k], sum[k].box_nodes, sum[k].final_vertices,
           sum[k].final_triangles, sum[k].solver_iterations, sum[k].worst_relres);
    printf("%-10s %10s %14s %8s\n", "stage", "total s", "per iter ms", "share");
    double staged = 0;
    for (int q = 0; q < SESSILE_STAGE_COUNT; q++) staged += sum[k].stage_seconds[q];
    int its = sum[k].iterations ? sum[k].iterations : 1;
    for (int q = 0; q < SESSILE_STAGE_COUNT; q++)
      printf("%-10s %10.2f %14.1f %7.1f%%\n", sessile_grow_stage_name(q), sum[k].stage_seconds[q],
             1e3 * sum[k].stage_seconds[q] / its, staged > 0 ? 100 * sum[k].stage_seconds[q] / staged : 0);
    printf("%-10s %10.2f %14.1f\n", "run", sum[k].total_seconds, 1e3 * sum[k].total_seconds / its);
  }
  int nut = 0;
  while (nut < SESSILE_STAGE_COUNT && strcmp(sessile_grow_stage_name(nut), "nutrient")) nut++;
  double a = nut < SESSILE_STAGE_COUNT ? sum[0].stage_seconds[nut] : 0;
  double b = nut < SESSILE_STAGE_COUNT ? sum[1].stage_seconds[nut] : 0;
  printf("\nmultigrid / jacobi-pcg: nutrient stage %.3f (%.2f s / %.2f s), nutrient iterations "
         "%.3f (%ld / %ld), whole run %.3f\n", b > 0 ? a / b : 0, a, b,
         sum[1].solver_iterations ? (double)sum[0].solver_iterations / sum[1].solver_iterations : 0,
         sum[0].solver_iterations, sum[1].solver_iterations,
         sum[1].total_seconds > 0 ? sum[0].total_seconds / sum[1].total_seconds : 0);
  return EXIT_OK;
}
