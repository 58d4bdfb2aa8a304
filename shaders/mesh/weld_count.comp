#version 450
#extension GL_GOOGLE_include_directive : require
// Pass 1 of the polygonisation, one workgroup per brick of 8^3 nodes (each
// invocation a column of 8 along z, reading each cube's top corners once):
// per node its packed word (active edges to node + e for the 7 Kuhn edge
// types, inside flag, the triangles of the cell whose lowest corner it is)
// and its row's totals by atomic integer sums (order-free), which the host
// scans into each row's first vertex, triangle and active cell.  A brick
// whose own and upper neighbours' lists are empty is all outside (clampv)
// with nothing to count: skipped (packed starts zeroed).  As
// weld_count_node (host/mesh/weld_poly.c).
#include "mesh_kernels.glsl"
#include "weld_tables.glsl"

void main() {
  uint b = sessile_group();
  if (b >= pc.bx * pc.by * pc.bz) return;
  uint bxi = b % pc.bx, byi = (b / pc.bx) % pc.by, bzi = b / (pc.bx * pc.by);
  bool busy = false;
  for (uint k = 0u; k < 8u; k++) {
    uint x1 = bxi + (k & 1u), y1 = byi + ((k >> 1) & 1u), z1 = bzi + (k >> 2);
    if (x1 < pc.bx && y1 < pc.by && z1 < pc.bz) {
      uint b1 = x1 + pc.bx * (y1 + pc.by * z1);
      busy = busy || boff[b1 + 1u] != boff[b1];
    }
  }
  if (!busy) return;
  uint l = gl_LocalInvocationID.x;
  uint x = bxi * 8u + (l & 7u), y = byi * 8u + ((l >> 3) & 7u), z0 = bzi * 8u;
  if (x >= pc.nx || y >= pc.ny || z0 >= pc.nz) return;
  bool vx = x + 1u < pc.nx, vy = y + 1u < pc.ny;
  // inside flags of the square (x..x+1, y..y+1) at height z: bits 0-3
  uint lower = 0u;
  {
    uint i = x + pc.nx * (y + pc.ny * z0);
    if (field[i] < REAL(0)) lower |= 1u;
    if (vx && field[i + 1u] < REAL(0)) lower |= 2u;
    if (vy && field[i + pc.nx] < REAL(0)) lower |= 4u;
    if (vx && vy && field[i + pc.nx + 1u] < REAL(0)) lower |= 8u;
  }
  uint zend = min(z0 + 8u, pc.nz);
  for (uint z = z0; z < zend; z++) {
    uint i = x + pc.nx * (y + pc.ny * z);
    bool vz = z + 1u < pc.nz;
    uint upper = 0u;
    if (vz) {
      uint i1 = i + pc.nx * pc.ny;
      if (field[i1] < REAL(0)) upper |= 1u;
      if (vx && field[i1 + 1u] < REAL(0)) upper |= 2u;
      if (vy && field[i1 + pc.nx] < REAL(0)) upper |= 4u;
      if (vx && vy && field[i1 + pc.nx + 1u] < REAL(0)) upper |= 8u;
    }
    uint cube = lower | (upper << 4);
    uint valid = 1u | (vx ? 2u : 0u) | (vy ? 4u : 0u) | (vx && vy ? 8u : 0u);
    valid |= vz ? valid << 4 : 0u;
    bool in0 = (cube & 1u) != 0u;
    uint w = in0 ? WP_INSIDE : 0u;
    w |= (((cube ^ (in0 ? 255u : 0u)) & valid) >> 1) & 127u;  // corner e (1..7) is edge type e
    uint t = valid == 255u ? cube_triangles(cube) : 0u;
    w |= t << WP_TRI_SHIFT;
    packed[i] = w;
    uint nv = bitCount(w & 127u);
    uint r = y + pc.ny * z;
    if (nv != 0u) atomicAdd(rows[3u * r], nv);
    if (t != 0u) {
      atomicAdd(rows[3u * r + 1u], t);
      atomicAdd(rows[3u * r + 2u], 1u);
    }
    lower = upper;
  }
}
