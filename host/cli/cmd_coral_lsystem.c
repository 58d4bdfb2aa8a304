/* `sessile coral lsystem`: stony corals from a stochastic parametric
 * L-system (sessile/coral/lsystem.h, docs/lsystem.md).  Everything is computed
 * before the run directory opens, so bad input, a malformed grammar or a
 * derivation too large writes nothing. */
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "cli_progress.h"
#include "cli_run.h"
#include "sessile/io/io.h"
#include "sessile/coral/lsystem.h"

static const char *CMD = "coral lsystem";

static const char *help =
    "usage: sessile coral lsystem [--grammar NAME|FILE.lsys] [--define NAME=VALUE]... [--config FILE.json]...\n"
    "                             [--set KEY=VALUE]... [--seed N] [--iterations N] [--out DIR] [--force]\n"
    "                             [--print-config] [--quiet] [--progress MODE] [--device D]\n"
    "\n"
    "Stony corals after Coralize (Section 3.1): a stochastic parametric L-system\n"
    "grammar derived N times, drawn by a 3-D turtle with tropism and\n"
    "rotation-minimising frames, meshed as tubes (Mesh Detail sides) or as one\n"
    "welded surface (geometry=weld, on the device).  Writes coral/final.ply (per-\n"
    "vertex 'value': the branch order), coral/final.obj, coral/grammar.lsys,\n"
    "manifest.json and records.jsonl (modules per derivation step).  The grammar\n"
    "format: docs/lsystem.md.  Parameters: --print-config.\n"
    "\n"
    "  --grammar G     a shipped grammar (lophelia1, lophelia2, flat; the same as\n"
    "                  --set grammar=G) or a grammar file (a name ending in .lsys)\n"
    "  --define N=V    override the grammar's 'define N = ...' (repeatable)\n"
    "  --iterations N  derivation steps, 0..1000 (default: the grammar's 'iterations:')\n"
    "  --seed N        seed of every random choice, 0..2^64-1 (default 1)\n"
    "  --out DIR       run directory (default runs/coral-lsystem); must be new or empty\n"
    "  --force         replace the earlier run in DIR\n"
    "  --no-preview    no preview.png at the end of the run (docs/render.md)\n"
    "  --glb           coral/final.glb too: the mesh as glTF 2.0 binary (docs/io.md)\n"
    "  --obj-axes A    coral/final.obj in zup-cm, sessile's z up and cm (default), or\n"
    "                  yup-m, y up and metres for Blender and other DCC tools (docs/io.md)\n"
    "  --quiet         no progress and no summary line\n"
    "%s"
    "A derivation has no iterations to resume: --resume and --every are refused.\n"
    "Exit codes: 0 success, 1 runtime failure, 2 bad usage or input (one line on stderr).\n";

enum { MAX_DEFINES = 64 };

typedef struct lsys_cli {
  const char *grammar_opt;
  int ndef;
  char *dname[MAX_DEFINES];
  double dval[MAX_DEFINES];
} lsys_cli;

static int parse_define(const char *v, lsys_cli *c) {
  const char *eq = strchr(v, '=');
  if (!eq || eq == v || eq - v > 31)
    return cli_usage_error(CMD, "--define '%.60s': expected NAME=VALUE with a name of 1..31 characters", v);
  if (c->ndef == MAX_DEFINES) return cli_usage_error(CMD, "more than %d --define options", MAX_DEFINES);
  double x = cli_is_decimal(eq + 1) ? strtod(eq + 1, NULL) : NAN;
  if (!isfinite(x)) return cli_usage_error(CMD, "--define '%.60s': the value is not a finite decimal number", v);
  c->dname[c->ndef] = strndup(v, (size_t)(eq - v));
  if (!c->dname[c->ndef]) return cli_usage_error(CMD, "out of host memory");
  c->dval[c->ndef++] = x;
  return 0;
}

static int is_file_name(const char *g) {
  size_t n = strlen(g);
  return strchr(g, '/') || (n > 5 && !strcmp(g + n - 5, ".lsys"));
}

/* A grammar file: regular, at most 1 MiB (sessile_read_small_file). */
static sessile_status read_grammar(const char *path, char **text, size_t *len) {
  return sessile_read_small_file(path, (size_t)1 << 20, "grammar", text, len);
}

/* A stage of the run (the build is one library call: derivation, turtle
 * and mesh or weld), fraction: the work done after it.  The shares are
 * rough (lophelia1 on lavapipe: tubes 0/15/100%, weld 23/62/100% for
 * build/write/preview): writing a welded mesh's 1.5 million triangles and
 * drawing its preview cost as much as the weld. */
static void stage(cli_progress *pr, const char *name, double fraction, int ended) {
  sessile_progress e = {.stage = name, .fraction = fraction, .left_s = -1, .ended = ended};
  cli_progress_report(pr, &e);
}

static int run_main(int argc, char **argv, const cli_gpu_opts *global, cli_run_args *a, lsys_cli *c) {
  cli_gpu_opts go = *global;
  for (int i = 1; i < argc; i++) {
    if (cli_stray_value(CMD, argv, i)) return EXIT_USAGE;
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      printf(help, cli_progress_help);
      return EXIT_OK;
    }
    if (!strcmp(argv[i], "--grammar") || !strcmp(argv[i], "--define")) {
      int is_g = argv[i][2] == 'g';
      const char *v = cli_value(CMD, argc, argv, &i);
      if (!v || (is_g && cli_once(CMD, "--grammar", "--grammar"))) return EXIT_USAGE; /* --define repeats */
      if (is_g) c->grammar_opt = v;
      else if (parse_define(v, c)) return EXIT_USAGE;
      continue;
    }
    int r = cli_gpu_option(CMD, argc, argv, &i, &go);
    if (r == 0) r = cli_run_option(CMD, argc, argv, &i, a);
    if (r < 0) return EXIT_USAGE;
    if (r == 0) return cli_usage_error(CMD, "unknown option '%.60s'", argv[i]);
  }
  if (a->resume)
    return cli_usage_error(CMD, "--resume: an L-system run has no iterations to resume (it runs in seconds: "
                                "run it again with the same seed)");
  if (a->every != -1) return cli_usage_error(CMD, "--every: an L-system run writes only its final mesh");
  if (a->have_iterations && a->iterations > 1000)
    return cli_usage_error(CMD, "--iterations: %d is more than 1000", a->iterations);
  sessile_coral_lsystem_params p;
  sessile_params_defaults(&sessile_coral_lsystem_param_table, &p);
  const char *file = NULL;
  if (c->grammar_opt) {
    if (is_file_name(c->grammar_opt)) file = c->grammar_opt;
    else if (sessile_params_set_text(&sessile_coral_lsystem_param_table, &p, "grammar", c->grammar_opt) != SESSILE_OK)
      return cli_fail(SESSILE_ERR_USAGE);
  }
  sessile_status s = cli_run_apply_params(&sessile_coral_lsystem_param_table, &p, a);
  if (s == SESSILE_OK) s = sessile_params_check(&sessile_coral_lsystem_param_table, &p);
  if (s != SESSILE_OK) return cli_fail(s);
  /* the grammar: a file, or the shipped one the parameter names */
  char *owned = NULL;
  const char *text, *gname;
  size_t len = 0;
  char where[300];
  if (file) {
    s = read_grammar(file, &owned, &len);
    if (s != SESSILE_OK) return cli_fail(s);
    text = owned, gname = file;
    snprintf(where, sizeof where, "%s", file);
  } else {
    gname = sessile_coral_lsystem_param_table.params[0].names[p.grammar];
    text = sessile_lsys_builtin_find(gname, &len);
    if (!text) return cli_fail(sessile_error_set(SESSILE_ERR_INTERNAL, "the grammar '%s' is not embedded", gname));
    snprintf(where, sizeof where, "%s.lsys", gname);
  }
  sessile_lsys *g = NULL;
  s = sessile_lsys_parse(text, len, where, c->ndef, (const char *const *)c->dname, c->dval, &g);
  if (s != SESSILE_OK) {
    free(owned);
    return cli_fail(s);
  }
  if (a->print_config) {
    s = sessile_params_print(&sessile_coral_lsystem_param_table, &p, stdout);
    printf("grammar %s: iterations %d, angle %g deg, width_factor %g\n", gname,
           a->have_iterations ? a->iterations : sessile_lsys_iterations(g), sessile_lsys_angle(g),
           sessile_lsys_width_factor(g));
    for (int i = 0; i < sessile_lsys_define_count(g); i++) {
      double v;
      const char *nm = sessile_lsys_define_name(g, i, &v);
      printf("  define %-24s %.15g\n", nm, v);
    }
    sessile_lsys_destroy(g);
    free(owned);
    return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
  }
  /* from here on SIGINT/SIGTERM stop the derivation, the mesh or the writing
   * within a second: nothing is written before the run folder opens */
  volatile sig_atomic_t *stop = cli_stop_flag_install();
  sessile_gpu *gpu = NULL;
  s = cli_gpu_check(&go); /* an unknown --device (the preview's too): refused before anything is written */
  if (s == SESSILE_OK && p.geometry == 1) s = cli_gpu_create(&go, &gpu);
  sessile_coral_lsystem_result r = {0};
  cli_progress pr;
  cli_progress_start(&pr, CMD, a->progress, a->quiet);
  stage(&pr, p.geometry == 1 ? "derive and weld" : "derive and mesh", 0, 0);
  if (s == SESSILE_OK)
    s = sessile_coral_lsystem_build(&p, g, a->have_iterations ? a->iterations : -1, a->seed, gpu, stop, &r);
  if (s == SESSILE_OK) stage(&pr, p.geometry == 1 ? "derive and weld" : "derive and mesh", a->no_preview ? 0.6 : 0.4, 1);
  if (s != SESSILE_OK) {
    cli_progress_end(&pr);
    sessile_gpu_destroy(gpu);
    sessile_lsys_destroy(g);
    free(owned);
    if (s == SESSILE_ERR_INTERRUPTED) {
      fprintf(stderr, "sessile %s: interrupted (signal %d) before anything was written\n", CMD, (int)*stop);
      return cli_signal_exit_code((int)*stop);
    }
    /* refused before starting (max_modules, a grammar that draws nothing): bad input */
    int rc = cli_fail(s);
    return s == SESSILE_ERR_TOO_LARGE ? EXIT_USAGE : rc;
  }
  const char *dir = a->out ? a->out : "runs/coral-lsystem";
  sessile_run *run = NULL;
  s = cli_run_open("coral lsystem", argc, argv, a, dir, stop, &run);
  if (s == SESSILE_OK) {
    cJSON *cfg = cJSON_CreateObject();
    char seed[32];
    snprintf(seed, sizeof seed, "%llu", a->seed);
    if (cfg) {
      cJSON_AddStringToObject(cfg, "seed", seed);
      cJSON_AddNumberToObject(cfg, "iterations", r.iterations);
      cJSON_AddStringToObject(cfg, "grammar", gname);
      cJSON_AddItemToObject(cfg, "parameters", sessile_params_to_config(&sessile_coral_lsystem_param_table, &p));
      s = sessile_run_set_config(run, cfg);
    } else {
      s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    }
  }
  if (s == SESSILE_OK) cli_run_obj_style(CMD, a, run);
  if (s == SESSILE_OK) s = sessile_coral_lsystem_write(run, &p, g, gname, text, len, &r, gpu, stop);
  if (s == SESSILE_OK && !*stop) s = cli_run_glb(CMD, a, run, "coral/final.ply");
  if (s == SESSILE_OK) stage(&pr, "write", a->no_preview ? 1 : 0.7, 1);
  if (s == SESSILE_OK && !*stop) cli_run_preview(CMD, a, run, "coral/final.ply", gpu, &go);
  if (s == SESSILE_OK && !a->no_preview) stage(&pr, "preview", 1, 1);
  cli_progress_end(&pr);
  if (s == SESSILE_OK && *stop) s = sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d", (int)*stop);
  sessile_gpu_destroy(gpu);
  s = sessile_run_close(run, s);
  if (s == SESSILE_OK && !a->quiet)
    printf("coral lsystem: %s, %d iterations, %u modules, %u segments, %u triangles; run in %s\n", gname,
           r.iterations, r.str.n, r.turtle.segments, r.mesh.nf, dir);
  sessile_coral_lsystem_result_free(&r);
  sessile_lsys_destroy(g);
  free(owned);
  if (s == SESSILE_ERR_INTERRUPTED) { /* no resume: say what is left */
    fprintf(stderr, "sessile %s: interrupted (signal %d); '%s' holds an incomplete run (its manifest says "
                    "interrupted; every file in it is whole): run again with --force\n", CMD, (int)*stop, dir);
    return cli_signal_exit_code((int)*stop);
  }
  return cli_run_exit(CMD, s, dir, stop, 0);
}

int cmd_coral_lsystem(int argc, char **argv, const cli_gpu_opts *global) {
  cli_run_args a;
  lsys_cli c = {0};
  if (cli_run_args_init(&a, argc, 1, 0, -1) != 0) {
    cli_run_args_free(&a);
    fprintf(stderr, "sessile coral lsystem: error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int rc = run_main(argc, argv, global, &a, &c);
  for (int i = 0; i < c.ndef; i++) free(c.dname[i]);
  cli_run_args_free(&a);
  return rc;
}
