#version 450
#extension GL_GOOGLE_include_directive : require
// Pass 1 of the polygonisation, one invocation per row of nodes (fixed y, z;
// x ascending): per node the packed word (active edges, inside flag, the
// triangles of its cell) and per row the totals, which the host scans into
// each row's first vertex and triangle.  As weld_count_row (weld_poly.c).
#include "mesh_kernels.glsl"
#include "weld_tables.glsl"

bool inside_at(uint x, uint y, uint z) { return field[x + pc.nx * (y + pc.ny * z)] < REAL(0); }

void main() {
  uint r = sessile_gid();
  if (r >= pc.ny * pc.nz) return;
  uint y = r % pc.ny, z = r / pc.ny;
  uint nv = 0u, nt = 0u;
  for (uint x = 0u; x < pc.nx; x++) {
    bool in0 = inside_at(x, y, z);
    uint w = in0 ? WP_INSIDE : 0u;
    for (uint e = 1u; e < 8u; e++) {
      uint x1 = x + (e & 1u), y1 = y + ((e >> 1) & 1u), z1 = z + (e >> 2);
      if (x1 < pc.nx && y1 < pc.ny && z1 < pc.nz && inside_at(x1, y1, z1) != in0) w |= 1u << (e - 1u);
    }
    if (x + 1u < pc.nx && y + 1u < pc.ny && z + 1u < pc.nz) {
      uint cube = 0u;
      for (uint c = 0u; c < 8u; c++)
        if (inside_at(x + (c & 1u), y + ((c >> 1) & 1u), z + (c >> 2))) cube |= 1u << c;
      uint t = cube_triangles(cube);
      w |= t << WP_TRI_SHIFT;
      nt += t;
    }
    nv += bitCount(w & 127u);
    packed[x + pc.nx * r] = w;
  }
  rows[2u * r] = nv;
  rows[2u * r + 1u] = nt;
}
