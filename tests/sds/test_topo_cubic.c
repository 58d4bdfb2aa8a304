/* The inversion-time cubic: random cubics with known roots, degenerate
 * leading coefficients, tets with analytic inversion times and their case
 * (Figure 3), random motions against dense sampling. */
#include "sessile/rng.h"
#include "test_topo_fixture.h"

static double vol_at(const double *p, const double *q, double s) {
  double x[12];
  for (int i = 0; i < 12; i++) x[i] = p[i] + s * (q[i] - p[i]);
  return sessile_sds_topo_volume(x, x + 3, x + 6, x + 9);
}

int main(void) {
  uint64_t rng = sessile_rng_stream(13, 2);
  /* 1. random cubics k (s - r1)(s - r2)(s - r3), roots apart by >= 0.01 and
   * >= 1e-6 from the interval's ends: the first root in [0, 1] */
  double worst = 0;
  int n_found = 0, n_none = 0, wrong = 0;
  for (int it = 0; it < 20000; it++) {
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = sessile_rng_range(&rng, -0.5, 1.5);
    if (fabs(r[0] - r[1]) < 0.01 || fabs(r[0] - r[2]) < 0.01 || fabs(r[1] - r[2]) < 0.01) continue;
    int near_end = 0;
    for (int i = 0; i < 3; i++) near_end |= fabs(r[i]) < 1e-6 || fabs(r[i] - 1) < 1e-6;
    if (near_end) continue;
    double k = sessile_rng_range(&rng, 0.1, 10) * (sessile_rng_uniform(&rng) < 0.5 ? -1 : 1);
    double c[4] = {-k * r[0] * r[1] * r[2], k * (r[0] * r[1] + r[0] * r[2] + r[1] * r[2]), -k * (r[0] + r[1] + r[2]),
                   k};
    double want = INFINITY;
    for (int i = 0; i < 3; i++)
      if (r[i] >= 0 && r[i] <= 1) want = fmin(want, r[i]);
    double s;
    int got = sessile_sds_topo_cubic_root(c, &s);
    if (isfinite(want)) {
      n_found++;
      if (!got)
        wrong++;
      else
        worst = fmax(worst, fabs(s - want));
    } else {
      n_none++;
      wrong += got;
    }
  }
  printf("random cubics: %d with a root in [0,1], %d without\n", n_found, n_none);
  t_true("root found exactly when one lies in [0, 1]", wrong == 0);
  t_check("first root of random cubics", worst, 1e-12);
  /* 2. degenerate leading coefficients */
  double s = -1;
  double quad[4] = {0.06, -0.5, 1, 0}; /* (s - 0.2)(s - 0.3) */
  t_true("quadratic: found", sessile_sds_topo_cubic_root(quad, &s));
  t_check("quadratic: first root 0.2", fabs(s - 0.2), 1e-14);
  double lin[4] = {0.7, -1, 0, 0};
  t_true("linear: found", sessile_sds_topo_cubic_root(lin, &s));
  t_check("linear: root 0.7", fabs(s - 0.7), 1e-15);
  double tiny[4] = {0.7, -1, 0, 1e-22}; /* nearly linear */
  t_true("tiny cubic term: found", sessile_sds_topo_cubic_root(tiny, &s));
  t_check("tiny cubic term: root 0.7", fabs(s - 0.7), 1e-15);
  double cst[4] = {1, 0, 0, 0}, zero[4] = {0, 0, 0, 0};
  t_true("constant non-zero: no root", !sessile_sds_topo_cubic_root(cst, &s));
  t_true("identically zero: root at 0", sessile_sds_topo_cubic_root(zero, &s) && s == 0);
  double pos[4] = {1, -3, 3, -0.999}; /* (1-s)^3 + 0.001 s^3 > 0 on [0,1] */
  t_true("positive cubic without root in [0,1]", !sessile_sds_topo_cubic_root(pos, &s));
  double far[4] = {2e6, -3e6, 0, 0}; /* root at 2/3, large scale */
  t_true("scaled: found", sessile_sds_topo_cubic_root(far, &s));
  t_check("scaled: root 2/3", fabs(s - 2.0 / 3), 1e-15);

  /* 3. tets with analytic inversion times */
  sessile_sds_topo_inversion inv;
  {
    double p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.3, 1}, q[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.3, -2};
    t_true("vertex through face: positive at start", vol_at(p, q, 0) > 0);
    t_true("vertex through face: found", sessile_sds_topo_inversion_time(p, q, 3, 4, &inv));
    t_check("vertex through face: time 3 + 1/3", fabs(inv.u - (3 + 1.0 / 3)), 1e-12);
    t_true("vertex through face: case 1, vertex 3", inv.kind == SESSILE_SDS_TOPO_VERTEX_FACE && inv.vertex == 3);
  }
  {
    /* every vertex moving: the face (0 1 2) rises through vertex 3 at rest */
    double p[12] = {0, 0, -1, 1, 0, -1, 0, 1, -1, 0.25, 0.25, 0}, q[12];
    memcpy(q, p, sizeof q);
    for (int i = 0; i < 3; i++) q[3 * i + 2] = 3; /* z = -1 + 4 s: zero at s = 1/4 */
    t_true("face through vertex: found", sessile_sds_topo_inversion_time(p, q, 0, 2, &inv));
    t_check("face through vertex: time 2/4", fabs(inv.u - 0.5), 1e-12);
    t_true("face through vertex: case 1, vertex 3", inv.kind == SESSILE_SDS_TOPO_VERTEX_FACE && inv.vertex == 3);
  }
  {
    /* edge (0 1) on the x axis, edge (2 3) parallel to y at height h = 1 - 2 s */
    double p[12] = {0, 0, 0, 1, 0, 0, 0.5, -0.5, 1, 0.5, 0.5, 1},
           q[12] = {0, 0, 0, 1, 0, 0, 0.5, -0.5, -1, 0.5, 0.5, -1};
    if (vol_at(p, q, 0) < 0) { /* orient positively */
      for (int k = 0; k < 3; k++) {
        double t = p[6 + k];
        p[6 + k] = p[9 + k];
        p[9 + k] = t;
        t = q[6 + k];
        q[6 + k] = q[9 + k];
        q[9 + k] = t;
      }
    }
    t_true("edge through edge: found", sessile_sds_topo_inversion_time(p, q, 1, 2, &inv));
    t_check("edge through edge: time 1.5", fabs(inv.u - 1.5), 1e-12);
    int pair = (inv.edge[0][0] == 0 && inv.edge[0][1] == 1) || (inv.edge[1][0] == 0 && inv.edge[1][1] == 1);
    t_true("edge through edge: case 2, edges (0 1) and (2 3)", inv.kind == SESSILE_SDS_TOPO_EDGE_EDGE && pair);
  }
  /* 4. random tets, random linear motions: the time against dense sampling
   * of the volume (no sign change before it, one just after it) */
  int bad = 0, hits = 0;
  for (int it = 0; it < 3000; it++) {
    double p[12], q[12];
    for (int i = 0; i < 12; i++) p[i] = sessile_rng_normal(&rng), q[i] = p[i] + 1.5 * sessile_rng_normal(&rng);
    if (vol_at(p, q, 0) <= 0) {
      for (int k = 0; k < 3; k++) {
        double t = p[3 + k];
        p[3 + k] = p[6 + k];
        p[6 + k] = t;
        t = q[3 + k];
        q[3 + k] = q[6 + k];
        q[6 + k] = t;
      }
    }
    int found = sessile_sds_topo_inversion_time(p, q, 0, 1, &inv);
    /* sampled first sign change */
    double first = INFINITY;
    for (int k = 1; k <= 4000 && !isfinite(first); k++)
      if (vol_at(p, q, k / 4000.0) <= 0) first = k / 4000.0;
    if (isfinite(first) != found) {
      /* a touch between samples is possible only near a double root */
      bad += !found || fabs(vol_at(p, q, inv.s)) > 1e-9;
      continue;
    }
    if (!found) continue;
    hits++;
    bad += inv.s > first || inv.s < first - 1.0 / 4000 - 1e-12 || fabs(vol_at(p, q, inv.s)) > 1e-12;
  }
  printf("random motions: %d inversions\n", hits);
  t_true("random motions: inversion time = the sampled first sign change", bad == 0);
  return t_finish(NULL);
}
