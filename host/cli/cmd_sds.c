/* `sessile sds run MODEL`: the Simplicial Developmental System (Porter &
 * McCormack) on the run framework (sessile/sds_run.h, docs/sds.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "cli_run.h"
#include "sessile/sds_builtin.h"
#include "sessile/io.h"
#include "sessile/sds_run.h"

#define CMD "sds run"

static const char *help =
    "usage: sessile sds run MODEL [--config FILE.json]... [--set KEY=VALUE]... [--print-config]\n"
    "                           [--t-end T] [--frames N] [--max-cells N] [--max-steps N] [--seed N]\n"
    "                           [--out DIR] [--force] [--quiet] [--device D]\n"
    "       sessile sds run [MODEL] --resume DIR [--quiet] [--device D]\n"
    "       sessile sds models         list the shipped models\n"
    "\n"
    "Grows a form with SDS (Porter & McCormack): a tetrahedral complex whose\n"
    "vertices are cells, with mass-spring physics and morphogen diffusion on the\n"
    "device, rules per cell (grow, divide toward a morphogen's gradient), cell\n"
    "division and inversions re-tetrahedralised with TetGen.  MODEL is a shipped\n"
    "model (limb, six_limbs_box, rock, attractor, budded) or a model file\n"
    "(a name ending in .sds; the language: docs/sds_rules.md).\n"
    "Writes sds/frame_NNNN.ply (the surface with per-cell radius, morphogens and\n"
    "state), sds/frame_NNNN.vtu and sds/series.pvd (the complex, for ParaView),\n"
    "sds/final.ply, sds/model.sds (the model run), manifest.json and\n"
    "records.jsonl (per frame: time, cells, tets, ms per step, divisions,\n"
    "inversions) and sds/steps.csv (the same per physics step: the paper's\n"
    "Figure 12; `sessile render DIR` draws it as renders/plot_step_times.png).\n"
    "\n"
    "Parameters: the model's physics and set-up numbers (dt, edge_stiffness, gravity, ...)\n"
    "have a table with defaults, ranges, units and sources; the model file's NAME = value\n"
    "lines override the defaults, then --config files (JSON objects) in order, then --set\n"
    "in order.  --print-config prints the table with the model's values (docs/sds.md).\n"
    "\n"
    "  --config FILE   a JSON object of parameters over the model's ({\"dt\": 0.002})\n"
    "  --set KEY=VALUE one parameter over the model's and the configs'\n"
    "  --print-config  print every parameter (value, unit, range, source, meaning) and exit\n"
    "  --t-end T       simulated time to reach (default: the model's t_end)\n"
    "  --frames N      frames over t_end (default: the model's frames)\n"
    "  --max-cells N   stop with an error past N cells (default 200000)\n"
    "  --max-steps N   refuse a run whose estimate at the starting organism's stable step\n"
    "                  exceeds N steps (default 10000000)\n"
    "  --seed N        seed of the random choices: division directions where a gradient vanishes,\n"
    "                  and the start's realisation where the model sets start_jitter (default 1)\n"
    "  --out DIR       run directory (default runs/sds-MODEL); must be new or empty\n"
    "  --force         replace the earlier run in DIR\n"
    "  --no-preview    no preview.png at the end of the run (docs/render.md)\n"
    "  --resume DIR    continue the run in DIR from its checkpoint (written at every frame\n"
    "                  and when SIGINT/SIGTERM stops it) with its own model and options; the\n"
    "                  outputs are the same bytes as a run that never stopped (same device).\n"
    "                  A MODEL given with it must be the run's own.\n"
    "On a failure mid-run (a blow-up, a division TetGen cannot mesh) the frames\n"
    "written so far stay and the message names the time and the cause.  A blow-up\n"
    "(a non-finite position, velocity, radius or morphogen, a cell 1e6 starting sizes\n"
    "away, the step below dt_min, time standing still) ends with exit code 3, the\n"
    "manifest's sds.status \"blow-up\" and the last good frame kept (docs/sds.md).\n"
    "Exit codes: 0 success, 1 runtime failure, 2 bad usage or input, 3 blow-up,\n"
    "130/143 interrupted.\n";

/* A blow-up ends the run with its own exit code (docs/sds.md, "Blow-ups"). */
enum { EXIT_BLOWUP = 3 };

static int is_file_name(const char *g) {
  size_t n = strlen(g);
  return strchr(g, '/') || (n > 4 && !strcmp(g + n - 4, ".sds"));
}

static int list_models(void) {
  for (const embedded_text *b = sds_builtins; b->name; b++) {
    /* the first comment line says what it is */
    const char *t = b->text, *e = strchr(t, '\n');
    int n = e ? (int)(e - t) : (int)strlen(t);
    printf("%-14s %.*s\n", b->name, n > 2 ? n - 2 : 0, t + (n > 2 ? 2 : 0));
  }
  return EXIT_OK;
}

static int parse_double(const char *v, double lo, double hi, double *out) {
  char *end = NULL;
  double x = v ? strtod(v, &end) : 0;
  if (!v || !*v || *end || !(x >= lo && x <= hi)) return -1;
  *out = x;
  return 0;
}

/* The run's configuration in its manifest: what --resume restarts from. */
typedef struct stored {
  char *name, *text;
  unsigned long long seed;
  double t_end;
  int frames;
  unsigned max_cells;
  sessile_sds_run_params p; /* the parameter table's values */
} stored;

/* The run's configuration in its manifest: what --resume restarts from
 * (the parameters bit for bit: sessile_params_to_config). */
static cJSON *config_make(const stored *o) {
  cJSON *c = cJSON_CreateObject();
  char sd[32];
  snprintf(sd, sizeof sd, "%llu", o->seed);
  cJSON *pj = sessile_params_to_config(&sessile_sds_run_param_table, &o->p);
  if (!c || !pj || !cJSON_AddStringToObject(c, "seed", sd) || !cJSON_AddStringToObject(c, "model", o->name) ||
      !cJSON_AddStringToObject(c, "model_text", o->text) || !cJSON_AddNumberToObject(c, "t_end", o->t_end) ||
      !cJSON_AddNumberToObject(c, "frames", o->frames) || !cJSON_AddNumberToObject(c, "max_cells", o->max_cells) ||
      !cJSON_AddItemToObject(c, "parameters", pj)) {
    if (pj && !cJSON_GetObjectItemCaseSensitive(c, "parameters")) cJSON_Delete(pj);
    cJSON_Delete(c);
    return NULL;
  }
  return c;
}

static sessile_status config_take(const cJSON *c, const char *dir, stored *o) {
  const cJSON *sd = cJSON_GetObjectItemCaseSensitive(c, "seed"), *nm = cJSON_GetObjectItemCaseSensitive(c, "model");
  const cJSON *tx = cJSON_GetObjectItemCaseSensitive(c, "model_text"), *te = cJSON_GetObjectItemCaseSensitive(c, "t_end");
  const cJSON *fr = cJSON_GetObjectItemCaseSensitive(c, "frames"), *mc = cJSON_GetObjectItemCaseSensitive(c, "max_cells");
  char *end = NULL;
  int ok = cJSON_IsString(sd) && cJSON_IsString(nm) && cJSON_IsString(tx) && cJSON_IsNumber(te) && cJSON_IsNumber(fr) &&
           cJSON_IsNumber(mc);
  if (ok) o->seed = strtoull(sd->valuestring, &end, 10);
  ok = ok && end && !*end && te->valuedouble <= 1e9 && fr->valuedouble >= -1 && fr->valuedouble <= 100000 &&
       fr->valuedouble == (int)fr->valuedouble && mc->valuedouble >= 4 && mc->valuedouble <= 50000000;
  SESSILE_CHECK(ok, SESSILE_ERR_USAGE, "'%s/manifest.json' holds no SDS configuration to resume from (damaged?)", dir);
  o->name = strdup(nm->valuestring), o->text = strdup(tx->valuestring);
  SESSILE_CHECK(o->name && o->text, SESSILE_ERR_NO_MEMORY, "out of host memory");
  o->t_end = te->valuedouble, o->frames = (int)fr->valuedouble, o->max_cells = (unsigned)mc->valuedouble;
  /* a run from before the parameter table stored none: the model text's own */
  const cJSON *pj = cJSON_GetObjectItemCaseSensitive(c, "parameters");
  if (!pj) return sessile_sds_run_params_of_model(o->text, o->name, &o->p);
  sessile_params_defaults(&sessile_sds_run_param_table, &o->p);
  SESSILE_CALL(sessile_params_apply_json(&sessile_sds_run_param_table, &o->p, pj, "the run's stored configuration"));
  return sessile_params_check(&sessile_sds_run_param_table, &o->p);
}

static int read_model(const char *model, char **text) {
  size_t len = 0;
  if (is_file_name(model)) {
    sessile_status s = sessile_read_small_file(model, (size_t)1 << 20, "model file", text, &len);
    return s == SESSILE_OK ? -1 : cli_fail(s);
  }
  const embedded_text *b = embedded_text_find(sds_builtins, model);
  if (!b) return cli_usage_error(CMD, "no shipped model '%.60s' (sessile sds models lists them)", model);
  *text = malloc(b->len + 1);
  if (!*text) return cli_usage_error(CMD, "out of host memory");
  memcpy(*text, b->text, b->len + 1);
  return -1;
}

/* The manifest's sds member: totals, and how the run ended. */
static void manifest_sds(sessile_run *run, const char *name, const sessile_sds_run_stats *st, sessile_status s) {
  cJSON *m = sessile_run_manifest(run);
  cJSON *js = cJSON_CreateObject();
  if (!js) return;
  cJSON_AddStringToObject(js, "model", name);
  cJSON_AddStringToObject(js, "status", s == SESSILE_OK ? "completed"
                                        : s == SESSILE_ERR_INTERRUPTED ? "interrupted"
                                        : st->blowup ? "blow-up" : "failed");
  if (st->blowup) {
    cJSON *b = cJSON_AddObjectToObject(js, "blowup");
    if (b) {
      cJSON_AddNumberToObject(b, "time", st->blowup_time);
      cJSON_AddNumberToObject(b, "step", (double)st->blowup_step);
      cJSON_AddStringToObject(b, "cause", st->blowup_cause);
      cJSON_AddNumberToObject(b, "last_good_frame", st->frames - 1);
    }
  }
  cJSON_AddNumberToObject(js, "time", st->time);
  cJSON_AddNumberToObject(js, "steps", (double)st->steps);
  cJSON_AddNumberToObject(js, "cells", st->cells);
  cJSON_AddNumberToObject(js, "tets", st->tets);
  cJSON_AddNumberToObject(js, "divisions", (double)st->divisions);
  cJSON_AddNumberToObject(js, "inversions", (double)st->inversions);
  cJSON_AddNumberToObject(js, "inversions_resisted", (double)st->resisted);
  cJSON_AddNumberToObject(js, "sliver_steps", (double)st->slivers);
  cJSON_AddNumberToObject(js, "repairs", (double)st->repairs);
  cJSON_AddNumberToObject(js, "divisions_deferred", (double)st->deferred);
  cJSON_AddNumberToObject(js, "frames", st->frames);
  cJSON_AddNumberToObject(js, "wall_s", st->wall_s);
  cJSON_DeleteItemFromObjectCaseSensitive(m, "sds");
  cJSON_AddItemToObject(m, "sds", js);
}

static int run_main(int argc, char **argv, const cli_gpu_opts *global, cli_run_args *a) {
  cli_gpu_opts go = *global;
  const char *model = NULL;
  double t_end = -1;
  unsigned frames = 0, max_cells = 200000, max_steps = 10000000;
  int have_frames = 0, have_shape = 0; /* have_shape: an option a resume must not change */
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    if (!strcmp(o, "--help") || !strcmp(o, "-h")) {
      fputs(help, stdout);
      return EXIT_OK;
    }
    if (!strcmp(o, "--t-end")) {
      const char *v = cli_value(CMD, argc, argv, &i);
      if (!v) return EXIT_USAGE;
      if (parse_double(v, 0, 1e9, &t_end)) return cli_usage_error(CMD, "--t-end needs a time in [0, 1e9] (got '%.40s')", v);
      have_shape = 1;
      continue;
    }
    if (!strcmp(o, "--frames")) {
      if (cli_parse_uint(CMD, o, i + 1 < argc ? argv[++i] : NULL, 1, 100000, &frames)) return EXIT_USAGE;
      have_frames = have_shape = 1;
      continue;
    }
    if (!strcmp(o, "--max-steps")) {
      if (cli_parse_uint(CMD, o, i + 1 < argc ? argv[++i] : NULL, 1, 4000000000u, &max_steps)) return EXIT_USAGE;
      have_shape = 1;
      continue;
    }
    if (!strcmp(o, "--max-cells")) {
      if (cli_parse_uint(CMD, o, i + 1 < argc ? argv[++i] : NULL, 4, 50000000, &max_cells)) return EXIT_USAGE;
      have_shape = 1;
      continue;
    }
    int r = cli_gpu_option(CMD, argc, argv, &i, &go);
    if (r == 0) r = cli_run_option(CMD, argc, argv, &i, a);
    if (r < 0) return EXIT_USAGE;
    if (r > 0) continue;
    if (o[0] == '-' || model) return cli_usage_error(CMD, "unknown option or second model '%.60s'", o);
    model = o;
  }
  if (a->have_iterations || a->every != 1)
    return cli_usage_error(CMD, "--iterations and --every do not apply: the model runs to its t_end (--t-end), "
                                "in frames (--frames)");
  if (a->resume && (a->have_run_option || have_shape))
    return cli_usage_error(CMD, "--resume continues a run with its own model, parameters and options: only a MODEL "
                                "(its own), --quiet and device options go with it");
  if (!model && !a->resume) return cli_usage_error(CMD, "name a model: a shipped one (sessile sds models) or FILE.sds");
  char *text = NULL;
  if (model) {
    int rc = read_model(model, &text);
    if (rc >= 0) return rc;
  }
  stored cfg = {.seed = a->seed, .t_end = t_end, .frames = have_frames ? (int)frames : -1, .max_cells = max_cells};
  sessile_status s = SESSILE_OK;
  if (!a->resume) {
    /* the parameters: the table's defaults, the model's lines, --config, --set */
    s = sessile_sds_run_params_of_model(text, model, &cfg.p);
    if (s == SESSILE_OK) s = cli_run_apply_params(&sessile_sds_run_param_table, &cfg.p, a);
    if (s == SESSILE_OK) s = sessile_params_check(&sessile_sds_run_param_table, &cfg.p);
    if (s == SESSILE_OK && a->print_config) {
      s = sessile_params_print(&sessile_sds_run_param_table, &cfg.p, stdout);
      free(text);
      return s == SESSILE_OK ? EXIT_OK : cli_fail(s);
    }
    /* everything about the model that needs no device, before the run directory */
    if (s == SESSILE_OK) s = sessile_sds_model_check(text, model, &cfg.p, t_end, max_steps);
    if (s != SESSILE_OK) {
      free(text);
      return cli_fail(s);
    }
  }
  char dir_buf[256];
  const char *base = model ? (strrchr(model, '/') ? strrchr(model, '/') + 1 : model) : "";
  snprintf(dir_buf, sizeof dir_buf, "runs/sds-%.*s", (int)(strcspn(base, ".") ? strcspn(base, ".") : 1), base);
  const char *dir = a->resume ? a->resume : a->out ? a->out : dir_buf;
  sessile_gpu *g = NULL;
  s = cli_gpu_create(&go, &g);
  if (s != SESSILE_OK) {
    free(text);
    return cli_fail(s);
  }
  volatile sig_atomic_t *stop = cli_stop_flag_install();
  sessile_run *run = NULL;
  s = cli_run_open("sds", argc, argv, a, dir, stop, &run);
  if (s == SESSILE_OK && a->resume) {
    s = config_take(sessile_run_config(run), dir, &cfg);
    if (s == SESSILE_OK && text && strcmp(text, cfg.text))
      s = sessile_error_set(SESSILE_ERR_USAGE, "'%s' holds a run of another model ('%.60s'), not '%.60s'", dir, cfg.name,
                            model);
  } else if (s == SESSILE_OK) {
    cfg.name = strdup(model), cfg.text = strdup(text);
    if (!cfg.name || !cfg.text) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    char path[4096];
    if (s == SESSILE_OK) s = sessile_run_file(run, "sds/model.sds", path, sizeof path);
    if (s == SESSILE_OK) s = sessile_write_file_atomic(path, text, strlen(text));
  }
  if (s == SESSILE_OK) cli_run_note_device(run, g);
  if (s == SESSILE_OK) {
    cJSON *c = config_make(&cfg);
    s = c ? sessile_run_set_config(run, c) : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  }
  sessile_sds_run_stats st;
  memset(&st, 0, sizeof st);
  const char *name = cfg.name ? cfg.name : model ? model : "?";
  if (s == SESSILE_OK) {
    sessile_sds_run_options o = {.run = run, .gpu = g, .seed = cfg.seed, .model_text = cfg.text, .model_name = cfg.name,
                                 .params = &cfg.p,
                                 .t_end = cfg.t_end, .frames = cfg.frames, .max_cells = cfg.max_cells};
    s = sessile_sds_run(&o, &st);
    manifest_sds(run, name, &st, s);
  }
  if (s == SESSILE_OK) cli_run_preview(CMD, a, run, "sds/final.ply", g, &go);
  s = sessile_run_close(run, s);
  sessile_gpu_destroy(g);
  if (s == SESSILE_OK && !a->quiet)
    printf("sds %s: t = %g, %u cells, %u tets, %llu steps, %llu divisions, %llu inversions, %d frames in %.1f s; run in %s\n",
           name, st.time, st.cells, st.tets, (unsigned long long)st.steps, (unsigned long long)st.divisions,
           (unsigned long long)st.inversions, st.frames, st.wall_s, dir);
  free(text), free(cfg.name), free(cfg.text);
  if (s == SESSILE_ERR_NUMERIC && st.blowup) {
    cli_fail(s);
    return EXIT_BLOWUP;
  }
  return cli_run_exit(CMD, s, dir, stop, st.frames);
}

int cmd_sds(int argc, char **argv, const cli_gpu_opts *global) {
  if (argc < 2) return cli_usage_error("sds", "name a subcommand: run or models");
  if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
    fputs(help, stdout);
    return EXIT_OK;
  }
  if (!strcmp(argv[1], "models")) {
    if (argc > 2) return cli_usage_error("sds models", "takes no arguments");
    return list_models();
  }
  if (strcmp(argv[1], "run")) return cli_usage_error("sds", "unknown subcommand '%.60s' (run, models)", argv[1]);
  cli_run_args a;
  if (cli_run_args_init(&a, argc, 1, 0, 1) != 0) {
    cli_run_args_free(&a);
    fprintf(stderr, "sessile sds run: error: out of host memory\n");
    return EXIT_RUNTIME;
  }
  int rc = run_main(argc - 1, argv + 1, global, &a);
  cli_run_args_free(&a);
  return rc;
}
