#version 450
#extension GL_GOOGLE_include_directive : require
// GMRES(m) scalar work on the device: 0 cycle start (g = βe1, v0 scale),
// 1 Givens rotation of Hessenberg column j and residual estimate, 2 back
// substitution H y = g, 3 end-of-cycle convergence test.
// Layout from GM_BASE: H (m+1)×m column-major, then g (m+1), cs (m), sn (m), y (m).
#include "la_kernels.glsl"
uint H(uint i, uint j) { return GM_BASE + i + j * (pc.m + 1u); }
uint G(uint i) { return GM_BASE + (pc.m + 1u) * pc.m + i; }
uint CS(uint i) { return G(pc.m + 1u) + i; }
uint SN(uint i) { return CS(pc.m) + i; }
uint Y(uint i) { return SN(pc.m) + i; }
void stop(REAL why, REAL reason) { s[S_STOP] = why; s[S_REASON] = reason; }
void main() {
  if (s[S_STOP] != REAL(0)) return;
  REAL tol = sqrt(s[S_TOL2]);
  if (pc.op == 0u) {
    REAL beta = s[GM_BETA];
    s[GM_K] = REAL(0);
    s[GM_DONE] = REAL(0);
    s[GM_EST] = beta;
    for (uint i = 0u; i <= pc.m; i++) s[G(i)] = REAL(0);
    s[G(0u)] = beta;
    if (!is_finite(beta)) { stop(STOP_BREAKDOWN, R_NONFINITE); s[GM_DONE] = REAL(1); }
    else if (beta <= tol) { stop(STOP_CONVERGED, REAL(0)); s[GM_DONE] = REAL(1); }
    else s[GM_INV] = REAL(1) / beta;
  } else if (pc.op == 1u) {
    if (s[GM_DONE] != REAL(0)) return;
    uint j = pc.j;
    for (uint i = 0u; i < j; i++) { // apply the previous rotations to column j
      REAL a = s[H(i, j)], b = s[H(i + 1u, j)];
      s[H(i, j)] = s[CS(i)] * a + s[SN(i)] * b;
      s[H(i + 1u, j)] = -s[SN(i)] * a + s[CS(i)] * b;
    }
    REAL a = s[H(j, j)], b = s[H(j + 1u, j)];
    REAL hnext = b; // ‖w‖ before rotation: 0 means the Krylov space is invariant
    REAL r = sqrt(a * a + b * b);
    REAL c = r > REAL(0) ? a / r : REAL(1), sn = r > REAL(0) ? b / r : REAL(0);
    s[CS(j)] = c; s[SN(j)] = sn;
    s[H(j, j)] = r; s[H(j + 1u, j)] = REAL(0);
    REAL gj = s[G(j)];
    s[G(j)] = c * gj;
    s[G(j + 1u)] = -sn * gj;
    s[GM_EST] = abs(s[G(j + 1u)]);
    s[GM_K] = REAL(j + 1u);
    s[S_ITER] += REAL(1);
    if (!is_finite(r) || !is_finite(s[GM_EST]) || r == REAL(0)) {
      // r == 0: H singular; stop the cycle before dividing by it
      s[GM_K] = REAL(j);
      s[GM_DONE] = REAL(1);
      if (!is_finite(r) || !is_finite(s[GM_EST])) stop(STOP_BREAKDOWN, R_NONFINITE);
      return;
    }
    if (s[GM_EST] <= tol || s[S_ITER] >= s[S_MAXIT] || hnext == REAL(0) || j + 1u == pc.m)
      s[GM_DONE] = REAL(1);
    else s[GM_INV] = REAL(1) / hnext;
  } else if (pc.op == 2u) {
    int k = int(s[GM_K]);
    for (int i = k - 1; i >= 0; i--) {
      REAL t = s[G(uint(i))];
      for (int l = i + 1; l < k; l++) t -= s[H(uint(i), uint(l))] * s[Y(uint(l))];
      s[Y(uint(i))] = t / s[H(uint(i), uint(i))];
    }
    // y_i = 0 beyond k: a basis split over buffers is summed over all m (gmres.c)
    for (uint i = uint(k); i < pc.m; i++) s[Y(i)] = REAL(0);
  } else {
    if (!is_finite(s[GM_EST])) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (s[GM_EST] <= tol) stop(STOP_CONVERGED, REAL(0));
    else if (s[S_ITER] >= s[S_MAXIT]) stop(STOP_MAXIT, REAL(0));
    else if (s[GM_K] == REAL(0)) stop(STOP_BREAKDOWN, R_STAGNATION);
  }
}
