/* The morphogen reference (host/sds/morph.c) against invariants and closed
 * forms:
 *  - conservation without decay and sources, uncapped regime (amounts well
 *    below every volume) and capped regime (a corner of full cells, so the
 *    min(., vol) caps bind in the fluxes): the pair flux is antisymmetric
 *    whether or not a cap binds, and under dt <= dt_max the update is
 *    monotone so amounts stay in [0, vol] and the clamp never acts: 1e-13
 *    relative after 200 steps, and 0 clamped values;
 *  - amounts above the cell volume (which only a source or a shrinking cell
 *    can produce) are clamped: the total falls, by the excess (1e-12);
 *  - decay only (D = 0): total = (1 - C dt)^n total0 (1e-13 relative), and
 *    |total/total0 - exp(-C t)| is O(dt): the error at dt/2 is half the error
 *    at dt (ratio in [1.9, 2.1]) and below 1.05 C^2 t dt exp(-Ct) / 2 (first order term; the
 *    higher ones add about 1%);
 *  - diffusion on a chain of 20 cells from one full end cell approaches
 *    uniform amounts: max |phi - mean| / mean < 1e-6 after t = 3000;
 *  - dt above dt_max (and dt <= 0) is refused with SESSILE_ERR_USAGE;
 *  - the Laplacian of a uniform field is 0 (no cap binding). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "morph_lattice.h"
#include "testutil.h"

static double run(const sessile_morph_cells *cl, const sessile_morph_coef *co, double *phi, double dt, int steps,
                  size_t *clamped) {
  size_t n = (size_t)cl->ncells * co->nmorph, cs = 0, c1;
  double *tmp = t_dalloc(n);
  for (int i = 0; i < steps; i++) {
    t_must("step", sessile_morph_step(cl, co, phi, NULL, dt, tmp, &c1));
    cs += c1;
    memcpy(phi, tmp, n * sizeof *phi);
  }
  free(tmp);
  if (clamped) *clamped = cs;
  return 0;
}

int main(void) {
  lattice L = lattice_make(8, 7, 6, 1.0, 0.2, 0.1, 3);
  int n = L.cells.ncells;
  double D = 0.2, C = 0.0;
  sessile_morph_coef co = {1, &D, &C, NULL};
  double *phi = t_dalloc(n);
  uint64_t s = sessile_rng_stream(5, 1);
  double dtm = sessile_morph_dt_max(&L.cells, &co);
  printf("lattice %d cells, dt_max = %.6g\n", n, dtm);

  /* uncapped: amounts <= 0.1 vol */
  for (int c = 0; c < n; c++) phi[c] = sessile_rng_range(&s, 0, 0.1) * sessile_morph_vol(L.radius[c]);
  double t0 = sessile_morph_total(n, 1, phi, 0);
  size_t cl = 0;
  run(&L.cells, &co, phi, dtm, 200, &cl);
  t_check("conserved, uncapped regime, 200 steps at dt_max (relative)",
          fabs(sessile_morph_total(n, 1, phi, 0) - t0) / t0, 1e-13);
  t_true("uncapped regime: no value clamped", cl == 0);

  /* capped: a corner of full cells, caps bind in the fluxes */
  int binding = 0;
  for (int c = 0; c < n; c++) {
    double v = sessile_morph_vol(L.radius[c]);
    phi[c] = L.pos[3 * c] < 2.5 && L.pos[3 * c + 1] < 2.5 ? v : 0.2 * v;
  }
  for (int c = 0; c < n; c++)
    for (uint32_t q = L.off[c]; q < L.off[c + 1]; q++)
      if (phi[c] > sessile_morph_vol(L.radius[L.nbr[q]]) || phi[L.nbr[q]] > sessile_morph_vol(L.radius[c]))
        binding++;
  printf("capped regime: %d (cell, neighbour) pairs where a cap binds at the start\n", binding);
  t_true("capped regime: some caps bind", binding > 0);
  t0 = sessile_morph_total(n, 1, phi, 0);
  run(&L.cells, &co, phi, dtm, 200, &cl);
  t_check("conserved, capped regime, 200 steps (relative)", fabs(sessile_morph_total(n, 1, phi, 0) - t0) / t0,
          1e-13);
  t_true("capped regime: no value clamped (monotone update keeps [0, vol])", cl == 0);
  int inside = 1;
  for (int c = 0; c < n; c++) inside &= phi[c] >= 0 && phi[c] <= sessile_morph_vol(L.radius[c]);
  t_true("capped regime: every amount in [0, vol(c)]", inside);

  /* over-full cells are clamped to their volume: the excess is lost */
  double excess = 0;
  for (int c = 0; c < n; c++) {
    double v = sessile_morph_vol(L.radius[c]);
    phi[c] = c % 5 == 0 ? 1.5 * v : 0.5 * v;
  }
  double *out = t_dalloc(n);
  double Dz = 0;
  sessile_morph_coef still = {1, &Dz, &C, NULL};
  t_must("over-full step", sessile_morph_step(&L.cells, &still, phi, NULL, 1.0, out, &cl));
  for (int c = 0; c < n; c += 5) excess += 0.5 * sessile_morph_vol(L.radius[c]);
  t_check("clamp removes exactly the excess over vol (relative)",
          fabs(sessile_morph_total(n, 1, phi, 0) - sessile_morph_total(n, 1, out, 0) - excess) / excess, 1e-12);
  t_true("clamp count = over-full cells", cl == (size_t)((n + 4) / 5));

  /* decay only */
  double Cd = 0.3, T = 4.0, err[2];
  sessile_morph_coef dec = {1, &Dz, &Cd, NULL};
  for (int h = 0; h < 2; h++) {
    int steps = 40 << h;
    double dt = T / steps;
    for (int c = 0; c < n; c++) phi[c] = 0.5 * sessile_morph_vol(L.radius[c]);
    t0 = sessile_morph_total(n, 1, phi, 0);
    run(&L.cells, &dec, phi, dt, steps, NULL);
    double r = sessile_morph_total(n, 1, phi, 0) / t0;
    t_check(h ? "decay: total = (1 - C dt)^n, dt = T/80" : "decay: total = (1 - C dt)^n, dt = T/40",
            fabs(r - pow(1 - Cd * dt, steps)) / r, 1e-13);
    err[h] = fabs(r - exp(-Cd * T));
    printf("decay: dt = %g, |total/total0 - exp(-C t)| = %.6g\n", dt, err[h]);
    t_true("decay: error vs exp(-Ct) <= 1.05 C^2 T dt exp(-CT) / 2",
           err[h] <= 1.05 * Cd * Cd * T * dt * exp(-Cd * T) / 2);
  }
  double ratio = err[0] / err[1];
  printf("decay: error ratio dt / (dt/2) = %.4f\n", ratio);
  t_true("decay: O(dt), error halves when dt halves (ratio in [1.9, 2.1])", ratio > 1.9 && ratio < 2.1);

  /* chain: one full end cell, D = 0.5 */
  enum { NC = 20 };
  double cp[3 * NC], cr[NC], ch[NC];
  uint32_t coff[NC + 1], cn[2 * NC];
  uint32_t e = 0;
  for (int c = 0; c < NC; c++) {
    cp[3 * c] = 0.9 * c, cp[3 * c + 1] = 0.05 * (c % 2), cp[3 * c + 2] = 0;
    cr[c] = 0.45;
    coff[c] = e;
    if (c > 0) cn[e++] = (uint32_t)(c - 1);
    if (c < NC - 1) cn[e++] = (uint32_t)(c + 1);
    ch[c] = 0;
  }
  coff[NC] = e;
  ch[0] = sessile_morph_vol(0.45);
  sessile_morph_cells chain = {NC, cp, cr, coff, cn, NULL};
  double Dc = 0.5, Cc = 0;
  sessile_morph_coef cco = {1, &Dc, &Cc, NULL};
  double dtc = sessile_morph_dt_max(&chain, &cco);
  double ctot = ch[0];
  run(&chain, &cco, ch, dtc, (int)ceil(3000 / dtc), NULL);
  double mean = ctot / NC, dev = 0;
  for (int c = 0; c < NC; c++) dev = fmax(dev, fabs(ch[c] - mean));
  printf("chain: dt = %g, max |phi - mean| / mean = %.3g\n", dtc, dev / mean);
  t_check("chain approaches uniform (max |phi - mean| / mean)", dev / mean, 1e-6);
  t_check("chain: total conserved (relative)", fabs(sessile_morph_total(NC, 1, ch, 0) - ctot) / ctot, 1e-13);

  /* refusals */
  t_true("refuses dt = 1.001 dt_max",
         sessile_morph_step(&chain, &cco, ch, NULL, 1.001 * dtc, out, NULL) == SESSILE_ERR_USAGE);
  printf("  message: %s\n", sessile_error_message());
  t_true("refuses dt = 0", sessile_morph_step(&chain, &cco, ch, NULL, 0, out, NULL) == SESSILE_ERR_USAGE);
  t_true("accepts dt = dt_max", sessile_morph_step(&chain, &cco, ch, NULL, dtc, out, NULL) == SESSILE_OK);

  /* uniform field: zero Laplacian */
  for (int c = 0; c < n; c++) phi[c] = 1e-3;
  double lmax = 0;
  for (int c = 0; c < n; c++) lmax = fmax(lmax, fabs(sessile_morph_laplacian(&L.cells, 1, phi, c, 0)));
  t_check("Laplacian of a uniform field", lmax, 0);

  free(phi), free(out);
  lattice_free(&L);
  return t_finish(NULL);
}
