/* The P1-P1 stabilised Navier-Stokes element (O'Hagan et al. §4.2, eqs 3-4,
 * stationary): residual and exact Newton Jacobian of one tetrahedron.
 *
 * Weak form, per element, test functions (v, q), unknowns (u, p):
 *   Galerkin   rho (u.grad u, v) + eta (grad u, grad v) - (p, div v) + (q, div u) - (f, v)
 *   SUPG       rho tp (u.grad v, r)            r = rho u.grad u + grad p - f
 *              (= tau_t (u.grad v, r) with tau_t = rho tp in seconds: the
 *              same units as the Galerkin term)
 *   PSPG       tp (grad q, r)                  (eta Lap u = 0 for P1)
 *   LSIC       tc (div u, div v)
 * with tp = tau/rho = [ (2 rho |u_c| / h)^2 + 9 (4 eta / h^2)^2 ]^(-1/2)
 * (Tezduyar / Shakib's stationary tau, divided by rho so rho = 0 gives Stokes
 * with PSPG tau h^2/(12 eta)), tc = h^2 / (12 tp) (the trace of the metric
 * tensor form, Whiting & Jansen), u_c the centroid velocity and
 * h = the diameter of the sphere of the tet's volume.  The derivatives of tp
 * and tc with respect to u_c are in the Jacobian, so Newton is exact
 * (quadratic).  All products are of degree <= 2 and are integrated exactly
 * by the 4-point rule; the momentum test sums per quadrature point are
 * reduced to a few element moments first (docs/fluid.md). */
#include <math.h>
#include <string.h>

#include "fem/ns_internal.h"

static inline double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void ns_element(const double X[4][3], const double U[16], const double F[4][3], const ns_coef *c,
                double Re[16], double *Ke) {
  double d[3][3], G[4][3];
  for (int r = 0; r < 3; r++)
    for (int k = 0; k < 3; k++) d[r][k] = X[r + 1][k] - X[0][k];
  double c12[3] = {d[1][1] * d[2][2] - d[1][2] * d[2][1], d[1][2] * d[2][0] - d[1][0] * d[2][2],
                   d[1][0] * d[2][1] - d[1][1] * d[2][0]};
  double c20[3] = {d[2][1] * d[0][2] - d[2][2] * d[0][1], d[2][2] * d[0][0] - d[2][0] * d[0][2],
                   d[2][0] * d[0][1] - d[2][1] * d[0][0]};
  double c01[3] = {d[0][1] * d[1][2] - d[0][2] * d[1][1], d[0][2] * d[1][0] - d[0][0] * d[1][2],
                   d[0][0] * d[1][1] - d[0][1] * d[1][0]};
  double det = dot3(d[0], c12);
  for (int k = 0; k < 3; k++) {
    G[1][k] = c12[k] / det;
    G[2][k] = c20[k] / det;
    G[3][k] = c01[k] / det;
    G[0][k] = -(G[1][k] + G[2][k] + G[3][k]);
  }
  const double V = fabs(det) / 6.0, w = V / 4.0;
  const double rho = c->rho, eta = c->eta, nw = c->newton;
  const double h = 2.0 * cbrt(0.238732414637843 * V) /* 3/(4 pi) */;

  double L[3][3] = {{0}}, gp[3] = {0}, uc[3] = {0}, pbar = 0;
  for (int a = 0; a < 4; a++) {
    for (int i = 0; i < 3; i++) {
      for (int j = 0; j < 3; j++) L[i][j] += U[4 * a + i] * G[a][j];
      gp[i] += U[4 * a + 3] * G[a][i];
      uc[i] += 0.25 * U[4 * a + i];
    }
    pbar += 0.25 * U[4 * a + 3];
  }
  const double div = L[0][0] + L[1][1] + L[2][2];
  const double s1 = 2.0 * rho / h, s2 = 12.0 * eta / (h * h); /* 3 * 4 eta / h^2 */
  const double tp = 1.0 / sqrt(s1 * s1 * dot3(uc, uc) + s2 * s2);
  double dtp[3], dtc[3];
  const double tc = c->lsic ? h * h / (12.0 * tp) : 0.0;
  for (int j = 0; j < 3; j++) {
    dtp[j] = -nw * tp * tp * tp * s1 * s1 * uc[j];
    dtc[j] = c->lsic ? -h * h / (12.0 * tp * tp) * dtp[j] : 0.0;
  }

  /* quadrature-point fields and element moments */
  double Mv[4][3] = {{0}}, Sv[4][3] = {{0}}, Tv[4][3] = {{0}}, Fp[4][3] = {{0}}, UU[3][3] = {{0}},
         Rb[3] = {0};
  for (int q = 0; q < 4; q++) {
    double uq[3], r[3], ug[4];
    for (int i = 0; i < 3; i++) {
      uq[i] = NS_QB * (U[0 + i] + U[4 + i] + U[8 + i] + U[12 + i]) + (NS_QA - NS_QB) * U[4 * q + i];
    }
    for (int i = 0; i < 3; i++) r[i] = rho * dot3(L[i], uq) + gp[i] - (F ? F[q][i] : 0.0);
    for (int a = 0; a < 4; a++) ug[a] = dot3(uq, G[a]);
    for (int a = 0; a < 4; a++) {
      double phi = a == q ? NS_QA : NS_QB;
      for (int i = 0; i < 3; i++) {
        Mv[a][i] += w * phi * uq[i];
        Sv[a][i] += w * ug[a] * r[i];
        Tv[a][i] += w * phi * r[i];
        if (F) Fp[a][i] += w * phi * F[q][i];
      }
    }
    for (int k = 0; k < 3; k++) {
      Rb[k] += w * r[k];
      for (int l = 0; l < 3; l++) UU[k][l] += w * uq[k] * uq[l];
    }
  }

  const double ts = rho * tp; /* the SUPG weight tau_t (seconds) */
  for (int a = 0; a < 4; a++) {
    for (int i = 0; i < 3; i++)
      Re[4 * a + i] = rho * dot3(L[i], Mv[a]) - Fp[a][i] + ts * Sv[a][i] +
                      V * eta * dot3(G[a], L[i]) - V * pbar * G[a][i] + V * tc * div * G[a][i];
    Re[4 * a + 3] = w * div + tp * dot3(G[a], Rb);
  }
  if (!Ke) return;

  double mg[4][4], P[4][4], GG[4][4], LtG[4][3], ucG[4];
  for (int a = 0; a < 4; a++) {
    ucG[a] = dot3(uc, G[a]);
    for (int j = 0; j < 3; j++) LtG[a][j] = G[a][0] * L[0][j] + G[a][1] * L[1][j] + G[a][2] * L[2][j];
    for (int b = 0; b < 4; b++) {
      mg[a][b] = dot3(Mv[a], G[b]);
      GG[a][b] = dot3(G[a], G[b]);
      double UG[3] = {dot3(UU[0], G[b]), dot3(UU[1], G[b]), dot3(UU[2], G[b])};
      P[a][b] = dot3(G[a], UG);
    }
  }
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < 4; b++) {
      const double mab = V * (a == b ? 2.0 : 1.0) / 20.0;
      double *K = Ke + (size_t)(4 * a) * 16 + 4 * b; /* row 4a+i is K + 16 i */
      for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
          double v = rho * nw * L[i][j] * mab +
                     rho * (0.25 * dtp[j] * Sv[a][i] + nw * tp * G[a][j] * Tv[b][i] +
                            tp * rho * nw * L[i][j] * mg[b][a]) +
                     V * (0.25 * dtc[j] * div * G[a][i] + tc * G[a][i] * G[b][j]);
          if (i == j) v += rho * mg[a][b] + ts * rho * P[a][b] + V * eta * GG[a][b];
          K[16 * i + j] = v;
        }
        K[16 * i + 3] = ts * V * ucG[a] * G[b][i] - w * G[a][i];
      }
      for (int j = 0; j < 3; j++)
        K[16 * 3 + j] = w * G[b][j] + 0.25 * dtp[j] * dot3(G[a], Rb) +
                        tp * rho * (V * ucG[b] * G[a][j] + nw * w * LtG[a][j]);
      K[16 * 3 + 3] = V * tp * GG[a][b];
    }
}
