#version 450
#extension GL_GOOGLE_include_directive : require
// Dirichlet data of the masked 7-point operator (host/fem/nutrient.c).
// Dirichlet nodes: every box wall node and every node with mask != 0.  Their
// value is g[node], or 0 on masked nodes when zero_masked (the nutrient: c = 0
// on solid nodes, whatever the wall says).
// mode 0 (lift): the homogenised system A u = b of symmetric elimination:
//   b = h * (sum of Dirichlet values over the face neighbours) on free nodes
//   (= -K_fD g, the 7-point P1 stiffness is -h off the diagonal), b = 0 and
//   c = 0 on Dirichlet nodes; free entries of c (the warm start) are kept.
// mode 1 (restore): c = Dirichlet value on Dirichlet nodes.
#include "fem_kernels.glsl"

bool wall(uint i, uint j, uint k) {
  return i == 0u || j == 0u || k == 0u || i == pc.n0 - 1u || j == pc.n1 - 1u || k == pc.n2 - 1u;
}
bool dir(uint node, uint i, uint j, uint k) { return wall(i, j, k) || mask[node] != 0u; }
REAL value(uint node) { return (pc.zero_masked != 0u && mask[node] != 0u) ? REAL(0) : g[node]; }
REAL nb(uint node, uint i, uint j, uint k) { return dir(node, i, j, k) ? value(node) : REAL(0); }

void main() {
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  uint i = node % pc.n0, t = node / pc.n0;
  uint j = t % pc.n1, k = t / pc.n1;
  bool d = dir(node, i, j, k);
  if (pc.mode == 1u) {
    if (d) c[node] = value(node);
    return;
  }
  if (d) {
    c[node] = REAL(0);
    b[node] = REAL(0);
    return;
  }
  uint s1 = pc.n0, s2 = pc.n0 * pc.n1;
  REAL sum = nb(node - 1u, i - 1u, j, k) + nb(node + 1u, i + 1u, j, k)
           + nb(node - s1, i, j - 1u, k) + nb(node + s1, i, j + 1u, k)
           + nb(node - s2, i, j, k - 1u) + nb(node + s2, i, j, k + 1u);
  b[node] = pc.h * sum;
}
