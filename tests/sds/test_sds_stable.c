/* The stable-step bound against the scheme's real stability limit (host;
 * docs/sds.md, "Integrator").  sessile_sds_critical_dt finds the critical
 * step of semi-implicit Euler by power iteration; checked (1) on one edge,
 * where it is analytic (2 / sqrt(4 k / R')) and Gershgorin is exact, and (2)
 * on an imported sphere, by running the scheme itself: a small perturbation
 * stays bounded at 0.9 x the critical step and grows without bound at 1.1 x.
 * Then the bound sessile_sds_stable_dt must lie below that critical step,
 * at rest and on deformed bodies: stable_safety is a fraction of a step that
 * is stable by this test, not by trust in the bound. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "sessile/rng.h"
#include "sessile/sds/sds.h"
#include "testutil.h"
#include "one_edge.h"

/* The undamped physics of the springs alone: no gravity, walls or contacts. */
static sessile_sds_params springs_only(void) {
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.gravity = 0, p.damp_visc = 0, p.damp_vol = 0, p.self_collide = 0;
  p.dt_max = 1e6; /* the bound itself, not the step control's ceiling */
  return p;
}

static void edge_analytic(void) {
  sessile_sds o = {0};
  one_edge(&o, 2.0);
  sessile_sds_params p = springs_only();
  double res = 0, crit = sessile_sds_critical_dt(&o, &p, 50, &res), bound = sessile_sds_stable_dt(&o, &p);
  /* the relative coordinate: omega^2 = K_e (1/m_a + 1/m_b), K_e = k (m_a + m_b) / R' = 2 k m / R' */
  double exact = 2 / sqrt(4 * p.k_edge / 2.0);
  printf("one edge: critical step %.15g (power iteration, residual %.2g), bound %.15g, analytic %.15g\n", crit, res,
         bound, exact);
  t_check("one edge: the power iteration's critical step = 2/sqrt(4k/R') (rel)", fabs(crit - exact) / exact, 1e-6);
  t_check("one edge: Gershgorin is exact for one spring (rel)", fabs(bound - exact) / exact, 1e-12);
  /* uniform stiffness: s_k = k itself, K_e = k / R'^2; with k = R' (m_a + m_b)
   * (the prototype's scale of this edge) the same spring as above */
  p.uniform_stiffness = 1, p.k_edge = 2.0 * 2 * o.m[0];
  double ures = 0, ucrit = sessile_sds_critical_dt(&o, &p, 50, &ures), ubound = sessile_sds_stable_dt(&o, &p);
  printf("one edge, uniform stiffness k = R'(m_a + m_b): critical step %.15g, bound %.15g\n", ucrit, ubound);
  t_check("uniform stiffness, one edge: the critical step the prototype's (rel)", fabs(ucrit - exact) / exact, 1e-6);
  t_check("uniform stiffness, one edge: the bound the prototype's (rel)", fabs(ubound - exact) / exact, 1e-12);
  p.k_edge = 1;
  double ubound1 = sessile_sds_stable_dt(&o, &p), exact1 = 2 / sqrt(p.k_edge / 4.0 * 2 / o.m[0]);
  t_check("uniform stiffness k = 1: 2/sqrt((k/R'^2) (1/m_a + 1/m_b)) (rel)", fabs(ubound1 - exact1) / exact1, 1e-12);
  sessile_sds_free(&o);
}

/* Energy after `steps` of the host scheme at dt, over its start. */
static double growth(const sessile_sds *start, const sessile_sds_params *p, double dt, int steps) {
  sessile_sds o = {0};
  t_must("copy", sessile_sds_copy(start, &o));
  sessile_sds_energy e;
  sessile_sds_energy_of(&o, p, &e);
  double E0 = sessile_sds_energy_total(&e), worst = 1;
  for (int k = 0; k < steps; k++) {
    sessile_sds_step_ref(&o, p, dt);
    sessile_sds_energy_of(&o, p, &e);
    double r = sessile_sds_energy_total(&e) / E0;
    if (!(r <= worst)) worst = r; /* NaN too */
    if (!(worst < 1e12)) break;
  }
  sessile_sds_free(&o);
  return worst;
}

static void sphere_critical(void) {
  const double ctr[3] = {0, 0, 0};
  sessile_sds o = {0};
  t_must("icosphere level 2", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 0, 0, 1.0, &o));
  sessile_sds_params p = springs_only();
  /* a small perturbation: the linear regime, where the critical step is sharp */
  uint64_t rng = sessile_rng_stream(11, 2);
  for (size_t k = 0; k < 3 * (size_t)o.ncells; k++) o.x[k] += 1e-5 * o.r[k / 3] * sessile_rng_normal(&rng);
  double res = 0, crit = sessile_sds_critical_dt(&o, &p, 400, &res), bound = sessile_sds_stable_dt(&o, &p);
  double below = growth(&o, &p, 0.9 * crit, 600), above = growth(&o, &p, 1.1 * crit, 600);
  printf("sphere (%u cells), at rest: critical step %.6g (residual %.2g), bound %.6g (%.3f of it); "
         "energy grows by at most %.3g at 0.9x, %.3g at 1.1x in 600 steps\n",
         o.ncells, crit, res, bound, bound / crit, below, above);
  t_check("the power iteration settled (relative residual)", res, 1e-3);
  t_true("the scheme is stable at 0.9 x the critical step (energy below 20x its start)", below < 20);
  t_true("and unstable at 1.1 x (energy above 1e6x its start)", above > 1e6);
  t_true("the bound lies below the critical step, at rest", bound < crit);
  sessile_sds_free(&o);
}

/* Deformed bodies (cells moved by 5 and 15 % of their radii) and a divided
 * complex's stiff mix of small and large cells are where the bound could
 * fail: it takes Gershgorin's sum at rest, without the stress terms. */
static void deformed(void) {
  const double ctr[3] = {0, 0, 0};
  const double amp[] = {0.05, 0.15};
  for (int level = 2; level <= 3; level++)
    for (int a = 0; a < 2; a++) {
      sessile_sds o = {0};
      t_must("icosphere", sessile_sds_from_icosphere(level, 1.0, ctr, 0, 0, 0, 1.0, &o));
      sessile_sds_params p = springs_only();
      p.self_collide = 1; /* the bound's contact term is then part of it, and of the forces */
      uint64_t rng = sessile_rng_stream(5 + (uint64_t)a, 2);
      for (size_t k = 0; k < 3 * (size_t)o.ncells; k++) o.x[k] += amp[a] * o.r[k / 3] * sessile_rng_normal(&rng);
      double res = 0, crit = sessile_sds_critical_dt(&o, &p, 400, &res), bound = sessile_sds_stable_dt(&o, &p);
      printf("level %d sphere moved by %.0f %% of the radii: critical %.6g (residual %.2g), bound %.6g (%.3f of it)\n",
             level, 100 * amp[a], crit, res, bound, bound / crit);
      t_check("the power iteration settled (relative residual)", res, 1e-2);
      t_true("the bound lies below the critical step of a deformed body", bound < crit);
      sessile_sds_free(&o);
    }
}

int main(void) {
  edge_analytic();
  sphere_critical();
  deformed();
  return t_finish(NULL);
}
