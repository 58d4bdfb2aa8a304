#version 450
#extension GL_GOOGLE_include_directive : require
// BiCGSTAB scalar steps: 0 init, 1 β, 2 α, 3 ω, 4 convergence test.
#include "la_kernels.glsl"
// A restart when ρ = r̂0·r has fallen to rounding: |ρ| <= RESTART_EPS ‖r̂0‖ ‖r‖
// (64 units in the last place; docs/la.md, "BiCGSTAB restarts").
#if SESSILE_F64
#define RESTART_EPS REAL(BI_RESTART_EPS64)
#else
#define RESTART_EPS REAL(BI_RESTART_EPS32)
#endif
void stop(REAL why, REAL reason) { s[S_STOP] = why; s[S_REASON] = reason; }
void main() {
  if (s[S_STOP] != REAL(0)) return;
  if (pc.op == 0u) {
    s[S_ITER] = REAL(0);
    s[S_TOL2] = s[S_RTOL2] * s[S_BB];
    s[BI_RHO] = REAL(1); s[BI_ALPHA] = REAL(1); s[BI_OMEGA] = REAL(1); s[BI_HALF] = REAL(0);
    s[BI_R0R0] = s[BI_RR]; s[BI_RESTART] = REAL(0); s[BI_RESTARTS] = REAL(0);
    if (!is_finite(s[BI_RR])) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (s[BI_RR] <= s[S_TOL2]) stop(STOP_CONVERGED, REAL(0));
  } else if (pc.op == 1u) {
    REAL rn = s[BI_RHONEW], rr = s[BI_RR];
    s[BI_RESTART] = REAL(0);
    if (!is_finite(rn)) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (abs(rn) <= RESTART_EPS * sqrt(s[BI_R0R0]) * sqrt(rr)) {
      // r̂0 and r orthogonal to rounding: the next β and α would be noise.
      // Restart from r (r̂0 = r, p = r: bicgstab_p), whose ρ is r·r > 0.
      if (!(rr > REAL(0))) stop(STOP_BREAKDOWN, R_RHO_ZERO);
      else {
        s[BI_RESTART] = REAL(1), s[BI_R0R0] = rr, s[BI_RHO] = rr;
        s[BI_RESTARTS] += REAL(1);
      }
    } else {
      s[BI_BETA] = (rn / s[BI_RHO]) * (s[BI_ALPHA] / s[BI_OMEGA]);
      s[BI_RHO] = rn;
    }
  } else if (pc.op == 2u) {
    REAL d = s[BI_R0V];
    if (!is_finite(d)) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (d == REAL(0)) stop(STOP_BREAKDOWN, R_R0V_ZERO);
    else s[BI_ALPHA] = s[BI_RHO] / d;
  } else if (pc.op == 3u) {
    if (!is_finite(s[BI_SS]) || !is_finite(s[BI_TT]) || !is_finite(s[BI_TS]))
      stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (s[BI_SS] <= s[S_TOL2]) { s[BI_OMEGA] = REAL(0); s[BI_HALF] = REAL(1); }
    else if (!(s[BI_TT] > REAL(0))) stop(STOP_BREAKDOWN, R_T_ZERO);
    else s[BI_OMEGA] = s[BI_TS] / s[BI_TT];
  } else {
    s[S_ITER] += REAL(1);
    REAL rr = s[BI_RR];
    if (!is_finite(rr)) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (s[BI_HALF] != REAL(0) || rr <= s[S_TOL2]) stop(STOP_CONVERGED, REAL(0));
    else if (s[BI_OMEGA] == REAL(0)) stop(STOP_BREAKDOWN, R_STAGNATION);
    else if (s[S_ITER] >= s[S_MAXIT]) stop(STOP_MAXIT, REAL(0));
  }
}
