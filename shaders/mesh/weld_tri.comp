#version 450
#extension GL_GOOGLE_include_directive : require
// Pass 3b, one invocation per active cell (cells in node order, from
// weld_rowscan): its triangles in Kuhn tet order from the cell's first
// triangle, counter-clockwise seen from outside (value >= 0).  As
// weld_cell_tris (host/mesh/weld_poly.c).
#include "mesh_kernels.glsl"
#include "weld_tables.glsl"

uint node_of(uint x, uint y, uint z, uint c) {
  return (x + (c & 1u)) + pc.nx * ((y + ((c >> 1) & 1u)) + pc.ny * (z + (c >> 2)));
}

// The vertex on the edge between cube corners ca and cb.
uint edge_vertex(uint x, uint y, uint z, uint ca, uint cb) {
  uint lo = (ca & cb) == ca ? ca : cb;
  uint type = ca ^ cb;
  uint n = node_of(x, y, z, lo);
  return vbase[n] + bitCount(packed[n] & ((1u << (type - 1u)) - 1u));
}

void main() {
  uint c = sessile_gid();
  if (c >= pc.count) return;
  uint i = clist[c], t = ctri[c];
  uint nxy = pc.nx * pc.ny;
  uint x = i % pc.nx, y = (i / pc.nx) % pc.ny, z = i / nxy;
  {
    uint in8 = 0u;
    for (uint cc = 0u; cc < 8u; cc++)
      if ((packed[node_of(x, y, z, cc)] & WP_INSIDE) != 0u) in8 |= 1u << cc;
    for (uint k = 0u; k < 6u; k++) {
      uint q[4] = uint[4](KUHN[4u * k], KUHN[4u * k + 1u], KUHN[4u * k + 2u], KUHN[4u * k + 3u]);
      uint m = 0u, n = 0u;
      for (uint j = 0u; j < 4u; j++)
        if (((in8 >> q[j]) & 1u) != 0u) m |= 1u << j, n++;
      if (n == 0u || n == 4u) continue;
      if (n == 2u) {
        uint o[4];
        tet_pair_order(m, o);
        uint ik = edge_vertex(x, y, z, q[o[0]], q[o[2]]), il = edge_vertex(x, y, z, q[o[0]], q[o[3]]);
        uint jl = edge_vertex(x, y, z, q[o[1]], q[o[3]]), jk = edge_vertex(x, y, z, q[o[1]], q[o[2]]);
        tri[3u * t] = ik, tri[3u * t + 1u] = il, tri[3u * t + 2u] = jl;
        t++;
        tri[3u * t] = ik, tri[3u * t + 1u] = jl, tri[3u * t + 2u] = jk;
        t++;
      } else {
        uint o[4];
        uint lone = tet_lone_order(m, n, o);
        uint a = edge_vertex(x, y, z, q[o[0]], q[o[1]]), b = edge_vertex(x, y, z, q[o[0]], q[o[2]]),
             d = edge_vertex(x, y, z, q[o[0]], q[o[3]]);
        tri[3u * t] = a;
        tri[3u * t + 1u] = lone == 1u ? b : d;
        tri[3u * t + 2u] = lone == 1u ? d : b;
        t++;
      }
    }
  }
}
