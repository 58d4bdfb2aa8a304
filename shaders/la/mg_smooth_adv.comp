#version 450
#extension GL_GOOGLE_include_directive : require
// One damped-Jacobi sweep (mg_smooth.glsl) of the advective cut-cell
// operator (CUT_ADV) on a multigrid level; x and y are different buffers.
#define CUT_ADV 1
#include "mg_smooth.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  y[node] = mg_sweep(node);
}
