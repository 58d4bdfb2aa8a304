/* Fuzz target of the SDS process-model parser and rule evaluation
 * (sessile/sds/sds_process.h, docs/sds_rules.md): the input is a model text.  A
 * refused model must give SESSILE_ERR_USAGE and no handle, with one line
 * "fuzz.sds:LINE:COLUMN: ..." (LINE within the input's lines, COLUMN >= 1);
 * an accepted one is evaluated on a 3x3x3 lattice of cells (random amounts
 * and states) and every action must be well-formed: targets in range,
 * finite values, unit or zero division directions, at most one division per
 * cell.  The rules' bytecode (docs/sds_rules.md, "Bytecode") must give the
 * same status and, when it evaluates, the same actions bit for bit; a model
 * it does not compile must say why in one line naming fuzz.sds; one the
 * device accepts must compile as the generated rules kernel.  Anything
 * else aborts.  Built with driver.c (-DFUZZ_WORDS) by CMake's
 * fuzz_sds_short, or with libFuzzer like the other targets. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/sds/sds_process.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void fail(const char *what) {
  fprintf(stderr, "fuzz_sds: %s (last message: %s)\n", what, sessile_error_message());
  abort();
}

static void check_refusal(const char *text) {
  const char *m = sessile_error_message();
  if (strncmp(m, "fuzz.sds:", 9)) fail("a refusal without 'fuzz.sds:'");
  if (strchr(m, '\n')) fail("a refusal of more than one line");
  long line = 0, col = 0;
  char tail = 0;
  if (sscanf(m + 9, "%ld:%ld%c", &line, &col, &tail) != 3) fail("a refusal without line and column");
  long lines = 1;
  for (const char *p = text; *p; p++) lines += *p == '\n';
  if (line < 1 || line > lines || col < 1 || tail != ':') fail("a refusal's line or column outside the input");
}

static int same_bits(const double *x, const double *y, size_t n) { return !n || !memcmp(x, y, n * sizeof *x); }

/* The bytecode's evaluation of the same cells against muparser's (status s,
 * actions a): the same status, message and actions. */
static void same_as_bytecode(const sessile_sds_model *m, const sessile_morph_cells *cl, const double *phi,
                             const double *state, sessile_status s, const sessile_sds_actions *a) {
  const char *why = sessile_sds_model_bytecode_refusal(m, 0);
  if (why) {
    if (strncmp(why, "fuzz.sds:", 9) || strchr(why, '\n') || !strstr(why, ": rule "))
      fail("a bytecode refusal without file, line and rule");
    return;
  }
  char host_msg[512];
  snprintf(host_msg, sizeof host_msg, "%s", sessile_error_message());
  sessile_sds_actions b = {0};
  sessile_status t = sessile_sds_rules_eval_vm(m, cl, phi, state, 1.5, &b);
  if (t != s) fail("the bytecode's status differs from muparser's");
  if (s != SESSILE_OK && strcmp(host_msg, sessile_error_message()))
    fail("the bytecode's message differs from muparser's");
  if (s == SESSILE_OK) {
    int nm = sessile_sds_model_nmorph(m), ok = a->nsets == b.nsets && a->ndivides == b.ndivides && a->fired == b.fired;
    ok = ok && same_bits(a->grow, b.grow, (size_t)cl->ncells) &&
         same_bits(a->produce, b.produce, (size_t)cl->ncells * nm);
    for (size_t i = 0; ok && i < a->nsets; i++)
      ok = a->sets[i].cell == b.sets[i].cell && a->sets[i].target == b.sets[i].target &&
           a->sets[i].kind == b.sets[i].kind && same_bits(&a->sets[i].value, &b.sets[i].value, 1);
    for (size_t i = 0; ok && i < a->ndivides; i++)
      ok = a->divides[i].cell == b.divides[i].cell && same_bits(a->divides[i].dir, b.divides[i].dir, 3);
    if (!ok) fail("the bytecode's actions differ from muparser's");
  }
  sessile_sds_actions_free(&b);
}

static void evaluate(const sessile_sds_model *m) {
  enum { N = 27 };
  double pos[3 * N], radius[N], phi[N * 16], state[N * 32];
  uint32_t off[N + 1], nbr[6 * N], e = 0;
  int nm = sessile_sds_model_nmorph(m), ns = sessile_sds_model_nstate(m);
  uint64_t r = 12345;
  for (int c = 0; c < N; c++) {
    int i = c % 3, j = c / 3 % 3, k = c / 9;
    pos[3 * c] = i, pos[3 * c + 1] = j, pos[3 * c + 2] = k;
    radius[c] = 0.3 + 0.01 * c;
    off[c] = e;
    if (i > 0) nbr[e++] = (uint32_t)(c - 1);
    if (i < 2) nbr[e++] = (uint32_t)(c + 1);
    if (j > 0) nbr[e++] = (uint32_t)(c - 3);
    if (j < 2) nbr[e++] = (uint32_t)(c + 3);
    if (k > 0) nbr[e++] = (uint32_t)(c - 9);
    if (k < 2) nbr[e++] = (uint32_t)(c + 9);
  }
  off[N] = e;
  for (int i = 0; i < N * 16; i++) r = r * 6364136223846793005u + 1442695040888963407u, phi[i] = (r >> 40) * 1e-8;
  for (int i = 0; i < N * 32; i++) state[i] = i % 3 == 0;
  sessile_morph_cells cl = {N, pos, radius, off, nbr, NULL};
  sessile_sds_actions a = {0};
  sessile_status s = sessile_sds_rules_eval(m, &cl, phi, state, 1.5, &a);
  if (s != SESSILE_OK && s != SESSILE_ERR_NUMERIC) fail("an unexpected status from the evaluation");
  same_as_bytecode(m, &cl, phi, state, s, &a);
  if (s == SESSILE_OK) {
    for (size_t i = 0; i < a.nsets; i++) {
      const sessile_sds_set *q = &a.sets[i];
      int lim = q->kind == SESSILE_SDS_SET_STATE ? ns : nm;
      if (q->cell < 0 || q->cell >= N || q->target < 0 || q->target >= lim || !isfinite(q->value))
        fail("a malformed set action");
    }
    for (int c = 0; c < N; c++) {
      if (!isfinite(a.grow[c])) fail("a non-finite growth rate");
      for (int k = 0; k < nm; k++)
        if (!isfinite(a.produce[c * nm + k])) fail("a non-finite source rate");
    }
    for (size_t i = 0; i < a.ndivides; i++) {
      const sessile_sds_divide *d = &a.divides[i];
      double l = sqrt(d->dir[0] * d->dir[0] + d->dir[1] * d->dir[1] + d->dir[2] * d->dir[2]);
      if (d->cell < 0 || d->cell >= N || (i && d->cell <= a.divides[i - 1].cell)) fail("divisions out of order");
      if (!(l == 0 || fabs(l - 1) < 1e-12)) fail("a division direction neither unit nor zero");
    }
    double dt = 0.1;
    sessile_sds_actions_apply(m, &a, dt, radius, phi, state);
  }
  sessile_sds_actions_free(&a);
}

/* The rules' generated kernel (docs/sds_rules.md, "Generated kernel"):
 * every model the device accepts is written out as GLSL and compiled by
 * glslang; it must compile (a failure is a fault of the writer), into a
 * SPIR-V module (its magic word).  The first 400 such models of a run only:
 * glslang takes milliseconds a model, the rest of a case microseconds. */
static void generated_kernel(const sessile_sds_model *m) {
  static int compiled;
  if (sessile_sds_model_bytecode_refusal(m, 1) || compiled >= 400) return;
  compiled++;
  uint32_t *w = NULL;
  size_t n = 0;
  if (sessile_sds_model_rules_spirv(m, &w, &n) != SESSILE_OK) fail("the generated rules kernel did not compile");
  if (n < 5 || w[0] != 0x07230203u) fail("the generated rules kernel is not SPIR-V");
  free(w);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *text = malloc(size + 1);
  if (!text) return 0;
  memcpy(text, data, size);
  text[size] = 0;
  sessile_sds_model *m = NULL;
  sessile_status s = sessile_sds_model_parse(text, "fuzz.sds", &m);
  if (s != SESSILE_OK) {
    if (m) fail("a refused model returned a handle");
    if (s != SESSILE_ERR_USAGE && s != SESSILE_ERR_NO_MEMORY) fail("an unexpected status from the parser");
    if (s == SESSILE_ERR_USAGE) check_refusal(text);
  } else {
    if (sessile_sds_model_nmorph(m) > 16 || sessile_sds_model_nstate(m) > 32 || sessile_sds_model_nrules(m) < 1)
      fail("model counts out of range");
    evaluate(m);
    generated_kernel(m);
    sessile_sds_model_destroy(m);
  }
  free(text);
  return 0;
}
