/* The one iteration loop every generator runs through (sessile/run/generator.h):
 * what used to be copied into each generator (resume, records, snapshots,
 * checkpoints, stop requests) lives here once. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "run_internal.h"

int sessile_gen_snapshot_kind(const sessile_gen_setup *su, int it) {
  if (su->every > 0 && it % su->every == 0) return 1;
  return it == su->iterations ? 2 : 0;
}

cJSON *sessile_gen_config(const sessile_generator *g, const void *params, const sessile_gen_setup *su) {
  cJSON *c = sessile_run_config_make(g->table, params, su->seed, su->iterations, su->every);
  int ok = c != NULL;
  for (int k = 0; ok && k < g->nflags; k++) ok = cJSON_AddBoolToObject(c, g->flags[k].key, (su->flags >> k) & 1u) != NULL;
  for (int k = 0; ok && k < g->noptions && k < SESSILE_GEN_MAX_OPTIONS; k++)
    ok = cJSON_AddStringToObject(c, g->options[k].key, su->values[k] ? su->values[k] : "") != NULL;
  if (ok && g->presets) ok = cJSON_AddStringToObject(c, "preset", su->preset ? su->preset : "") != NULL;
  if (ok && g->config_write) ok = g->config_write(su->extra, c) == SESSILE_OK;
  if (!ok) cJSON_Delete(c);
  return ok ? c : NULL;
}

/* A text member of a stored configuration. */
static sessile_status config_text(const cJSON *cfg, const char *key, const char **out) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(cfg, key);
  SESSILE_CHECK(cJSON_IsString(v), SESSILE_ERR_USAGE, "the run's stored configuration is damaged (no '%s')", key);
  *out = v->valuestring;
  return SESSILE_OK;
}

sessile_status sessile_gen_config_read(const sessile_generator *g, const cJSON *cfg, void *params,
                                       sessile_gen_setup *su) {
  uint64_t seed = 0;
  SESSILE_CALL(sessile_run_config_take(cfg, g->table, params, &seed, &su->iterations, &su->every));
  su->seed = seed;
  su->flags = 0;
  for (int k = 0; k < g->nflags; k++) {
    const cJSON *f = cJSON_GetObjectItemCaseSensitive(cfg, g->flags[k].key);
    SESSILE_CHECK(cJSON_IsBool(f), SESSILE_ERR_USAGE, "the run's stored configuration is damaged (no '%s')",
                  g->flags[k].key);
    if (cJSON_IsTrue(f)) su->flags |= 1u << k;
  }
  for (int k = 0; k < g->noptions && k < SESSILE_GEN_MAX_OPTIONS; k++)
    SESSILE_CALL(config_text(cfg, g->options[k].key, &su->values[k]));
  if (g->presets) SESSILE_CALL(config_text(cfg, "preset", &su->preset));
  return g->config_read ? g->config_read(su->extra, cfg) : SESSILE_OK;
}

static sessile_status snapshot_rel(const sessile_generator *g, int it, char *rel, size_t n) {
  int k = snprintf(rel, n, g->snapshot_name, it);
  SESSILE_CHECK(k > 0 && (size_t)k < n, SESSILE_ERR_INTERNAL, "%s: snapshot name too long", g->name);
  return SESSILE_OK;
}

/* Removes the final-only snapshot of iteration k. */
static sessile_status unsnapshot(const sessile_generator *g, void *state, sessile_run *run, int k) {
  if (g->unsnapshot) return g->unsnapshot(state, k);
  char rel[256];
  SESSILE_CALL(snapshot_rel(g, k, rel, sizeof rel));
  SESSILE_CALL(sessile_run_remove_file(run, rel));
  size_t l = strlen(rel); /* a surface's .vtp beside its PLY (run_mesh.c) */
  if (l <= 4 || strcmp(rel + l - 4, ".ply")) return SESSILE_OK;
  memcpy(rel + l - 4, ".vtp", 4);
  return sessile_run_remove_file(run, rel);
}

static sessile_status checkpoint(const sessile_generator *g, void *state, sessile_run *run, int it) {
  sessile_ckpt_section sec[SESSILE_GEN_MAX_SECTIONS];
  int n = 0;
  SESSILE_CALL(g->sections(state, sec, &n));
  SESSILE_CHECK(n >= 0 && n <= SESSILE_GEN_MAX_SECTIONS, SESSILE_ERR_INTERNAL, "%s: %d checkpoint sections",
                g->name, n);
  return sessile_run_checkpoint(run, it, n, sec);
}

static sessile_status one_iteration(const sessile_generator *g, void *state, const sessile_gen_setup *su,
                                    int it, int *snap) {
  cJSON *rec = cJSON_CreateObject();
  SESSILE_CHECK(rec && cJSON_AddNumberToObject(rec, "iteration", it), SESSILE_ERR_NO_MEMORY,
                "out of host memory for a record");
  sessile_status s = g->step(state, it, rec);
  if (s == SESSILE_ERR_INTERRUPTED && su->run) { /* stopped part way: the state so far, as iteration it - 1 */
    char why[512];
    snprintf(why, sizeof why, "%s", sessile_error_message());
    cJSON_Delete(rec);
    SESSILE_CALL(checkpoint(g, state, su->run, it - 1));
    return sessile_error_set(SESSILE_ERR_INTERRUPTED, "%s", why);
  }
  if (s == SESSILE_OK && su->run) s = sessile_run_record(su->run, rec);
  cJSON_Delete(rec);
  SESSILE_CALL_AT(s, "iteration %d", it);
  *snap = su->run && sessile_gen_snapshot_kind(su, it);
  if (*snap) {
    char rel[256];
    SESSILE_CALL(snapshot_rel(g, it, rel, sizeof rel));
    sessile_run_set_iteration(su->run, it); /* what its mesh files say (run_mesh.c) */
    sessile_status ss = g->snapshot(state, rel);
    sessile_run_set_iteration(su->run, -1);
    SESSILE_CALL_AT(ss, "iteration %d: snapshot %s", it, rel);
  }
  return SESSILE_OK;
}

static sessile_status loop(const sessile_generator *g, void *state, const sessile_gen_setup *su, int *done) {
  sessile_run *run = su->run;
  const sessile_ckpt *ck = run ? sessile_run_checkpoint_loaded(run) : NULL;
  int first = 1;
  if (ck) {
    int k = sessile_ckpt_iteration(ck);
    SESSILE_CHECK(k <= su->iterations, SESSILE_ERR_USAGE,
                  "the run's checkpoint is at iteration %d: --iterations must be at least %d", k, k);
    SESSILE_CALL_AT(g->restore(state, ck), "resuming from the checkpoint of iteration %d", k);
    first = k + 1;
    *done = k;
    /* the old last iteration was a snapshot only because it was the last */
    if (k < su->iterations && sessile_gen_snapshot_kind(su, k) != 1) SESSILE_CALL(unsnapshot(g, state, run, k));
  }
  for (int it = first; it <= su->iterations; it++) {
    int snap = 0;
    run_progress_begin(su, it);
    SESSILE_CALL(one_iteration(g, state, su, it, &snap));
    *done = it;
    int stop = run ? sessile_run_stop_requested(run) : 0;
    /* the memory budget is checked between iterations: over it, the run
     * stops with its state saved, before the machine's OOM killer ends it */
    double rss = su->max_memory > 0 && run ? sessile_process_memory() : 0;
    int over = rss > su->max_memory && su->max_memory > 0 && run && it < su->iterations;
    if (snap || stop || over) SESSILE_CALL_AT(checkpoint(g, state, run, it), "checkpoint at iteration %d", it);
    run_progress_end(su, it);
    if (stop && it < su->iterations)
      return sessile_error_set(SESSILE_ERR_INTERRUPTED, "stopped by signal %d after iteration %d", stop, it);
    SESSILE_CHECK(!over, SESSILE_ERR_TOO_LARGE,
                  "after iteration %d the run holds %.2f GiB, over its memory budget of %.2f GiB "
                  "(--max-memory): its state is saved; resume it with a larger --max-memory, or "
                  "change the parameters that make it grow", it, rss / 1073741824.0, su->max_memory / 1073741824.0);
  }
  sessile_run_set_iteration(run, su->iterations);
  run_progress_finish(su, 0);
  sessile_status fs = g->finish(state);
  sessile_run_set_iteration(run, -1);
  SESSILE_CALL_AT(fs, "final outputs");
  run_progress_finish(su, 1);
  return SESSILE_OK;
}

sessile_status sessile_run_loop(const sessile_generator *g, const void *params, const sessile_gen_setup *setup,
                                sessile_progress_fn progress, void *user, int *done) {
  /* the generator keeps su until destroy, within this call: a copy that
   * carries this loop's meter */
  sessile_gen_meter meter = {.fn = progress, .user = user, .unit = g->progress_unit ? g->progress_unit : "iteration"};
  sessile_gen_setup own = *setup;
  own.meter = &meter;
  const sessile_gen_setup *su = &own;
  *done = 0;
  SESSILE_CALL(sessile_params_check(g->table, params));
  if (su->run) {
    cJSON *m = sessile_run_manifest(su->run);
    cJSON *pj = sessile_params_to_json(g->table, params);
    SESSILE_CHECK(pj, SESSILE_ERR_NO_MEMORY, "out of host memory for the manifest");
    cJSON_DeleteItemFromObjectCaseSensitive(m, "parameters");
    cJSON_AddItemToObject(m, "parameters", pj);
  }
  void *state = NULL; /* a create that failed after setting it is destroyed too */
  sessile_status s = g->create(params, su, &state);
  if (s != SESSILE_OK) {
    g->destroy(state);
    return sessile_error_pass(s, "setting up");
  }
  s = loop(g, state, su, done);
  if (g->end) s = g->end(state, s, su->result);
  g->destroy(state);
  return s;
}

double sessile_process_memory(void) {
  /* resident set size: the second field of /proc/self/statm, in pages */
  FILE *f = fopen("/proc/self/statm", "r");
  unsigned long long size = 0, resident = 0;
  int ok = f && fscanf(f, "%llu %llu", &size, &resident) == 2;
  if (f) fclose(f);
  long page = sysconf(_SC_PAGESIZE);
  return ok && page > 0 ? (double)resident * (double)page : 0;
}

double sessile_physical_memory(void) {
  long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? (double)pages * (double)page : 0;
}
