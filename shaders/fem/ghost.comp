#version 450
#extension GL_GOOGLE_include_directive : require
// The nutrient extended across the sponge surface for interpolation: free and
// Dirichlet nodes keep c; a solid node next to free nodes takes the mean over
// them of the linear extrapolation through the free node's value and c = 0 on
// the surface between them, c_n + (0 - c_n)/theta (a second-order extension,
// so that P1 interpolation stays second order in the cut cells the flux probe
// samples; docs/nutrient.md).  Mirrored by sessile_cut_ref_ghost.
#include "cut_common.glsl"

void main() {
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  if (mask[node] != CUT_SOLID) {
    ext[node] = c[node];
    return;
  }
  uint p[3];
  cut_ijk(node, p);
  uint n[3] = uint[3](pc.n0, pc.n1, pc.n2);
  precise REAL sum = REAL(0);
  uint count = 0u;
  for (uint dir = 0u; dir < 6u; dir++) {
    uint a = dir >> 1u;
    bool plus = (dir & 1u) != 0u;
    if (plus ? p[a] + 1u >= n[a] : p[a] == 0u) continue;
    uint m = plus ? node + cut_stride(a) : node - cut_stride(a);
    if (mask[m] != CUT_FREE) continue;
    // from m back towards this node: the opposite side of m
    REAL t = cut_theta(m, dir ^ 1u);
    precise REAL e = c[m] - c[m] / t;
    sum += e;
    count++;
  }
  ext[node] = count > 0u ? sum / REAL(count) : REAL(0);
}
