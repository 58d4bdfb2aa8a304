#version 450
#extension GL_GOOGLE_include_directive : require
// x += P xc on the free unknowns of the fine grid (n0 x n1 x n2; coarse grid
// f0 x f1 x f2): fine node 2C + o (o in {0,1}^3) is coarse node C when o = 0,
// else the midpoint of the coarse Kuhn edge from C to C + o (P1 interpolation
// on the coarse tets, which the fine Kuhn tets refine).
#include "la_kernels.glsl"
#include "grid_index.glsl"
#include "bmg_common.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  uint m = fmask[node];
  if (m == 0u) return;
  uvec3 f = grid_ijk(node), c0 = f >> 1u, c1 = c0 + (f & 1u);
  uint i0 = c0.x + pc.f0 * (c0.y + pc.f1 * c0.z), i1 = c1.x + pc.f0 * (c1.y + pc.f1 * c1.z);
  REAL4 v = i0 == i1 ? xc[i0] : REAL(0.5) * (xc[i0] + xc[i1]);
  x[node] += bmg_free(m) * v;
}
