/* `coral lsystem` on the run framework (sessile/run/generator.h), for the
 * callers that run generators by their table: the reef's pool
 * (docs/reef.md, "Organisms").  The command `sessile coral lsystem` keeps
 * its own driver (cmd_coral_lsystem.c: grammar files, --define, no resume)
 * and its bytes; both call sessile_coral_lsystem_build and _write.
 *
 * The shipped grammar of the `grammar` parameter; the run's iterations are
 * the derivation steps (0: the grammar's), done in one loop iteration (a
 * derivation has no state worth a checkpoint: it runs in seconds). */
#include <stdio.h>
#include <stdlib.h>
#include "sessile/coral/lsystem.h"

typedef struct lsys_gen_args {
  int derivations; /* -1: the grammar's */
} lsys_gen_args;

typedef struct lsys_gen {
  const sessile_gen_setup *su;
  const sessile_coral_lsystem_params *p;
  sessile_lsys *g;
  const char *name, *text;
  size_t len;
  sessile_coral_lsystem_result r;
  uint32_t built;
} lsys_gen;

static sessile_status schedule(const void *params, sessile_gen_setup *su) {
  (void)params;
  lsys_gen_args *a = su->extra;
  SESSILE_CHECK(a, SESSILE_ERR_INTERNAL, "coral lsystem: no options");
  SESSILE_CHECK(su->iterations >= 0 && su->iterations <= 1000, SESSILE_ERR_USAGE,
                "coral lsystem: %d derivation steps: at most 1000", su->iterations);
  a->derivations = su->iterations ? su->iterations : -1;
  su->iterations = 1;
  return SESSILE_OK;
}

static int needs_device(const void *params) { return ((const sessile_coral_lsystem_params *)params)->geometry == 1; }

static sessile_status create(const void *params, const sessile_gen_setup *su, void **state) {
  lsys_gen *s = calloc(1, sizeof *s);
  SESSILE_CHECK(s, SESSILE_ERR_NO_MEMORY, "out of host memory");
  *state = s;
  s->su = su, s->p = params;
  s->name = sessile_coral_lsystem_param_table.params[0].names[s->p->grammar];
  s->text = sessile_lsys_builtin_find(s->name, &s->len);
  SESSILE_CHECK(s->text, SESSILE_ERR_INTERNAL, "the grammar '%s' is not embedded", s->name);
  char where[64];
  snprintf(where, sizeof where, "%s.lsys", s->name);
  return sessile_lsys_parse(s->text, s->len, where, 0, NULL, NULL, &s->g);
}

static sessile_status restore(void *state, const sessile_ckpt *ck) {
  (void)state, (void)ck;
  return sessile_error_set(SESSILE_ERR_USAGE, "an L-system run has no iterations to resume");
}

static sessile_status step(void *state, int it, cJSON *rec) {
  lsys_gen *s = state;
  const lsys_gen_args *a = s->su->extra;
  (void)it;
  sessile_coral_lsystem_result_free(&s->r);
  SESSILE_CALL(sessile_coral_lsystem_build(s->p, s->g, a ? a->derivations : -1, s->su->seed, s->su->gpu, NULL, &s->r));
  s->built = 1;
  SESSILE_CHECK(cJSON_AddNumberToObject(rec, "modules", s->r.str.n), SESSILE_ERR_NO_MEMORY, "out of host memory");
  return SESSILE_OK;
}

/* The mesh is written once, by finish. */
static sessile_status snapshot(void *state, const char *rel) {
  (void)state, (void)rel;
  return SESSILE_OK;
}

static sessile_status sections(void *state, sessile_ckpt_section *sec, int *n) {
  (void)state, (void)sec;
  *n = 0;
  return SESSILE_OK;
}

static sessile_status finish(void *state) {
  lsys_gen *s = state;
  if (!s->su->run) return SESSILE_OK; /* a library caller without files */
  SESSILE_CHECK(s->built, SESSILE_ERR_INTERNAL, "coral lsystem: finish before the derivation");
  return sessile_coral_lsystem_write(s->su->run, s->p, s->g, s->name, s->text, s->len, &s->r, s->su->gpu, NULL);
}

static void destroy(void *state) {
  lsys_gen *s = state;
  if (!s) return;
  sessile_coral_lsystem_result_free(&s->r);
  sessile_lsys_destroy(s->g);
  free(s);
}

const sessile_generator sessile_gen_coral_lsystem = {
    .name = "coral lsystem",
    .summary = "stony corals from a stochastic parametric L-system (Coralize §3.1)",
    .about = "A shipped grammar derived N times (the run's iterations; 0: the grammar's),\n"
             "drawn by a 3-D turtle and meshed (docs/lsystem.md).",
    .seed_help = "every random choice", .out_default = "runs/coral-lsystem",
    .snapshot_name = "coral/final.ply", .preview = "coral/final.ply", .table = &sessile_coral_lsystem_param_table,
    .iterations = 0, .every = 0, .needs_device = needs_device,
    .extra_size = sizeof(lsys_gen_args), .schedule = schedule,
    SESSILE_GEN_CALLBACKS,
};
