#version 450
#extension GL_GOOGLE_include_directive : require
// One order-independent translocation pass (eqs 7-8 applied at once):
// out = clamp(c - N T c + T sum_{nbr} c', 0, 1).  The paper's sequential form
// is in the host reference; docs/growth.md measures how the two differ.
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
  cout_[v] = clamp(r, REAL(0), REAL(1));
}
