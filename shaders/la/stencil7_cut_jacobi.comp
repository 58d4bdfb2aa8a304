#version 450
#extension GL_GOOGLE_include_directive : require
// Jacobi inverse diagonal of the cut-cell operator: 1/(h diag) on free nodes,
// 1 on Dirichlet nodes, from the device mask and diag.
#include "la_kernels.glsl"
void main() {
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  y[pc.yoff + node] = mask[node] != 0u ? REAL(1) : REAL(1) / (pc.h * diag[node]);
}
