#version 450
#extension GL_GOOGLE_include_directive : require
// CG scalar steps on the device (one invocation), so k iterations run
// without the host: op 0 init, 1 α = (r·z)/(p·Ap), 2 convergence test and β.
// MG-PCG splits op 2 so that the V-cycle of the last iteration is skipped:
// op 3 the convergence test (after the update), op 4 β (after the V-cycle).
#include "la_kernels.glsl"
void stop(REAL why, REAL reason) { s[S_STOP] = why; s[S_REASON] = reason; }
void main() {
  if (s[S_STOP] != REAL(0)) return;
  if (pc.op == 0u) {
    s[S_ITER] = REAL(0);
    s[S_TOL2] = s[S_RTOL2] * s[S_BB];
    s[CG_RZ] = s[CG_RZNEW];
    if (!is_finite(s[CG_RR]) || !is_finite(s[CG_RZ])) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (s[CG_RR] <= s[S_TOL2]) stop(STOP_CONVERGED, REAL(0));
  } else if (pc.op == 1u) {
    REAL pq = s[CG_PQ];
    if (!is_finite(pq)) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (!(pq > REAL(0))) stop(STOP_BREAKDOWN, R_NOT_SPD);
    else s[CG_ALPHA] = s[CG_RZ] / pq;
  } else if (pc.op == 3u) {
    s[S_ITER] += REAL(1);
    REAL rr = s[CG_RR];
    if (!is_finite(rr)) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (rr <= s[S_TOL2]) stop(STOP_CONVERGED, REAL(0));
    else if (s[S_ITER] >= s[S_MAXIT]) stop(STOP_MAXIT, REAL(0));
  } else if (pc.op == 4u) {
    REAL rzn = s[CG_RZNEW];
    if (!is_finite(rzn)) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (!(rzn > REAL(0)) || !(s[CG_RZ] != REAL(0))) stop(STOP_BREAKDOWN, R_NOT_SPD);
    else {
      s[CG_BETA] = rzn / s[CG_RZ];
      s[CG_RZ] = rzn;
    }
  } else {
    s[S_ITER] += REAL(1);
    REAL rr = s[CG_RR], rzn = s[CG_RZNEW];
    if (!is_finite(rr) || !is_finite(rzn)) stop(STOP_BREAKDOWN, R_NONFINITE);
    else if (rr <= s[S_TOL2]) stop(STOP_CONVERGED, REAL(0));
    else if (s[S_ITER] >= s[S_MAXIT]) stop(STOP_MAXIT, REAL(0));
    else if (!(s[CG_RZ] != REAL(0))) stop(STOP_BREAKDOWN, R_NOT_SPD);
    else {
      s[CG_BETA] = rzn / s[CG_RZ];
      s[CG_RZ] = rzn;
    }
  }
}
