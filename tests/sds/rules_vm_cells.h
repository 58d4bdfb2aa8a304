/* Seeded random cells for the rules' bytecode tests (test_rules_vm.c): a
 * jittered nx x ny x nz lattice with its 6-neighbour lists, radii, amounts
 * spread over [0, vol] (timers over [0, 0.2]), states 0 or 1 for names that
 * act as flags and random values for the rest (birth_radius below the
 * radius by up to 1.5x), and the bitwise comparison of two evaluations. */
#ifndef RULES_VM_CELLS_H
#define RULES_VM_CELLS_H
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/rng.h"
#include "sessile/sds/sds_process.h"
#include "testutil.h"

typedef struct rvm_cells {
  int n, nm, ns;
  double *pos, *r, *phi, *state;
  uint32_t *off, *nbr;
  uint8_t *surf;
} rvm_cells;

static inline rvm_cells rvm_cells_make(const sessile_sds_model *m, int nx, int ny, int nz, uint64_t seed) {
  rvm_cells C;
  memset(&C, 0, sizeof C);
  C.n = nx * ny * nz, C.nm = sessile_sds_model_nmorph(m), C.ns = sessile_sds_model_nstate(m);
  uint64_t s = sessile_rng_stream(seed, 33);
  C.pos = t_dalloc(3 * (size_t)C.n), C.r = t_dalloc((size_t)C.n);
  C.phi = t_dalloc((size_t)C.n * (C.nm ? C.nm : 1)), C.state = t_dalloc((size_t)C.n * (C.ns ? C.ns : 1));
  C.off = t_xalloc(((size_t)C.n + 1) * 4), C.nbr = t_xalloc(6 * (size_t)C.n * 4), C.surf = t_xalloc((size_t)C.n);
  uint32_t e = 0;
  for (int c = 0; c < C.n; c++) {
    int i = c % nx, j = c / nx % ny, k = c / (nx * ny);
    C.pos[3 * c] = i + sessile_rng_range(&s, -0.2, 0.2);
    C.pos[3 * c + 1] = j + sessile_rng_range(&s, -0.2, 0.2);
    C.pos[3 * c + 2] = k + sessile_rng_range(&s, -0.2, 0.2);
    C.r[c] = sessile_rng_range(&s, 0.2, 0.8);
    C.surf[c] = i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1;
    C.off[c] = e;
    if (i > 0) C.nbr[e++] = (uint32_t)(c - 1);
    if (i < nx - 1) C.nbr[e++] = (uint32_t)(c + 1);
    if (j > 0) C.nbr[e++] = (uint32_t)(c - nx);
    if (j < ny - 1) C.nbr[e++] = (uint32_t)(c + nx);
    if (k > 0) C.nbr[e++] = (uint32_t)(c - nx * ny);
    if (k < nz - 1) C.nbr[e++] = (uint32_t)(c + nx * ny);
  }
  C.off[C.n] = e;
  sessile_morph_coef co = sessile_sds_model_coef(m);
  for (int c = 0; c < C.n; c++) {
    double v = sessile_morph_vol(C.r[c]);
    for (int k = 0; k < C.nm; k++) {
      double u = sessile_rng_range(&s, 0, 1);
      C.phi[c * C.nm + k] = co.capped[k] ? v * u * u * u : 0.2 * u;
    }
    for (int k = 0; k < C.ns; k++) {
      const char *nm = sessile_sds_model_state_name(m, k);
      double u = sessile_rng_range(&s, 0, 1);
      if (!strcmp(nm, "birth_radius"))
        C.state[c * C.ns + k] = C.r[c] / (1 + 0.5 * u);
      else if (nm[0] == 's' && nm[1] >= '0' && nm[1] <= '9')
        C.state[c * C.ns + k] = 4 * u - 1;
      else
        C.state[c * C.ns + k] = u < 0.3; /* tip, stripe, budcell */
    }
  }
  return C;
}

static inline sessile_morph_cells rvm_morph_cells(const rvm_cells *C) {
  return (sessile_morph_cells){C->n, C->pos, C->r, C->off, C->nbr, C->surf};
}

static inline void rvm_cells_free(rvm_cells *C) {
  free(C->pos), free(C->r), free(C->phi), free(C->state), free(C->off), free(C->nbr), free(C->surf);
}

static inline int rvm_same(const char *what, const void *a, const void *b, size_t bytes) {
  if (!memcmp(a, b, bytes)) return 1;
  printf("  %s differ\n", what);
  return 0;
}

/* Both evaluations at `time`: every action the same bits. */
static inline int rvm_same_actions(const sessile_sds_model *m, const rvm_cells *C, double time) {
  sessile_morph_cells cl = rvm_morph_cells(C);
  sessile_sds_actions a = {0}, b = {0};
  sessile_status sa = sessile_sds_rules_eval(m, &cl, C->phi, C->state, time, &a);
  sessile_status sb = sessile_sds_rules_eval_vm(m, &cl, C->phi, C->state, time, &b);
  int ok = sa == SESSILE_OK && sb == SESSILE_OK;
  if (!ok) printf("  status %d and %d: %s\n", sa, sb, sessile_error_message());
  ok = ok && rvm_same("growth", a.grow, b.grow, (size_t)C->n * sizeof *a.grow);
  ok = ok && rvm_same("sources", a.produce, b.produce, (size_t)C->n * C->nm * sizeof *a.produce);
  ok = ok && a.nsets == b.nsets && a.ndivides == b.ndivides && a.fired == b.fired;
  for (size_t i = 0; ok && i < a.nsets; i++) /* field by field: the struct has padding */
    ok = a.sets[i].cell == b.sets[i].cell && a.sets[i].kind == b.sets[i].kind && a.sets[i].target == b.sets[i].target &&
         rvm_same("sets", &a.sets[i].value, &b.sets[i].value, sizeof a.sets[i].value);
  if (!ok && a.nsets == b.nsets)
    for (size_t i = 0; i < a.nsets; i++)
      if (memcmp(&a.sets[i].value, &b.sets[i].value, sizeof(double))) {
        printf("  first: cell %d target %d: %a against %a\n", a.sets[i].cell, a.sets[i].target, a.sets[i].value,
               b.sets[i].value);
        break;
      }
  for (size_t i = 0; ok && i < a.ndivides; i++)
    ok = a.divides[i].cell == b.divides[i].cell && a.divides[i].rule == b.divides[i].rule &&
         rvm_same("divisions", a.divides[i].dir, b.divides[i].dir, sizeof a.divides[i].dir);
  if (ok) printf("  %zu firings, %zu sets, %zu divisions\n", a.fired, a.nsets, a.ndivides);
  sessile_sds_actions_free(&a), sessile_sds_actions_free(&b);
  return ok;
}
#endif
