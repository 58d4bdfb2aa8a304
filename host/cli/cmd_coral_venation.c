/* `sessile coral venation`: soft corals by open or closed venation
 * (sessile/venation.h, docs/venation.md) on the shared generator options and
 * run directory (cli_run.h). */
#include <stdio.h>
#include <string.h>
#include "cli_run.h"
#include "sessile/venation.h"

#define CMD "coral venation"

static const char *help =
    "usage: sessile coral venation [--config FILE.json]... [--set KEY=VALUE]... [--seed N]\n"
    "                              [--iterations N] [--every K] [--out DIR] [--force] [--print-config]\n"
    "                              [--device D]\n"
    "       sessile coral venation --resume DIR [--iterations N]\n"
    "\n"
    "Soft corals by leaf venation in 3-D (Coralize Section 3.2, after Runions et al. 2005):\n"
    "auxins thrown per iteration into a leaf blade bounded by two Bezier curves that widens\n"
    "every iteration (or into a 3-D box: planar=false) attract vein nodes, which grow toward\n"
    "them; open venation (open=true) grows a tree, closed venation rejoins veins.  Veins\n"
    "thicken with their thickness index (a thickness curve) and are meshed as tubes.\n"
    "Writes coral/iter_NNNN.ply every K iterations and at the last, coral/final.ply and\n"
    "coral/final.obj (PLY: per-vertex thickness_index), manifest.json, records.jsonl and a\n"
    "checkpoint at each snapshot (docs/run.md).  Parameters, units and the paper's names:\n"
    "--print-config.\n"
    "\n"
    "  --seed N        seed of the auxins' placement, 0..2^64-1 (default 1)\n"
    "  --iterations N  iterations (default 60)      --every K  snapshot interval (default 20)\n"
    "  --out DIR       run directory (default runs/coral-venation); must be new or empty\n"
    "  --force         replace the earlier run in DIR     --resume DIR  continue it\n"
    "  --no-preview    no preview.png at the end of the run (docs/render.md)\n"
    "  --device D      the device of the nearest-node search (search=gpu)\n"
    "Exit codes: 0 success, 1 runtime failure, 2 bad usage or input, 130/143 interrupted.\n";

static int fail(sessile_status s) {
  char msg[1100];
  snprintf(msg, sizeof msg, "%s", sessile_error_message());
  fprintf(stderr, "sessile " CMD ": error: %s\n", msg);
  return s == SESSILE_ERR_USAGE ? EXIT_USAGE : EXIT_RUNTIME;
}

/* Refuse what cannot fit before anything is written: at most
 * iterations x auxins_per_iteration auxins live at once (24 bytes each, and
 * the search's 40 bytes of work per auxin). */
static sessile_status check_size(const sessile_venation_params *p, int iterations) {
  SESSILE_CHECK(iterations >= 1, SESSILE_ERR_USAGE, "--iterations 0: a venation run grows its veins in iterations (1 or more)");
  double aux = (double)iterations * p->auxins_per_iteration;
  SESSILE_CHECK(aux <= 5e7, SESSILE_ERR_USAGE,
                "%d iterations x %d auxins per iteration could hold %.3g auxins (about %.1f GB): at most 5e7",
                iterations, p->auxins_per_iteration, aux, aux * 64e-9);
  return SESSILE_OK;
}

static int venation_main(int argc, char **argv, const cli_gpu_opts *global, cli_run_args *a) {
  cli_gpu_opts go = *global;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    int r = cli_gpu_option(CMD, argc, argv, &i, &go);
    if (r == 0) r = cli_run_option(CMD, argc, argv, &i, a);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error(CMD, "unknown option '%.60s'", argv[i]);
  }
  int rc = cli_run_args_check(CMD, a);
  if (rc >= 0) return rc;
  sessile_venation_params p;
  sessile_venation_options o = {.seed = a->seed, .iterations = a->iterations, .every = a->every};
  sessile_params_defaults(&sessile_venation_param_table, &p);
  sessile_status s = SESSILE_OK;
  if (!a->resume) {
    s = cli_run_apply_params(&sessile_venation_param_table, &p, a);
    if (s == SESSILE_OK) s = sessile_params_check(&sessile_venation_param_table, &p);
    if (s == SESSILE_OK) s = check_size(&p, a->iterations);
    if (s != SESSILE_OK) return fail(s);
    if (a->print_config) {
      s = sessile_params_print(&sessile_venation_param_table, &p, stdout);
      return s == SESSILE_OK ? EXIT_OK : fail(s);
    }
  }
  if ((s = cli_gpu_check(&go)) != SESSILE_OK) return fail(s); /* an unknown --device: before any file */
  const char *dir = a->resume ? a->resume : a->out ? a->out : "runs/coral-venation";
  volatile sig_atomic_t *stop = cli_stop_flag_install();
  sessile_run *run = NULL;
  sessile_gpu *g = NULL;
  s = cli_run_open(CMD, argc, argv, a, dir, stop, &run);
  if (s == SESSILE_OK && a->resume) {
    s = sessile_venation_config_read(sessile_run_config(run), &p, &o);
    if (a->have_iterations) o.iterations = a->iterations;
    if (s == SESSILE_OK) s = check_size(&p, o.iterations);
  }
  if (s == SESSILE_OK) {
    cJSON *cfg = sessile_venation_config(&p, &o);
    if (!cfg) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    else s = sessile_run_set_config(run, cfg);
  }
  /* the device only when a kernel needs it */
  if (s == SESSILE_OK && (p.search == SESSILE_VENATION_GPU || p.geometry == SESSILE_VENATION_WELD))
    s = cli_gpu_create(&go, &g);
  if (s == SESSILE_OK) cli_run_note_device(run, g);
  int done = 0;
  o.run = run, o.gpu = g;
  if (s == SESSILE_OK) s = sessile_venation_run(&p, &o, &done);
  if (s == SESSILE_OK) cli_run_preview(CMD, a, run, "coral/final.ply", g, &go);
  s = sessile_run_close(run, s);
  sessile_gpu_destroy(g);
  if (s == SESSILE_OK && !a->quiet) printf("coral venation: %d iterations; run in %s\n", done, dir);
  if (s != SESSILE_OK && s != SESSILE_ERR_INTERRUPTED) return fail(s);
  return cli_run_exit(CMD, s, dir, stop, done);
}

int cmd_coral_venation(int argc, char **argv, const cli_gpu_opts *global) {
  cli_run_args a;
  if (cli_run_args_init(&a, argc, 1, 60, 20) != 0) {
    cli_run_args_free(&a);
    fprintf(stderr, "sessile " CMD ": error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int rc = venation_main(argc, argv, global, &a);
  cli_run_args_free(&a);
  return rc;
}
