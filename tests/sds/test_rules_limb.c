/* The limb bud process (r1-r3 of §3.4) with the morphogen step, on a fixed
 * jittered 9x9x9 lattice (no physics, no division: the cells stay where
 * they are).  The tip is the centre of the +x face.  The loop is the one the
 * run will use: morphogens sub-stepped at dt_max, rules evaluated, actions
 * applied.  After t = 60:
 *  - phi falls monotonically along the axis away from the tip;
 *  - the cells that grow are those above the threshold, a non-empty cluster
 *    near the tip (every one within 3.5 spacings), not the whole lattice;
 *  - every division request comes from a cell with radius > R, and points
 *    toward the tip (cos >= 0.5 between the direction and tip - cell; the
 *    smallest cosine is printed);
 *  - two runs give the same bytes (amounts, radii). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "morph_lattice.h"
#include "testutil.h"

static const char *model =
    "const K = 0.05\nconst Delta = 0.004\nconst R = 0.5\n"
    "morphogen phi diffusion=0.2 decay=0.05\nstate tip\n"
    "rule r1: tip == 1 -> set phi = volume\n"
    "rule r2: tip == 0 && phi > K * volume -> grow Delta\n"
    "rule r3: tip == 0 && radius > R -> divide toward grad(phi)\n";

enum { NX = 9 };

static void run(lattice *L, const sessile_sds_model *m, double *phi, double *state, sessile_sds_actions *a,
                size_t *requests) {
  int n = L->cells.ncells;
  sessile_morph_coef co = sessile_sds_model_coef(m);
  double *tmp = t_dalloc(n), dt = 0.5, dtm = sessile_morph_dt_max(&L->cells, &co);
  int sub = (int)ceil(dt / dtm);
  *requests = 0;
  for (int s = 0; s < 120; s++) {
    for (int q = 0; q < sub; q++) {
      t_must("morph step", sessile_morph_step(&L->cells, &co, phi, a->produce && a->ncells ? a->produce : NULL,
                                              dt / sub, tmp, NULL));
      memcpy(phi, tmp, sizeof(double) * n);
    }
    t_must("rules", sessile_sds_rules_eval(m, &L->cells, phi, state, s * dt, a));
    *requests += a->ndivides;
    sessile_sds_actions_apply(m, a, dt, L->radius, phi, state);
  }
  free(tmp);
}

int main(void) {
  sessile_sds_model *m = NULL;
  t_must("parse", sessile_sds_model_parse(model, "limb-loop", &m));
  double *phi[2], *rad[1];
  size_t req[2];
  sessile_sds_actions a = {0};
  lattice L;
  int tipc = (NX - 1) + NX * (NX / 2 + NX * (NX / 2)), n = NX * NX * NX;
  L = lattice_make(NX, NX, NX, 1.0, 0.1, 0.0, 4);
  for (int c = 0; c < n; c++) L.radius[c] = 0.45;
  phi[0] = t_dalloc(n);
  double *state0 = t_dalloc(n);
  state0[tipc] = 1;
  run(&L, m, phi[0], state0, &a, &req[0]);
  rad[0] = t_dalloc(n);
  memcpy(rad[0], L.radius, sizeof(double) * n);
  free(state0);
  /* the analysis on run 0 (L still holds its positions) */
  int mono = 1;
  for (int i = NX - 1; i > 0; i--) {
    int c = i + NX * (NX / 2 + NX * (NX / 2)), d = c - 1;
    mono &= phi[0][d] < phi[0][c];
  }
  t_true("phi falls monotonically along the axis away from the tip", mono);
  int grown = 0, far = 0;
  for (int c = 0; c < n; c++) {
    if (rad[0][c] > 0.45) {
      grown++;
      double d2 = 0;
      for (int k = 0; k < 3; k++) d2 += pow(L.pos[3 * c + k] - L.pos[3 * tipc + k], 2);
      far |= sqrt(d2) > 3.5;
    }
  }
  printf("grown cells: %d of %d; division requests over the run: %zu\n", grown, n, req[0]);
  t_true("a grown cluster near the tip (1 < grown < all, all within 3.5 spacings)", grown > 1 && grown < n / 4 && !far);
  double cmin = 2;
  int bad_r = 0;
  for (size_t i = 0; i < a.ndivides; i++) {
    int c = a.divides[i].cell;
    double t[3], tl = 0, cs = 0;
    for (int k = 0; k < 3; k++) t[k] = L.pos[3 * tipc + k] - L.pos[3 * c + k], tl += t[k] * t[k];
    for (int k = 0; k < 3; k++) cs += a.divides[i].dir[k] * t[k] / sqrt(tl);
    cmin = fmin(cmin, cs);
    bad_r |= !(rad[0][c] - 0.5 * 0.004 > 0.5 - 1e-12); /* radius > R when the rule fired (before this step's growth) */
  }
  printf("last step: %zu division requests, smallest cos(direction, toward tip) = %.3f\n", a.ndivides, cmin);
  t_true("division requests in the last step", a.ndivides > 0);
  t_true("every requester had radius > R", !bad_r);
  t_true("divisions point toward the tip (cos >= 0.5)", cmin >= 0.5);
  lattice_free(&L);
  /* run 1: the same bytes */
  L = lattice_make(NX, NX, NX, 1.0, 0.1, 0.0, 4);
  for (int c = 0; c < n; c++) L.radius[c] = 0.45;
  phi[1] = t_dalloc(n);
  double *state = t_dalloc(n);
  state[tipc] = 1;
  run(&L, m, phi[1], state, &a, &req[1]);
  t_true("same bytes twice (amounts, radii, requests)", !memcmp(phi[0], phi[1], sizeof(double) * n) &&
                                                            !memcmp(rad[0], L.radius, sizeof(double) * n) &&
                                                            req[0] == req[1]);
  free(state);
  lattice_free(&L);
  free(phi[0]), free(phi[1]), free(rad[0]);
  sessile_sds_actions_free(&a);
  sessile_sds_model_destroy(m);
  return t_finish(NULL);
}
