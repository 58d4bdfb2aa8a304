#version 450
#extension GL_GOOGLE_include_directive : require
// Pass 2, one invocation per row of nodes (x ascending) from the row's
// first vertex, triangle and active cell (the host's scan of the row
// totals): each node's first vertex, each vertex's node, each active cell
// and its first triangle.  Numbering in node order makes the mesh
// independent of scheduling.  As weld_rowscan_row (weld_poly.c).
#include "mesh_kernels.glsl"

void main() {
  uint r = sessile_gid();
  if (r >= pc.ny * pc.nz) return;
  uint v = rowbase[3u * r], t = rowbase[3u * r + 1u], c = rowbase[3u * r + 2u];
  for (uint x = 0u; x < pc.nx; x++) {
    uint i = x + pc.nx * r;
    uint w = packed[i];
    uint n = bitCount(w & 127u);
    if (n != 0u) {
      vbase[i] = v;
      for (uint k = 0u; k < n; k++) vnode[v + k] = i;
      v += n;
    }
    uint nt = (w >> WP_TRI_SHIFT) & 15u;
    if (nt != 0u) {
      clist[c] = i;
      ctri[c] = t;
      c++;
      t += nt;
    }
  }
}
