/* `sessile sphere`: the smallest generator (sessile/sphere.h) on the shared
 * generator options and run directory (cli_run.h). */
#include <stdio.h>
#include <string.h>
#include "cli_run.h"
#include "sessile/sphere.h"

static const char *help =
    "usage: sessile sphere [--config FILE.json]... [--set KEY=VALUE]... [--seed N]\n"
    "                      [--iterations N] [--every K] [--out DIR] [--force] [--print-config]\n"
    "       sessile sphere --resume DIR [--iterations N]\n"
    "\n"
    "The smallest generator, and the run framework's own test: an icosphere (level,\n"
    "radius) whose vertices take a seeded radial random walk (noise) for N\n"
    "iterations.  Writes sphere/iter_NNNN.ply every K iterations and at the last,\n"
    "sphere/final.ply, manifest.json, records.jsonl and a checkpoint at each snapshot,\n"
    "exactly as every generator does (docs/run.md).  Parameters: --print-config.\n"
    "\n"
    "  --seed N        seed of the random walk, 0..2^64-1 (default 1)\n"
    "  --iterations N  iterations (default 10)      --every K  snapshot interval (default 5)\n"
    "  --out DIR       run directory (default runs/sphere); must be new or empty\n"
    "  --force         replace the earlier run in DIR     --resume DIR  continue it\n"
    "  --no-preview    no preview.png at the end of the run (docs/render.md)\n"
    "Exit codes: 0 success, 1 runtime failure, 2 bad usage or input, 130/143 interrupted.\n";

static int sphere_main(int argc, char **argv, cli_run_args *a) {
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    /* device options are accepted everywhere (sessile --help says so); the
     * sphere needs no device and ignores them */
    cli_gpu_opts ignored = {0};
    int r = cli_gpu_option("sphere", argc, argv, &i, &ignored);
    if (r == 0) r = cli_run_option("sphere", argc, argv, &i, a);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error("sphere", "unknown option '%.60s'", argv[i]);
  }
  int rc = cli_run_args_check("sphere", a);
  if (rc >= 0) return rc;
  sessile_sphere_params p;
  sessile_sphere_options o = {.seed = a->seed, .iterations = a->iterations, .every = a->every};
  sessile_params_defaults(&sessile_sphere_param_table, &p);
  sessile_status s = SESSILE_OK;
  if (!a->resume) {
    s = cli_run_apply_params(&sessile_sphere_param_table, &p, a);
    if (s == SESSILE_OK) s = sessile_params_check(&sessile_sphere_param_table, &p);
    if (s != SESSILE_OK) return cli_fail(s);
    if (a->print_config) {
      s = sessile_params_print(&sessile_sphere_param_table, &p, stdout);
      return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
    }
  }
  const char *dir = a->resume ? a->resume : a->out ? a->out : "runs/sphere";
  volatile sig_atomic_t *stop = cli_stop_flag_install();
  sessile_run *run = NULL;
  s = cli_run_open("sphere", argc, argv, a, dir, stop, &run);
  if (s == SESSILE_OK && a->resume) {
    s = sessile_sphere_config_read(sessile_run_config(run), &p, &o);
    if (a->have_iterations) o.iterations = a->iterations;
  }
  if (s == SESSILE_OK) {
    cJSON *cfg = sessile_sphere_config(&p, &o);
    if (!cfg) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    else s = sessile_run_set_config(run, cfg);
  }
  int done = 0;
  o.run = run;
  if (s == SESSILE_OK) s = sessile_sphere_run(&p, &o, &done);
  if (s == SESSILE_OK) cli_run_preview("sphere", a, run, "sphere/final.ply", NULL, NULL);
  s = sessile_run_close(run, s);
  if (s == SESSILE_OK && !a->quiet) printf("sphere: %d iterations; run in %s\n", done, dir);
  return cli_run_exit("sphere", s, dir, stop, done);
}

int cmd_sphere(int argc, char **argv, const cli_gpu_opts *global) {
  (void)global;
  cli_run_args a;
  if (cli_run_args_init(&a, argc, 1, 10, 5) != 0) {
    cli_run_args_free(&a);
    fprintf(stderr, "sessile sphere: error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int rc = sphere_main(argc, argv, &a);
  cli_run_args_free(&a);
  return rc;
}
