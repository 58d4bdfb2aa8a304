/* A generator that exists only in the test tree: N walkers on a line take
 * seeded uniform steps; snapshots and the final state are CSV files.  It
 * shows what adding a generator takes: this folder and one line of
 * generators.def (tests/CMakeLists.txt builds the CLI with that line). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/run/generator.h"
#include "sessile/io/io.h"
#include "sessile/rng.h"

typedef struct walk_params {
  int walkers;
  double step;
} walk_params;

static const sessile_param_desc descs[] = {
    {"walkers", SESSILE_PT_INT, offsetof(walk_params, walkers), 8, 1, 1000, 0, "", "test", "walkers on the line", NULL},
    {"step", SESSILE_PT_REAL, offsetof(walk_params, step), 0.5, 0, 10, SESSILE_PARAM_LO_OPEN, "cm", "test",
     "largest step per iteration", NULL},
};
static const sessile_param_table table = {"testwalk", sizeof(walk_params), 2, descs, NULL, NULL, NULL};

typedef struct walk {
  walk_params p;
  sessile_run *run;
  uint64_t rng;
  double x[1000];
} walk;

static sessile_status create(const void *params, const sessile_gen_setup *su, void **state) {
  walk *w = calloc(1, sizeof *w);
  SESSILE_CHECK(w, SESSILE_ERR_NO_MEMORY, "out of host memory");
  w->p = *(const walk_params *)params, w->run = su->run, w->rng = su->seed;
  *state = w;
  return SESSILE_OK;
}

static sessile_status sections(void *state, sessile_ckpt_section *sec, int *n) {
  walk *w = state;
  sec[0] = (sessile_ckpt_section){"rng", &w->rng, sizeof w->rng};
  sec[1] = (sessile_ckpt_section){"x", w->x, (size_t)w->p.walkers * sizeof *w->x};
  *n = 2;
  return SESSILE_OK;
}

static sessile_status restore(void *state, const sessile_ckpt *ck) {
  walk *w = state;
  SESSILE_CALL(sessile_ckpt_take(ck, "rng", &w->rng, sizeof w->rng));
  return sessile_ckpt_take(ck, "x", w->x, (size_t)w->p.walkers * sizeof *w->x);
}

static sessile_status step(void *state, int it, cJSON *rec) {
  walk *w = state;
  double far = 0;
  for (int i = 0; i < w->p.walkers; i++) {
    w->x[i] += sessile_rng_range(&w->rng, -w->p.step, w->p.step);
    far = w->x[i] > far ? w->x[i] : -w->x[i] > far ? -w->x[i] : far;
  }
  cJSON_AddNumberToObject(rec, "farthest_cm", far);
  return SESSILE_OK;
}

static sessile_status snapshot(void *state, const char *rel) {
  walk *w = state;
  char path[4096], text[1000 * 32 + 16];
  size_t len = (size_t)snprintf(text, sizeof text, "x\n");
  for (int i = 0; i < w->p.walkers; i++) len += (size_t)snprintf(text + len, sizeof text - len, "%.17g\n", w->x[i]);
  SESSILE_CALL(sessile_run_file(w->run, rel, path, sizeof path));
  return sessile_write_file_atomic(path, text, len);
}

static sessile_status finish(void *state) { return snapshot(state, "walk/final.csv"); }
static void destroy(void *state) { free(state); }

const sessile_generator sessile_gen_testwalk = {
    .name = "testwalk",
    .summary = "a test-only generator: seeded walkers on a line (tests/run/testgen)",
    .about = "Walkers on a line take seeded uniform steps.  Writes walk/iter_NNNN.csv every K\n"
    "iterations and at the last, and walk/final.csv.",
    .seed_help = "the steps",
    .out_default = "runs/testwalk",
    .snapshot_name = "walk/iter_%04d.csv",
    .table = &table,
    .iterations = 6,
    .every = 2,
    SESSILE_GEN_CALLBACKS,
};
