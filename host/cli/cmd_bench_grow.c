/* `sessile bench grow`: runs N iterations of a preset without writing files
 * and prints the time of each stage and its share of the total. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli.h"
#include "sessile/grow.h"

static const char *help =
    "usage: sessile bench grow [--preset radiate|crella] [--iterations N] [--seed N]\n"
    "                          [--set KEY=VALUE]... [--device D]\n"
    "\n"
    "Runs N growth iterations (default 50) of a preset with no output files and\n"
    "prints, per stage (upload, classify, nutrient, growth, remesh), the total and\n"
    "per-iteration time and its share of the run, the box node count and the\n"
    "nutrient solver iterations.  Figures are for the record (docs/performance.md),\n"
    "never pass/fail.\n";

int cmd_bench_grow(int argc, char **argv, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  sessile_grow_options o;
  sessile_grow_options_default(&o);
  o.every = 0;
  o.slices = "";
  o.fields = 0;
  const char *preset = "crella";
  sessile_params p;
  const char **sets = calloc((size_t)argc + 1, sizeof *sets);
  if (!sets) {
    fprintf(stderr, "sessile bench grow: error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int nsets = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    unsigned u;
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
      return cli_usage_error("bench grow", "unknown option '%s'", a);
    }
    const char *v = cli_value("bench grow", argc, argv, &i);
    if (!v) { free(sets); return EXIT_USAGE; }
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
  sessile_grow_summary sum;
  if (s == SESSILE_OK) {
    const sessile_gpu_info *gi = sessile_gpu_info_of(g);
    printf("sessile bench grow: device %s (%s), driver %s, fp%d\n", gi->name, gi->type, gi->driver,
           gi->precision);
    printf("preset %s, %d iterations, seed %llu\n", preset, o.iterations, (unsigned long long)o.seed);
    fflush(stdout);
    s = sessile_grow_run(g, &p, &o, NULL, &sum);
  }
  sessile_gpu_destroy(g);
  if (s != SESSILE_OK) return cli_fail(s);
  printf("box nodes %u; final surface %u vertices, %u triangles; nutrient PCG iterations %ld "
         "(worst true relres %.2e)\n\n",
         sum.box_nodes, sum.final_vertices, sum.final_triangles, sum.solver_iterations, sum.worst_relres);
  printf("%-10s %10s %14s %8s\n", "stage", "total s", "per iter ms", "share");
  double staged = 0;
  for (int k = 0; k < SESSILE_STAGE_COUNT; k++) staged += sum.stage_seconds[k];
  for (int k = 0; k < SESSILE_STAGE_COUNT; k++)
    printf("%-10s %10.2f %14.1f %7.1f%%\n", sessile_grow_stage_name(k), sum.stage_seconds[k],
           1e3 * sum.stage_seconds[k] / (sum.iterations ? sum.iterations : 1),
           staged > 0 ? 100 * sum.stage_seconds[k] / staged : 0);
  printf("%-10s %10.2f %14.1f\n", "run", sum.total_seconds,
         1e3 * sum.total_seconds / (sum.iterations ? sum.iterations : 1));
  return EXIT_OK;
}
