/* `sessile grow`: the accretive sponge on the paper's defaults, with presets,
 * JSON configs and --set overrides, through the run framework (lock,
 * manifest, records, checkpoints, --force, --resume, signals). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "cli.h"
#include "cli_monitor.h"
#include "cli_run.h"
#include "sessile/grow.h"
#include "sessile/run.h"

static const char *help =
    "usage: sessile grow [--preset radiate|crella] [--config FILE.json]... [--set KEY=VALUE]...\n"
    "                    [--seed N] [--iterations N] [--out DIR] [--force] [--every K]\n"
    "                    [--slices SPEC] [--no-fields] [--quiet] [--print-config]\n"
    "       sessile grow --resume DIR [--iterations N] [--quiet]\n"
    "\n"
    "Grows a sponge by O'Hagan et al.'s accretive model: per iteration the nutrient\n"
    "field is solved (diffusion limited: a Laplace problem, c = 0 on the sponge's\n"
    "surface by cut cells, c = 1 in the far field; multigrid on the GPU), each vertex\n"
    "takes up the nutrient's flux into it (probe=flux; probe=paper: eq 6), which is\n"
    "translocated over the surface (eqs 7-8), and each vertex grows by the Chindapol\n"
    "function (eq 10) unless that would make the surface cross itself; then the\n"
    "surface is remeshed.  Lengths are in cm; docs/model.md has every equation and\n"
    "parameter, docs/science.md what converges and what the model shows.\n"
    "The ocean current (stationary Navier-Stokes, docs/fluid.md) is solved at each\n"
    "snapshot for the velocity and pressure outputs (fluid_at_snapshots); with\n"
    "--set diffusion_limited=false it is solved every iteration and advects the\n"
    "nutrient (--set domain=conforming meshes the water around the sponge with\n"
    "TetGen; fluid_resolution=2 doubles the flow's resolution at ~10x the time).\n"
    "\n"
    "  --preset P        radiate: Table 1 as is (radiate accretive growth, default);\n"
    "                    crella: Halichondrid normals + randomised x/y position (§4.7)\n"
    "  --config FILE     JSON object of parameter overrides {\"t_give\": 0.1, ...};\n"
    "                    repeatable: files apply in order, a later one wins\n"
    "  --set KEY=VALUE   override one parameter (repeatable; applied after every --config)\n"
    "  --print-config    list every parameter (value, unit, range, paper source) and exit;\n"
    "                    it checks exactly what a run checks before it starts\n"
    "  --seed N          seed of every random choice, 0..2^64-1 (default 1): same seed,\n"
    "                    same device, same bytes out\n"
    "  --iterations N    growth iterations (default 50; with --resume: the new total)\n"
    "  --out DIR         run directory (default runs/<preset>); it must be new or empty\n"
    "  --force           DIR holds an earlier run: remove that run's files (those its\n"
    "                    manifest lists) and start anew\n"
    "  --resume DIR      continue the run in DIR from its last checkpoint (interrupted,\n"
    "                    failed or completed: with a larger --iterations it goes on);\n"
    "                    the outputs are byte-identical to a run that never stopped\n"
    "  --every K         snapshot every K iterations and at the last one (default 10;\n"
    "                    0: the last only): sponge/iter_NNNN.ply, slices, fields, and a\n"
    "                    checkpoint\n"
    "  --slices SPEC     EXR slice planes: 'x,y,z' through the sponge centre (default),\n"
    "                    'z=3.5,y=19.2' at given heights in cm, or '' for none\n"
    "  --no-fields       no VTU volume fields\n"
    "  --quiet           no progress output (warnings still go to stderr)\n"
    "  --no-preview      no preview.png at the end of the run (docs/render.md)\n"
    "\n"
    "The run directory (docs/run.md) holds manifest.json (state, pid, host, command,\n"
    "times, every parameter, device, totals, the files of the run), records.jsonl (one\n"
    "line per iteration: stage timings, solver iterations and true residuals, mesh\n"
    "statistics), checkpoint.bin, sponge/final.ply and final.obj, and the snapshots\n"
    "(fields/series.pvd opens the VTU series in ParaView).  Every file is written\n"
    "atomically.  A second run into a directory in use is refused.  SIGINT/SIGTERM stop\n"
    "the run after its current iteration with a checkpoint (a second signal: at once).\n"
    "Exit codes: 0 success, 1 runtime failure, 2 bad usage or input, 130/143 interrupted.\n";

typedef struct grow_args {
  const char *preset;
  cli_run_args ra;
  sessile_grow_options o;
  cli_gpu_opts go;
} grow_args;

/* Parses argv; returns -1 to go on, else an exit code. */
static int parse(int argc, char **argv, grow_args *a) {
  for (int i = 1; i < argc; i++) {
    const char *opt = argv[i];
    int r = cli_gpu_option("grow", argc, argv, &i, &a->go);
    if (r == 0) r = cli_run_option("grow", argc, argv, &i, &a->ra);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (!strcmp(opt, "--help") || !strcmp(opt, "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    if (!strcmp(opt, "--no-fields")) {
      a->o.fields = 0, a->ra.have_run_option = 1;
    } else if (!strcmp(opt, "--slices")) {
      /* --slices '' is a value (no slices) */
      if (i + 1 < argc && argv[i + 1][0] == 0) a->o.slices = argv[++i];
      else if (!(a->o.slices = cli_value("grow", argc, argv, &i))) return EXIT_USAGE;
      if (cli_once("grow", opt, opt)) return EXIT_USAGE;
      a->ra.have_run_option = 1;
    } else if (!strcmp(opt, "--preset")) {
      if (!(a->preset = cli_value("grow", argc, argv, &i)) || cli_once("grow", opt, opt)) return EXIT_USAGE;
      a->ra.have_run_option = 1;
    } else return cli_usage_error("grow", "unknown option '%.60s'", opt);
  }
  return cli_run_args_check("grow", &a->ra);
}

static int grow_main(int argc, char **argv, grow_args *a) {
  int rc = parse(argc, argv, a);
  if (rc >= 0) return rc;
  a->o.seed = a->ra.seed, a->o.iterations = a->ra.iterations, a->o.every = a->ra.every;
  a->o.preset = a->preset; /* the manifest's and the config's preset name */
  sessile_params p;
  sessile_status s = SESSILE_OK;
  if (!a->ra.resume) {
    /* the preset, the configs in order, the --sets; then every check that
     * needs no device: bad input exits 2 here, before any work */
    s = sessile_params_preset(&p, a->preset);
    if (s == SESSILE_OK) s = cli_run_apply_params(&sessile_grow_param_table, &p, &a->ra);
    if (s == SESSILE_OK) s = sessile_grow_check_options(&p, &a->o);
    if (s != SESSILE_OK) return cli_fail(s);
    if (a->ra.print_config) {
      s = sessile_params_print(&sessile_grow_param_table, &p, stdout);
      return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
    }
  }
  s = cli_gpu_check(&a->go); /* an unknown --device: refused before anything is written */
  if (s != SESSILE_OK) return cli_fail(s);
  char outbuf[512];
  snprintf(outbuf, sizeof outbuf, "runs/%s", a->preset);
  const char *dir = a->ra.resume ? a->ra.resume : a->ra.out ? a->ra.out : outbuf;
  volatile sig_atomic_t *stop = cli_stop_flag_install();
  sessile_gpu *g = NULL;
  s = cli_gpu_create(&a->go, &g);
  if (s != SESSILE_OK) return cli_fail(s);
  sessile_run *run = NULL;
  cJSON *old = NULL; /* a resume's options point into its stored config: keep a copy */
  /* what the device cannot hold is refused before the folder is touched */
  if (!a->ra.resume) s = sessile_grow_check_device(g, &p);
  if (s == SESSILE_OK) s = cli_run_open("grow", argc, argv, &a->ra, dir, stop, &run);
  if (s == SESSILE_OK && a->ra.resume) {
    old = cJSON_Duplicate(sessile_run_config(run), 1);
    s = old ? sessile_grow_config_read(old, &p, &a->o)
            : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    if (s == SESSILE_OK && a->ra.have_iterations) a->o.iterations = a->ra.iterations;
  }
  if (s == SESSILE_OK) {
    cJSON *cfg = sessile_grow_config(&p, &a->o);
    if (!cfg) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    else s = sessile_run_set_config(run, cfg);
  }
  cli_monitor mon = {.cmd = "grow", .quiet = a->ra.quiet, .tty = isatty(2)};
  a->o.run = run;
  a->o.monitor = cli_monitor_line;
  a->o.monitor_user = &mon;
  sessile_grow_summary sum;
  memset(&sum, 0, sizeof sum);
  if (s == SESSILE_OK) s = sessile_grow_run(g, &p, &a->o, NULL, &sum);
  cli_monitor_end(&mon);
  if (s == SESSILE_OK) cli_run_preview("grow", &a->ra, run, "sponge/final.ply", g, &a->go);
  s = sessile_run_close(run, s);
  cJSON_Delete(old);
  sessile_gpu_destroy(g);
  if (s == SESSILE_OK && !a->ra.quiet)
    printf("grew %d iterations in %.1f s: %u vertices, %u triangles; box %u nodes; run in %s\n",
           sum.iterations, sum.total_seconds, sum.final_vertices, sum.final_triangles, sum.box_nodes, dir);
  return cli_run_exit("grow", s, dir, stop, sum.iterations);
}

int cmd_grow(int argc, char **argv, const cli_gpu_opts *global) {
  grow_args a;
  memset(&a, 0, sizeof a);
  a.go = *global;
  a.preset = "radiate";
  sessile_grow_options_default(&a.o);
  if (cli_run_args_init(&a.ra, argc, a.o.seed, a.o.iterations, a.o.every) != 0) {
    cli_run_args_free(&a.ra);
    fprintf(stderr, "sessile grow: error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int rc = grow_main(argc, argv, &a);
  cli_run_args_free(&a.ra);
  return rc;
}
