/* `sessile sponge particles`: Coralize's particle-fed sponge
 * (sessile/particle_sponge.h, docs/particle_sponge.md) on the shared
 * generator options and run directory (cli_run.h). */
#include <stdio.h>
#include <string.h>
#include "cli_run.h"
#include "sessile/particle_sponge.h"

static const char *help =
    "usage: sessile sponge particles [--config FILE.json]... [--set KEY=VALUE]... [--seed N]\n"
    "                                [--iterations N] [--every K] [--out DIR] [--force]\n"
    "                                [--check] [--print-config] [--device D]\n"
    "       sessile sponge particles --resume DIR [--iterations N]\n"
    "\n"
    "Sponges after Liapis et al., Coralize (Section 3.3; docs/particle_sponge.md):\n"
    "  particles  a hemisphere in a cube fed by falling nutrient particles\n"
    "\n"
    "A closed hemisphere on the substratum inside a cube; every iteration\n"
    "nutrient particles spawn on the cube's top face and fall (plus a current);\n"
    "a vertex a particle touches grows along its normal, its neighbours by a\n"
    "Gaussian falloff; the surface is remeshed (splitting and collapse\n"
    "thresholds) and never crosses itself.  Collisions: a GPU kernel over a\n"
    "uniform grid.  Writes sponge/iter_NNNN.ply every K iterations and at the\n"
    "last, sponge/final.ply (per-vertex growth_count) and sponge/final.obj,\n"
    "manifest.json, records.jsonl and a checkpoint at each snapshot.\n"
    "Parameters, units and the paper's names: --print-config.\n"
    "\n"
    "  --seed N        seed of the particles, 0..2^64-1 (default 1)\n"
    "  --iterations N  iterations (default 50)      --every K  snapshot interval (default 10)\n"
    "  --out DIR       run directory (default runs/sponge); must be new or empty\n"
    "  --force         replace the earlier run in DIR     --resume DIR  continue it\n"
    "  --no-preview    no preview.png at the end of the run (docs/render.md)\n"
    "  --check         check every iteration: closed 2-manifold, no self-intersection\n"
    "Exit codes: 0 success, 1 runtime failure, 2 bad usage or input, 130/143 interrupted.\n";

#define CMD "sponge particles"

/* A failure before the run directory opens: one line naming the command. */
static int fail(sessile_status s) {
  char msg[1100];
  snprintf(msg, sizeof msg, "%s", sessile_error_message());
  fprintf(stderr, "sessile " CMD ": error: %s\n", msg);
  return s == SESSILE_ERR_USAGE ? EXIT_USAGE : EXIT_RUNTIME;
}

static int particles_main(int argc, char **argv, cli_run_args *a, const cli_gpu_opts *global) {
  cli_gpu_opts go = *global;
  int check = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    if (!strcmp(argv[i], "--check")) {
      check = 1;
      a->have_run_option = 1;
      continue;
    }
    int r = cli_gpu_option(CMD, argc, argv, &i, &go);
    if (r == 0) r = cli_run_option(CMD, argc, argv, &i, a);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error(CMD, "unknown option '%.60s'", argv[i]);
  }
  int rc = cli_run_args_check(CMD, a);
  if (rc >= 0) return rc;
  sessile_psponge_params p;
  sessile_psponge_options o = {.seed = a->seed, .iterations = a->iterations, .every = a->every, .check = check};
  sessile_params_defaults(&sessile_psponge_param_table, &p);
  sessile_status s = SESSILE_OK;
  if (!a->resume) {
    s = cli_run_apply_params(&sessile_psponge_param_table, &p, a);
    if (s == SESSILE_OK) s = sessile_params_check(&sessile_psponge_param_table, &p);
    if (s != SESSILE_OK) return fail(s);
    if (a->print_config) {
      s = sessile_params_print(&sessile_psponge_param_table, &p, stdout);
      return s == SESSILE_OK ? EXIT_OK : fail(s);
    }
  }
  if ((s = cli_gpu_check(&go)) != SESSILE_OK) return fail(s); /* an unknown --device: before any file */
  const char *dir = a->resume ? a->resume : a->out ? a->out : "runs/sponge";
  volatile sig_atomic_t *stop = cli_stop_flag_install();
  sessile_run *run = NULL;
  s = cli_run_open(CMD, argc, argv, a, dir, stop, &run);
  if (s == SESSILE_OK && a->resume) {
    s = sessile_psponge_config_read(sessile_run_config(run), &p, &o);
    if (a->have_iterations) o.iterations = a->iterations;
  }
  if (s == SESSILE_OK) {
    cJSON *cfg = sessile_psponge_config(&p, &o);
    if (!cfg) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    else s = sessile_run_set_config(run, cfg);
  }
  sessile_gpu *g = NULL;
  if (s == SESSILE_OK && p.collider == SESSILE_PSPONGE_COLLIDE_GPU) {
    s = cli_gpu_create(&go, &g);
    if (s == SESSILE_OK) cli_run_note_device(run, g);
  }
  int done = 0;
  o.run = run;
  o.gpu = g;
  double t0 = sessile_wall_seconds();
  if (s == SESSILE_OK) s = sessile_psponge_run(&p, &o, &done);
  double secs = sessile_wall_seconds() - t0;
  if (s == SESSILE_OK) cli_run_preview(CMD, a, run, "sponge/final.ply", g, &go);
  sessile_gpu_destroy(g);
  s = sessile_run_close(run, s);
  if (s == SESSILE_OK && !a->quiet) printf("sponge particles: %d iterations in %.1f s; run in %s\n", done, secs, dir);
  return cli_run_exit(CMD, s, dir, stop, done);
}

static int particles(int argc, char **argv, const cli_gpu_opts *global) {
  cli_run_args a;
  if (cli_run_args_init(&a, argc, 1, 50, 10) != 0) {
    cli_run_args_free(&a);
    fprintf(stderr, "sessile " CMD ": error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int rc = particles_main(argc, argv, &a, global);
  cli_run_args_free(&a);
  return rc;
}

int cmd_sponge(int argc, char **argv, const cli_gpu_opts *global) {
  static const char *top =
      "usage: sessile sponge particles [OPTIONS]   ('sessile sponge particles --help')\n"
      "\n"
      "Sponges after Liapis et al., Coralize (docs/particle_sponge.md):\n"
      "  particles  a hemisphere in a cube fed by falling nutrient particles (Section 3.3)\n";
  if (argc < 2) return cli_usage_error("sponge", "name a generator: particles");
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    fputs(top, stdout);
    return EXIT_OK;
  }
  if (!strcmp(argv[1], "particles")) return particles(argc - 1, argv + 1, global);
  return cli_usage_error("sponge", "unknown generator '%.60s' (available: particles)", argv[1]);
}
