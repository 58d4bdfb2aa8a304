/* The axial stiffness and the oriented growth (host/sds/sds_axial.c;
 * docs/sds.md, "Axial stiffness", "Oriented growth"): a spring's stiffness
 * multiplier 1 + (q - 1) cos^2 of its angle to the axis, against hand
 * values; on an icosphere with the linear field phi = 2 x + 0.5 (whose
 * least-squares gradient is exactly (2, 0, 0) at every cell), the springs
 * marked born (edge_k 0) take 1 + (q - 1) d_x^2 / |d|^2, those born before
 * keep theirs, and a flat field leaves them isotropic (1); a division's
 * rebuild leaves the new springs 0 with edge_k_defer and 1 without, the
 * old ones their values.  The oriented growth: with the cells' radii grown
 * by dr, each edge's rest length s_m (r_a + r_b) grows by
 * (1 + A (3 cos^2 - 1)) s_m (dr_a + dr_b); A = 0, a flat field or cells
 * that did not grow leave s_m as it was, to the bit.  Convergent extension:
 * each edge between two cells whose state is set takes 1 + C dt (3 cos^2 - 1)
 * into its s_m, the others and a flat field leave it to the bit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "sds/sds_internal.h"
#include "sds/sds_sim.h"
#include "testutil.h"

int main(void) {
  const double x[3] = {1, 0, 0}, y[3] = {0, 3, 0}, xy[3] = {1, 1, 0}, zero[3] = {0, 0, 0};
  t_check("along the axis: q", fabs(sds_axial_k(0.25, x, x) - 0.25), 1e-15);
  t_check("along, the axis reversed: q", fabs(sds_axial_k(0.25, x, (double[3]){-2, 0, 0}) - 0.25), 1e-15);
  t_check("across the axis: 1", fabs(sds_axial_k(0.25, y, x) - 1), 0);
  t_check("at 45 degrees: (1 + q) / 2", fabs(sds_axial_k(0.25, xy, x) - 0.625), 1e-15);
  t_check("no axis (a flat field): 1", fabs(sds_axial_k(0.25, xy, zero) - 1), 0);

  const double ctr[3] = {0, 0, 0};
  sessile_sds o = {0};
  t_must("icosphere level 2 through TetGen", sessile_sds_from_icosphere(2, 1.0, ctr, 0, 1, 0, 1.0, &o));
  uint32_t *nbr = malloc(2 * (size_t)o.nedges * sizeof *nbr);
  for (uint32_t c = 0; c < o.ncells; c++)
    for (uint32_t k = o.cell_edge_off[c]; k < o.cell_edge_off[c + 1]; k++) {
      uint32_t e = o.cell_edge[k];
      nbr[k] = o.edge[2 * e] == c ? o.edge[2 * e + 1] : o.edge[2 * e];
    }
  sessile_morph_cells cells = {(int)o.ncells, o.x, o.r, o.cell_edge_off, nbr, o.surface};
  for (uint32_t c = 0; c < o.ncells; c++) o.phi[c] = 2 * o.x[3 * c] + 0.5;
  const double q = 0.3;
  for (uint32_t e = 0; e < o.nedges; e++) o.edge_k[e] = e % 7 == 3 ? 1.75 : 0; /* every 7th born before */
  sds_axial_springs(&o, &cells, 0, q);
  double worst = 0;
  int kept = 1, spread = 0;
  for (uint32_t e = 0; e < o.nedges; e++) {
    if (e % 7 == 3) {
      kept = kept && o.edge_k[e] == 1.75;
      continue;
    }
    double d[3];
    sds_sub(o.x + 3 * (size_t)o.edge[2 * e], o.x + 3 * (size_t)o.edge[2 * e + 1], d);
    double want = 1 + (q - 1) * d[0] * d[0] / sds_dot(d, d);
    worst = fmax(worst, fabs(o.edge_k[e] - want));
    spread += o.edge_k[e] < 0.5 || o.edge_k[e] > 0.9;
  }
  printf("%u springs, largest error %.3g, %d of them below 0.5 or above 0.9\n", o.nedges, worst, spread);
  t_check("a linear field: each born spring 1 + (q - 1) cos^2 to x (abs)", worst, 1e-12);
  t_true("the springs born before keep their stiffness", kept);
  t_true("and the field sets a range of them (not one value)", spread > (int)o.nedges / 4);
  for (uint32_t c = 0; c < o.ncells; c++) o.phi[c] = 0.5;
  for (uint32_t e = 0; e < o.nedges; e++) o.edge_k[e] = 0;
  sds_axial_springs(&o, &cells, 0, q);
  int ones = 1;
  for (uint32_t e = 0; e < o.nedges; e++) ones = ones && o.edge_k[e] == 1;
  t_true("a flat field: every spring isotropic (1)", ones);

  /* the oriented growth: cells grown by 0-0.005, every third not at all */
  for (uint32_t c = 0; c < o.ncells; c++) o.phi[c] = 2 * o.x[3 * c] + 0.5;
  double *r0 = malloc(o.ncells * sizeof *r0), *smg = malloc(o.nedges * sizeof *smg);
  for (uint32_t e = 0; e < o.nedges; e++) o.edge_sm[e] = smg[e] = 0.9 + 0.01 * (e % 13);
  for (uint32_t c = 0; c < o.ncells; c++) r0[c] = o.r[c], o.r[c] += c % 3 == 0 ? 0 : 0.001 * (1 + c % 5);
  const double A = 0.7;
  int changed = 0;
  t_must("oriented growth", sds_axial_grow_edges(&o, &cells, 0, A, r0, &changed));
  double wg = 0;
  int still = 1, ngrew = 0;
  for (uint32_t e = 0; e < o.nedges; e++) {
    uint32_t a = o.edge[2 * e], b = o.edge[2 * e + 1];
    double dr = (o.r[a] - r0[a]) + (o.r[b] - r0[b]);
    if (dr == 0) {
      still = still && o.edge_sm[e] == smg[e];
      continue;
    }
    double d[3];
    sds_sub(o.x + 3 * (size_t)a, o.x + 3 * (size_t)b, d);
    double c2 = d[0] * d[0] / sds_dot(d, d);
    double want = smg[e] * (r0[a] + r0[b]) + (1 + A * (3 * c2 - 1)) * smg[e] * dr; /* the rest length now */
    wg = fmax(wg, fabs(o.edge_sm[e] * (o.r[a] + o.r[b]) / want - 1));
    ngrew++;
  }
  printf("oriented growth A = %g: %d edges grew, largest relative error %.3g\n", A, ngrew, wg);
  t_check("oriented growth: each rest length R0 + (1 + A (3 cos^2 - 1)) s_m dr (rel)", wg, 1e-13);
  t_true("oriented growth: edges whose cells did not grow keep s_m to the bit", still && ngrew > 0 && changed);
  for (uint32_t e = 0; e < o.nedges; e++) o.edge_sm[e] = smg[e];
  changed = 0;
  t_must("oriented growth A = 0", sds_axial_grow_edges(&o, &cells, 0, 0.0, r0, &changed));
  int same = 1;
  for (uint32_t e = 0; e < o.nedges; e++) same = same && o.edge_sm[e] == smg[e];
  t_true("A = 0: every s_m as it was, to the bit (the growth isotropic)", same);
  for (uint32_t c = 0; c < o.ncells; c++) o.phi[c] = 0.5;
  changed = 0;
  t_must("oriented growth, a flat field", sds_axial_grow_edges(&o, &cells, 0, A, r0, &changed));
  for (uint32_t e = 0; e < o.nedges; e++) same = same && o.edge_sm[e] == smg[e];
  t_true("a flat field: every s_m as it was (no axis), nothing marked changed", same && !changed);
  for (uint32_t c = 0; c < o.ncells; c++) o.r[c] = r0[c];

  /* convergent extension: state 0 of two (the other a decoy of 1s) set in
   * the cells with x > -0.3; each edge between two such cells takes
   * 1 + C dt (3 cos^2 - 1) into its s_m, every other edge keeps it */
  for (uint32_t c = 0; c < o.ncells; c++) o.phi[c] = 2 * o.x[3 * c] + 0.5;
  double *state = malloc(2 * (size_t)o.ncells * sizeof *state), *state0 = o.state;
  uint32_t nstate0 = o.nstate;
  for (uint32_t c = 0; c < o.ncells; c++) state[2 * c] = o.x[3 * c] > -0.3 ? 1 : 0, state[2 * c + 1] = 1;
  o.state = state, o.nstate = 2;
  for (uint32_t e = 0; e < o.nedges; e++) o.edge_sm[e] = smg[e];
  const double C = 0.02, dte = 0.7; /* C dt 0.014: a visible step */
  changed = 0;
  t_must("convergent extension", sds_axial_extend_edges(&o, &cells, 0, C, dte, 0, &changed));
  double we = 0, lo = 2, hi = 0;
  int kept_out = 1, nin = 0, nout = 0;
  for (uint32_t e = 0; e < o.nedges; e++) {
    uint32_t a = o.edge[2 * e], b = o.edge[2 * e + 1];
    if (state[2 * a] == 0 || state[2 * b] == 0) {
      kept_out = kept_out && o.edge_sm[e] == smg[e], nout++;
      continue;
    }
    double d[3];
    sds_sub(o.x + 3 * (size_t)a, o.x + 3 * (size_t)b, d);
    double f = 1 + C * dte * (3 * d[0] * d[0] / sds_dot(d, d) - 1);
    we = fmax(we, fabs(o.edge_sm[e] / (smg[e] * f) - 1));
    lo = fmin(lo, o.edge_sm[e] / smg[e]), hi = fmax(hi, o.edge_sm[e] / smg[e]);
    nin++;
  }
  printf("convergent extension C dt = %g: %d edges between extending cells (factors %.5f-%.5f), %d others, "
         "largest relative error %.3g\n", C * dte, nin, lo, hi, nout, we);
  t_check("convergent extension: each s_m x (1 + C dt (3 cos^2 - 1)) (rel)", we, 1e-15);
  t_true("... edges with a cell not extending keep s_m to the bit", kept_out && nin > 0 && nout > 0 && changed);
  t_true("... those along the axis lengthen, those across shorten (factors both sides of 1)",
         lo < 1 - 0.5 * C * dte && hi > 1 + 1.5 * C * dte);
  for (uint32_t e = 0; e < o.nedges; e++) o.edge_sm[e] = smg[e];
  for (uint32_t c = 0; c < o.ncells; c++) o.phi[c] = 0.5;
  changed = 0;
  t_must("convergent extension, a flat field", sds_axial_extend_edges(&o, &cells, 0, C, dte, 0, &changed));
  same = 1;
  for (uint32_t e = 0; e < o.nedges; e++) same = same && o.edge_sm[e] == smg[e];
  t_true("a flat field: every s_m as it was (no axis), nothing marked changed", same && !changed);
  o.state = state0, o.nstate = nstate0;
  free(state);
  free(r0), free(smg);
  free(nbr);

  /* the rebuild after a change of topology: split tet 0 at its centroid */
  for (uint32_t e = 0; e < o.nedges; e++) o.edge_k[e] = 1 + 0.001 * e;
  for (int defer = 1; defer >= 0; defer--) {
    sessile_sds w = {0};
    t_must("copy", sessile_sds_copy(&o, &w));
    w.edge_k_defer = defer;
    uint32_t n = w.ncells, T = w.ntets, q4[4];
    t_must("reserve", sessile_sds_reserve(&w, n + 1, T + 3));
    for (int i = 0; i < 4; i++) q4[i] = w.tet[i];
    for (int i = 0; i < 3; i++) {
      double s = 0;
      for (int j = 0; j < 4; j++) s += w.x[3 * (size_t)q4[j] + i];
      w.x[3 * (size_t)n + i] = s / 4;
    }
    w.r[n] = w.r[q4[0]], w.m[n] = w.m[q4[0]], w.ncells = n + 1;
    /* (a b c d) -> (n b c d) (a n c d) (a b n d) (a b c n): each keeps the sign */
    for (int j = 0; j < 4; j++) {
      uint32_t *t = w.tet + 4 * (size_t)(j == 0 ? 0 : T + j - 1);
      for (int i = 0; i < 4; i++) t[i] = i == j ? n : q4[i];
      w.tet_sm[j == 0 ? 0 : T + j - 1] = 0;
    }
    w.ntets = T + 3;
    t_must("rebuild", sessile_sds_rebuild(&w, SESSILE_SDS_NEW_UNIT));
    int newk = 1, oldk = 1, nnew = 0;
    for (uint32_t e = 0; e < w.nedges; e++) {
      uint32_t a = w.edge[2 * e], b = w.edge[2 * e + 1];
      if (b == n) {
        nnew++, newk = newk && w.edge_k[e] == (defer ? 0.0 : 1.0);
        continue;
      }
      /* an old edge: the same pair in o */
      for (uint32_t f = 0; f < o.nedges; f++)
        if (o.edge[2 * f] == a && o.edge[2 * f + 1] == b) oldk = oldk && w.edge_k[e] == o.edge_k[f];
    }
    printf("edge_k_defer %d: %u edges, %d new\n", defer, w.nedges, nnew);
    t_true(defer ? "rebuild with edge_k_defer: the 4 new springs 0, for the caller"
                 : "rebuild without: the 4 new springs 1",
           nnew == 4 && newk);
    t_true("rebuild: the old springs keep their edge_k", oldk);
    sessile_sds_free(&w);
  }
  sessile_sds_free(&o);
  return t_finish(NULL);
}
