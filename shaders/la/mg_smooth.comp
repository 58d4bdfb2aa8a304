#version 450
#extension GL_GOOGLE_include_directive : require
// One damped-Jacobi sweep y = S(x, b) on a multigrid level (mg_smooth.glsl);
// x and y are different buffers (ping-pong).
#include "mg_smooth.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  y[node] = mg_sweep(node);
}
