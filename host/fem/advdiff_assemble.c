/* Host assembly of the P1 + SUPG advection-diffusion system (paper §4.3,
 * eq 5 at steady state) and the symmetric Dirichlet elimination.
 *
 * Per tet (coordinates in m), with M_kl = V (1 + delta_kl) / 20 the exact
 * integrals of phi_k phi_l and u the nodal velocity:
 *   diffusion   D V grad phi_i . grad phi_j
 *   advection   sum_k M_ik (u_k . grad phi_j)                 (exact for P1 u)
 *   SUPG        tau grad phi_i^T (sum_kl M_kl u_k u_l^T) grad phi_j   (exact)
 *   source      sum_l M_il f_l + tau sum_kl M_kl (u_k . grad phi_i) f_l
 * The SUPG diffusion term tau (u . grad v)(-D lap c) vanishes for P1. */
#include <math.h>
#include <string.h>
#include "advdiff_internal.h"

double sessile_advdiff_tau(double h, double speed, double D) {
  if (!(speed > 0) || !(h > 0)) return 0.0;
  double pe = speed * h / (2.0 * D);
  /* xi(P) = coth P - 1/P; its series P/3 - P^3/45 avoids the cancellation
   * for small P, and xi -> 1 for large P (also D -> 0). */
  double xi;
  if (!(D > 0) || pe > 350) xi = 1.0 - (D > 0 ? 1.0 / pe : 0.0);
  else if (pe < 1e-3) xi = pe / 3.0 - pe * pe * pe / 45.0;
  else xi = 1.0 / tanh(pe) - 1.0 / pe;
  return h / (2.0 * speed) * xi;
}

/* Position of column j in row i (columns sorted). */
static inline uint64_t slot(const sessile_csr *a, uint32_t i, uint32_t j) {
  uint64_t lo = a->rowptr[i], hi = a->rowptr[i + 1];
  while (hi - lo > 1) {
    uint64_t mid = (lo + hi) / 2;
    if (a->col[mid] <= j) lo = mid;
    else hi = mid;
  }
  return lo;
}

/* Gradients of the 4 barycentric functions (1/m) and the volume (m^3). */
static double tet_gradients(double x[4][3], double g[4][3]) {
  double e[3][3];
  for (int r = 0; r < 3; r++)
    for (int c = 0; c < 3; c++) e[r][c] = x[r + 1][c] - x[0][c];
  /* rows of inverse(J) with J's columns e_r: grad phi_{r+1} = (e_s x e_t)/det */
  double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
               e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
               e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  for (int r = 0; r < 3; r++) {
    const double *s = e[(r + 1) % 3], *t = e[(r + 2) % 3];
    g[r + 1][0] = (s[1] * t[2] - s[2] * t[1]) / det;
    g[r + 1][1] = (s[2] * t[0] - s[0] * t[2]) / det;
    g[r + 1][2] = (s[0] * t[1] - s[1] * t[0]) / det;
  }
  for (int c = 0; c < 3; c++) g[0][c] = -(g[1][c] + g[2][c] + g[3][c]);
  return det / 6.0;
}

static inline double dot3(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

sessile_status sessile_advdiff_assemble_(sessile_advdiff *ad, const double *vel, double D,
                                         const uint8_t *mask, const double *gval) {
  const sessile_tetmesh *m = ad->mesh;
  sessile_csr *a = &ad->a;
  uint32_t n = m->nnodes;
  memset(a->val, 0, (size_t)a->nnz * sizeof *a->val);
  memset(ad->b, 0, (size_t)n * sizeof *ad->b);
  const double *f = ad->f;
  const double cm = 0.01; /* mesh cm -> m */
  for (uint32_t t = 0; t < m->ntets; t++) {
    const uint32_t *v = m->tet + 4 * (size_t)t;
    double x[4][3], g[4][3], u[4][3] = {{0}}, ue[3] = {0, 0, 0};
    for (int k = 0; k < 4; k++)
      for (int c = 0; c < 3; c++) {
        x[k][c] = cm * m->xyz[3 * (size_t)v[k] + c];
        if (vel) u[k][c] = vel[3 * (size_t)v[k] + c], ue[c] += 0.25 * u[k][c];
      }
    double vol = tet_gradients(x, g);
    double mm[4][4];
    for (int k = 0; k < 4; k++)
      for (int l = 0; l < 4; l++) mm[k][l] = vol * (k == l ? 2.0 : 1.0) / 20.0;
    double ke[4][4];
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++) ke[i][j] = D * vol * dot3(g[i], g[j]);
    double tau = 0, fe[4] = {0, 0, 0, 0};
    if (f)
      for (int i = 0; i < 4; i++)
        for (int l = 0; l < 4; l++) fe[i] += mm[i][l] * f[v[l]];
    if (vel) {
      double ug[4][4]; /* ug[k][j] = u_k . grad phi_j */
      for (int k = 0; k < 4; k++)
        for (int j = 0; j < 4; j++) ug[k][j] = dot3(u[k], g[j]);
      for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
          for (int k = 0; k < 4; k++) ke[i][j] += mm[i][k] * ug[k][j];
      double speed = sqrt(dot3(ue, ue));
      if (speed > 0 && ad->tau_scale != 0) {
        double s = 0;
        for (int i = 0; i < 4; i++) s += fabs(dot3(ue, g[i]));
        double h = 2.0 * speed / s; /* length along the flow (h_UGN) */
        tau = ad->tau_scale * sessile_advdiff_tau(h, speed, D);
      }
      if (tau != 0) {
        /* sum_kl M_kl (u_k . grad phi_i)(u_l . grad phi_j) */
        for (int i = 0; i < 4; i++)
          for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
              for (int l = 0; l < 4; l++) s += mm[k][l] * ug[k][i] * ug[l][j];
            ke[i][j] += tau * s;
          }
        if (f)
          for (int i = 0; i < 4; i++)
            for (int k = 0; k < 4; k++)
              for (int l = 0; l < 4; l++) fe[i] += tau * mm[k][l] * ug[k][i] * f[v[l]];
      }
    }
    for (int i = 0; i < 4; i++) {
      ad->b[v[i]] += fe[i];
      for (int j = 0; j < 4; j++) a->val[slot(a, v[i], v[j])] += ke[i][j];
    }
  }
  /* Symmetric elimination (graph kept, eliminated entries explicit zeros). */
  for (uint32_t i = 0; i < n; i++) {
    if (mask[i]) {
      for (uint64_t p = a->rowptr[i]; p < a->rowptr[i + 1]; p++) a->val[p] = a->col[p] == i ? 1.0 : 0.0;
      ad->b[i] = 0;
      continue;
    }
    for (uint64_t p = a->rowptr[i]; p < a->rowptr[i + 1]; p++) {
      uint32_t j = a->col[p];
      if (!mask[j]) continue;
      ad->b[i] -= a->val[p] * gval[j];
      a->val[p] = 0;
    }
    SESSILE_CHECK(a->val[slot(a, i, i)] > 0, SESSILE_ERR_NUMERIC,
                  "advection-diffusion: diagonal of free node %u is %g (not positive); check D "
                  "and the velocity for NaN",
                  i, a->val[slot(a, i, i)]);
  }
  return SESSILE_OK;
}
