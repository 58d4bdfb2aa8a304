/* `sessile sds run MODEL` as a generator (sessile/run/generator.h): the run
 * loop's iteration is one frame interval of simulated time (--frames N over
 * --t-end T), a snapshot every frame, the step log appended through the run
 * (sds/steps.csv), the checkpoint's sections the SDS state (docs/sds.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/io/io.h"
#include "sessile/sds/sds_builtin.h"
#include "sds/sds_sim.h"

static const char help[] =
    "usage: sessile sds run MODEL [--config FILE.json]... [--set KEY=VALUE]... [--print-config]\n"
    "                           [--t-end T] [--frames N] [--max-cells N] [--max-steps N] [--seed N]\n"
    "                           [--out DIR] [--force] [--quiet] [--progress MODE] [--device D]\n"
    "       sessile sds run [MODEL] --resume DIR [--quiet] [--progress MODE] [--device D]\n"
    "       sessile sds models         list the shipped models\n"
    "\n"
    "Grows a form with SDS (Porter & McCormack): a tetrahedral complex whose\n"
    "vertices are cells, with mass-spring physics and morphogen diffusion on the\n"
    "device, rules per cell (grow, divide toward a morphogen's gradient), cell\n"
    "division and inversions re-tetrahedralised with TetGen.  MODEL is a shipped\n"
    "model (limb, limb_extension, six_limbs_box, rock, rock_stripes, attractor, budded) or a\n"
    "model file (a name ending in .sds; the language: docs/sds_rules.md).\n"
    "Writes sds/frame_NNNN.ply (the surface with per-cell radius, morphogens and\n"
    "state), sds/frame_NNNN.vtu and sds/series.pvd (the complex, for ParaView),\n"
    "sds/final.ply, sds/model.sds (the model run), manifest.json and\n"
    "records.jsonl (per frame: time, cells, tets, ms per step, divisions,\n"
    "inversions), sds/steps.csv (the same per physics step: the paper's\n"
    "Figure 12; `sessile render DIR` draws it as renders/plot_step_times.png) and\n"
    "sds/divisions.csv (per division: time, cell, daughter, place, radius).\n"
    "tools/sds/figures.py measures the paper's figures from these (docs/sds.md).\n"
    "\n"
    "Parameters: the model's physics and set-up numbers (dt, edge_stiffness, gravity, ...)\n"
    "have a table with defaults, ranges, units and sources; the model file's NAME = value\n"
    "lines override the defaults, then --config files (JSON objects) in order, then --set\n"
    "in order.  --print-config prints the table with the model's values (docs/sds.md).\n"
    "\n"
    "  --config FILE   a JSON object of parameters over the model's ({\"dt\": 0.002})\n"
    "  --set KEY=VALUE one parameter over the model's and the configs'\n"
    "  --print-config  print every parameter (value, unit, range, source, meaning) and exit\n"
    "  --t-end T       simulated time to reach: the run ends at the first step at or past it\n"
    "                  (default: the model's t_end)\n"
    "  --frames N      frames over t_end, each the state at the first step at or past its\n"
    "                  time, that time in sds/series.pvd; steps are never cut to land on a\n"
    "                  frame, so --frames and --t-end do not change the steps (default: the\n"
    "                  model's frames)\n"
    "  --max-cells N   stop with an error past N cells (default 200000)\n"
    "  --max-steps N   refuse a run whose estimate at the starting organism's stable step\n"
    "                  exceeds N steps (default 10000000)\n"
    "  --seed N        seed of the random choices: division directions where a gradient vanishes,\n"
    "                  and the start's realisation where the model sets start_jitter (default 1)\n"
    "  --out DIR       run directory (default runs/sds-MODEL); must be new or empty\n"
    "  --force         replace the earlier run in DIR\n"
    "  --no-preview    no preview.png at the end of the run (docs/render.md)\n"
    "  --quiet         no progress and no summary line\n"
    "  --progress M    progress on stderr (percent of t_end, time left): auto, tty, lines, json\n"
    "                  or none (default auto; docs/run.md \"Progress\")\n"
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

enum { SDS_MAX_CELLS = 200000, SDS_MAX_STEPS = 10000000 };

static int is_file_name(const char *g) {
  size_t n = strlen(g);
  return strchr(g, '/') || (n > 4 && !strcmp(g + n - 4, ".sds"));
}

static sessile_status read_model(const char *model, char **text) {
  size_t len = 0;
  if (is_file_name(model)) return sessile_read_small_file(model, (size_t)1 << 20, "model file", text, &len);
  const embedded_text *b = embedded_text_find(sds_builtins, model);
  SESSILE_CHECK(b, SESSILE_ERR_USAGE, "no shipped model '%.60s' (sessile sds models lists them)", model);
  *text = malloc(b->len + 1);
  SESSILE_CHECK(*text, SESSILE_ERR_NO_MEMORY, "out of host memory");
  memcpy(*text, b->text, b->len + 1);
  return SESSILE_OK;
}

static sessile_status parse_uint(const char *opt, const char *v, unsigned lo, unsigned hi, unsigned *out) {
  char *end = NULL;
  unsigned long long x = v && *v >= '0' && *v <= '9' ? strtoull(v, &end, 10) : 0;
  SESSILE_CHECK(v && *v, SESSILE_ERR_USAGE, "%s needs a value", opt);
  SESSILE_CHECK(end && !*end && x >= lo && x <= hi, SESSILE_ERR_USAGE, "%s: '%s' is not an integer in %u..%u", opt, v,
                lo, hi);
  *out = (unsigned)x;
  return SESSILE_OK;
}

static sessile_status sds_arg(void *extra, int argc, char **argv, int *i, int *taken) {
  sds_gen_args *a = extra;
  const char *o = argv[*i], *v = *i + 1 < argc ? argv[*i + 1] : NULL;
  unsigned u = 0;
  *taken = 1;
  /* each valued option once: the last one silently winning hid mistakes */
  static const char *const once[] = {"--t-end", "--frames", "--max-steps", "--max-cells"};
  for (unsigned k = 0; k < 4; k++) {
    if (strcmp(o, once[k])) continue;
    SESSILE_CHECK(!(a->given & (1u << k)), SESSILE_ERR_USAGE, "%s given twice", o);
    a->given |= 1u << k;
  }
  if (!strcmp(o, "--t-end")) {
    char *end = NULL;
    SESSILE_CHECK(v, SESSILE_ERR_USAGE, "%s needs a value", o);
    /* decimal only: no hexadecimal, inf or nan */
    double x = strspn(v, "0123456789.eE+-") == strlen(v) ? strtod(v, &end) : -1;
    SESSILE_CHECK(*v && end && !*end && x >= 0 && x <= 1e9, SESSILE_ERR_USAGE,
                  "%s: '%.40s' is not a decimal number in [%g, %g]", o, v, 0.0, 1e9);
    a->t_end = x, a->have_t_end = 1, ++*i;
  } else if (!strcmp(o, "--frames")) {
    SESSILE_CALL(parse_uint(o, v, 1, 100000, &u));
    a->frames = (int)u, ++*i;
  } else if (!strcmp(o, "--max-steps")) {
    SESSILE_CALL(parse_uint(o, v, 1, 4000000000u, &a->max_steps));
    ++*i;
  } else if (!strcmp(o, "--max-cells")) {
    SESSILE_CALL(parse_uint(o, v, 4, 50000000, &a->max_cells));
    ++*i;
  } else if (o[0] != '-') {
    SESSILE_CHECK(!a->model, SESSILE_ERR_USAGE, "unknown option or second model '%.60s'", o);
    a->model = o, *taken = 2;
  } else
    *taken = 0;
  return SESSILE_OK;
}

/* A new run: the model's text and parameters (the table's defaults, then
 * the model's NAME = value lines; --config and --set come after). */
static sessile_status sds_defaults(void *params, void *extra) {
  sds_gen_args *a = extra;
  SESSILE_CHECK(a->model, SESSILE_ERR_USAGE, "name a model: a shipped one (sessile sds models) or FILE.sds");
  SESSILE_CALL(read_model(a->model, &a->text));
  a->name = strdup(a->model);
  SESSILE_CHECK(a->name, SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (!a->max_cells) a->max_cells = SDS_MAX_CELLS;
  return sessile_sds_run_params_of_model(a->text, a->model, params);
}

/* Everything about the model that needs no device, before the run
 * directory; the frames are the loop's iterations. */
static sessile_status sds_schedule(const void *params, sessile_gen_setup *su) {
  sds_gen_args *a = su->extra;
  double t_end = a->have_t_end ? a->t_end : -1;
  SESSILE_CALL(sessile_sds_model_check(a->text, a->model, params, t_end, a->max_steps ? a->max_steps : SDS_MAX_STEPS));
  sessile_sds_model *m = NULL;
  int frames = 0;
  sessile_status s = sessile_sds_model_parse(a->text, a->name, &m);
  if (s == SESSILE_OK) s = sds_run_length(m, t_end, a->frames, &t_end, &frames);
  /* the loop on the device runs the rules' bytecode there: refused now, not
   * after the run directory exists */
  const char *why = s == SESSILE_OK && ((const sessile_sds_run_params *)params)->device_loop
                        ? sessile_sds_model_bytecode_refusal(m, 1) : NULL;
  if (why) s = sessile_error_set(SESSILE_ERR_USAGE, "device_loop: %s", why);
  sessile_sds_model_destroy(m);
  su->iterations = t_end > 0 ? frames : 0, su->every = 1;
  return s;
}

/* The run's configuration: the model (name and text) and the options as
 * given (-1: the model's), what --resume restarts from. */
static sessile_status sds_config_write(const void *extra, cJSON *c) {
  const sds_gen_args *a = extra;
  int ok = cJSON_AddStringToObject(c, "model", a->name) && cJSON_AddStringToObject(c, "model_text", a->text) &&
           cJSON_AddNumberToObject(c, "t_end", a->have_t_end ? a->t_end : -1) &&
           cJSON_AddNumberToObject(c, "frames", a->frames > 0 ? a->frames : -1) &&
           cJSON_AddNumberToObject(c, "max_cells", a->max_cells);
  SESSILE_CHECK(ok, SESSILE_ERR_NO_MEMORY, "out of host memory");
  return SESSILE_OK;
}

static sessile_status sds_config_read(void *extra, const cJSON *c) {
  sds_gen_args *a = extra;
  const cJSON *nm = cJSON_GetObjectItemCaseSensitive(c, "model");
  const cJSON *tx = cJSON_GetObjectItemCaseSensitive(c, "model_text"), *te = cJSON_GetObjectItemCaseSensitive(c, "t_end");
  const cJSON *fr = cJSON_GetObjectItemCaseSensitive(c, "frames"), *mc = cJSON_GetObjectItemCaseSensitive(c, "max_cells");
  int ok = cJSON_IsString(nm) && cJSON_IsString(tx) && cJSON_IsNumber(te) && cJSON_IsNumber(fr) && cJSON_IsNumber(mc) &&
           te->valuedouble <= 1e9 && fr->valuedouble >= -1 && fr->valuedouble <= 100000 &&
           fr->valuedouble == (int)fr->valuedouble && mc->valuedouble >= 4 && mc->valuedouble <= 50000000;
  SESSILE_CHECK(ok, SESSILE_ERR_USAGE, "the run's manifest holds no SDS configuration to resume from (damaged?)");
  if (a->model) { /* a MODEL given with --resume must be the run's own */
    char *given = NULL;
    SESSILE_CALL(read_model(a->model, &given));
    int same = !strcmp(given, tx->valuestring);
    free(given);
    SESSILE_CHECK(same, SESSILE_ERR_USAGE, "the run to resume is of another model ('%.60s'), not '%.60s'",
                  nm->valuestring, a->model);
  }
  a->name = strdup(nm->valuestring), a->text = strdup(tx->valuestring);
  SESSILE_CHECK(a->name && a->text, SESSILE_ERR_NO_MEMORY, "out of host memory");
  a->have_t_end = te->valuedouble >= 0, a->t_end = te->valuedouble;
  a->frames = (int)fr->valuedouble, a->max_cells = (unsigned)mc->valuedouble;
  return SESSILE_OK;
}

static void sds_extra_free(void *extra) {
  sds_gen_args *a = extra;
  if (!a->borrowed) free(a->name), free(a->text);
}

static void sds_out_dir(const void *extra, char *buf, size_t n) {
  const sds_gen_args *a = extra;
  const char *model = a->model ? a->model : "";
  const char *base = strrchr(model, '/') ? strrchr(model, '/') + 1 : model;
  snprintf(buf, n, "runs/sds-%.*s", (int)(strcspn(base, ".") ? strcspn(base, ".") : 1), base);
}

static sessile_status sds_create(const void *params, const sessile_gen_setup *su, void **state) {
  sds_gen_state *g = calloc(1, sizeof *g);
  SESSILE_CHECK(g, SESSILE_ERR_NO_MEMORY, "sds: out of host memory");
  g->su = su;
  sessile_status st = sds_gen_setup(g, params);
  /* a new run (or one whose checkpoint is gone): its model, frame 0, and
   * a checkpoint before the first step */
  if (st == SESSILE_OK && !sessile_run_checkpoint_loaded(su->run)) {
    sds_sim *s = &g->s;
    char path[4096];
    st = sessile_run_file(su->run, "sds/model.sds", path, sizeof path);
    if (st == SESSILE_OK) st = sessile_write_file_atomic(path, s->text, strlen(s->text));
    if (st == SESSILE_OK) st = sds_steplog_start(su->run);
    if (st == SESSILE_OK) st = sds_write_frame(s, su->run, 0, "sds/frame_0000.ply");
    if (st == SESSILE_OK) st = sds_record(s, su->run, 0, 0, 0);
    s->st->frames = s->frame = 1;
    s->frame_time[0] = s->time;
    if (st == SESSILE_OK) st = sds_write_pvd(su->run, 1, s->frame_time);
    sessile_ckpt_section sec[SDS_CKPT_NSECTIONS];
    int n = 0;
    if (st == SESSILE_OK) st = sds_sections(g, sec, &n);
    if (st == SESSILE_OK) st = sessile_run_checkpoint(su->run, 0, n, sec);
  }
  if (st != SESSILE_OK) {
    sds_teardown(&g->s);
    free(g);
    return st;
  }
  *state = g;
  return SESSILE_OK;
}

static sessile_status sds_restore(void *state, const sessile_ckpt *ck) {
  sds_gen_state *g = state;
  SESSILE_CALL(sds_gen_restore(g, ck));
  g->tf = sessile_wall_seconds();
  return SESSILE_OK;
}

/* Frame it: the steps to its time, its record. */
static sessile_status sds_step(void *state, int it, cJSON *rec) {
  sds_gen_state *g = state;
  sds_sim *s = &g->s;
  SESSILE_CHECK(s->frame == it, SESSILE_ERR_INTERNAL, "sds: frame %d in iteration %d", s->frame, it);
  SESSILE_CALL(sds_frame_steps(g));
  double now = sessile_wall_seconds();
  uint64_t n = s->steps_frame;
  SESSILE_CALL(sds_record_fill(s, rec, s->frame, 1e3 * (now - g->tf) / (double)(n ? n : 1), n));
  s->frame_time[s->frame] = s->time;
  s->st->frames = ++s->frame;
  g->tf = now, s->steps_frame = 0;
  return SESSILE_OK;
}

static sessile_status sds_snapshot(void *state, const char *rel) {
  sds_gen_state *g = state;
  SESSILE_CALL(sds_write_frame(&g->s, g->su->run, g->s.frame - 1, rel));
  return sds_write_pvd(g->su->run, g->s.frame, g->s.frame_time);
}

static sessile_status sds_gen_sections(void *state, sessile_ckpt_section *sec, int *n) {
  return sds_sections(state, sec, n);
}

static sessile_status sds_finish(void *state) {
  sds_gen_state *g = state;
  SESSILE_CALL(sds_write_pvd(g->su->run, g->s.frame, g->s.frame_time));
  SESSILE_CALL(sds_steplog_flush(&g->s, g->su->run));
  return sds_write_frame(&g->s, g->su->run, -1, "sds/final.ply");
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
  if (st->batches) { /* device_loop (docs/sds.md, "The loop on the device") */
    cJSON *d = cJSON_AddObjectToObject(js, "device_loop");
    if (d) {
      cJSON_AddNumberToObject(d, "batches", (double)st->batches);
      cJSON_AddNumberToObject(d, "host_completed_steps", (double)st->host_steps);
    }
  }
  cJSON_DeleteItemFromObjectCaseSensitive(m, "sds");
  cJSON_AddItemToObject(m, "sds", js);
}

/* Whatever the end: the steps up to a failure stay in the log (and the
 * failure's message stays), the manifest's sds member, the summary, and a
 * blow-up's own exit code (3, docs/sds.md "Blow-ups"). */
static sessile_status sds_end(void *state, sessile_status r, sessile_gen_result *res) {
  sds_gen_state *g = state;
  sds_sim *s = &g->s;
  sds_gen_args *a = g->su->extra;
  if (r != SESSILE_OK) {
    char why[1024];
    snprintf(why, sizeof why, "%s", sessile_error_message());
    if (sds_steplog_flush(s, g->su->run) != SESSILE_OK)
      sessile_error_set(r, "%s (and then: %s)", why, sessile_error_message());
    else
      sessile_error_set(r, "%s", why);
  }
  sessile_sds_run_stats *st = &g->st;
  st->wall_s = sessile_wall_seconds() - g->t0;
  st->time = s->time, st->cells = s->o.ncells, st->tets = s->o.ntets;
  st->resumed = s->resumed;
  manifest_sds(g->su->run, a->name ? a->name : "?", st, r);
  a->stats = *st;
  if (res) {
    res->exit_code = r == SESSILE_ERR_NUMERIC && st->blowup ? 3 : 0;
    snprintf(res->summary, sizeof res->summary,
             "sds %s: t = %g, %u cells, %u tets, %llu steps, %llu divisions, %llu inversions, %d frames in %.1f s",
             a->name, st->time, st->cells, st->tets, (unsigned long long)st->steps,
             (unsigned long long)st->divisions, (unsigned long long)st->inversions, st->frames, st->wall_s);
  }
  return r;
}

static void sds_destroy(void *state) {
  sds_gen_state *g = state;
  if (!g) return;
  sds_teardown(&g->s);
  free(g);
}

static int sds_needs_device(const void *params) {
  (void)params;
  return 1;
}

const sessile_generator sessile_gen_sds = {
    .name = "sds run",
    .generator = "sds",
    .summary = "SDS, a tetrahedral developmental system",
    .about = "Grows a form with SDS (Porter & McCormack).",
    .seed_help = "the random choices",
    .out_default = "runs/sds",
    .snapshot_name = "sds/frame_%04d.ply",
    .preview = "sds/final.ply",
    .table = &sessile_sds_run_param_table,
    .iterations = 1,
    .every = 1,
    .needs_device = sds_needs_device,
    .create = sds_create,
    .restore = sds_restore,
    .step = sds_step,
    .snapshot = sds_snapshot,
    .sections = sds_gen_sections,
    .finish = sds_finish,
    .destroy = sds_destroy,
    .help = help,
    .no_iterations = "--iterations and --every do not apply: the model runs to its t_end (--t-end), in frames "
                     "(--frames)",
    .extra_size = sizeof(sds_gen_args),
    .arg = sds_arg,
    .defaults = sds_defaults,
    .schedule = sds_schedule,
    .config_write = sds_config_write,
    .config_read = sds_config_read,
    .extra_free = sds_extra_free,
    .out_dir = sds_out_dir,
    .end = sds_end,
    .progress_unit = "frame",
};

sessile_status sessile_sds_run(const sessile_sds_run_options *opt, sessile_sds_run_stats *st) {
  memset(st, 0, sizeof *st);
  SESSILE_CHECK(opt->run && opt->gpu && opt->model_text, SESSILE_ERR_USAGE,
                "sessile sds run needs a run, a device and a model");
  sds_gen_args a = {.model = opt->model_name, .name = (char *)(opt->model_name ? opt->model_name : "model"),
                    .text = (char *)opt->model_text, .borrowed = 1, .t_end = opt->t_end,
                    .have_t_end = opt->t_end >= 0, .frames = opt->frames, .max_cells = opt->max_cells};
  sessile_sds_run_params p;
  if (opt->params) p = *opt->params;
  else SESSILE_CALL(sessile_sds_run_params_of_model(opt->model_text, a.name, &p));
  sessile_sds_model *m = NULL;
  double t_end = 0;
  int frames = 0, done = 0;
  sessile_status s = sessile_sds_model_parse(opt->model_text, a.name, &m);
  if (s == SESSILE_OK) s = sds_run_length(m, a.have_t_end ? a.t_end : -1, a.frames, &t_end, &frames);
  sessile_sds_model_destroy(m);
  SESSILE_CALL(s);
  sessile_gen_setup su = {.run = opt->run, .gpu = opt->gpu, .seed = opt->seed,
                          .iterations = t_end > 0 ? frames : 0, .every = 1, .extra = &a};
  s = sessile_run_loop(&sessile_gen_sds, &p, &su, NULL, NULL, &done);
  *st = a.stats;
  return s;
}
