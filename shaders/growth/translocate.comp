#version 450
#extension GL_GOOGLE_include_directive : require
// One pass of translocation (eqs 7-8), order-independent: every vertex gives
// T c to each of its N neighbours and loses N T c at once:
//   out = clamp(c - N T c + T sum_{nbr} c', 0, cmax).
// The paper gives at each vertex and then at each of its neighbours, so a
// vertex gives 1 + N times per sweep: the host runs a sweep as
// SESSILE_TRANSLOCATE_SWEEP = 7 passes (1 + 6, a regular vertex).  Conserves
// sum c and keeps a uniform field uniform, whatever the vertex order (the
// paper's literal sweep does neither exactly); cmax is 1 for the paper's
// concentrations, unbounded for the flux probe.  References:
// sessile_growth_ref_translocate_pass, ..._sequential (the paper's literal
// sweep); docs/growth.md compares them.
#include "growth_common.glsl"

void main() {
  uint v = sessile_gid();
  if (v >= pc.nv) return;
  precise REAL s = REAL(0);
  uint a = nbr_off[v], b = nbr_off[v + 1u];
  for (uint q = a; q < b; q++) s += cin[nbr[q]];
  REAL t = gp[P_TGIVE], c = cin[v];
  precise REAL lose = REAL(b - a) * t;
  precise REAL r = c - lose * c;
  precise REAL give = t * s;
  r = r + give;
  cout_[v] = clamp(r, REAL(0), gp[P_CMAX]);
}
