#version 450
#extension GL_GOOGLE_include_directive : require
// Pass 2a, one invocation per row of nodes: the vertices of the row's
// active edges in node order, then edge type 1..7, numbered from the row's
// first vertex (the host's scan): the zero of the linear interpolant on the
// edge (parameter kept in [tmin, 1 - tmin]) and the nearest capsule there
// (argmin over the brick of the edge's lower node; ties to the lowest
// index).  Also each node's first vertex for weld_tri.  As weld_vert_row.
#include "mesh_kernels.glsl"
#include "weld_common.glsl"

void main() {
  uint r = sessile_gid();
  if (r >= pc.ny * pc.nz) return;
  uint y = r % pc.ny, z = r / pc.ny;
  uint v = rowbase[2u * r];
  for (uint x = 0u; x < pc.nx; x++) {
    uint i = x + pc.nx * r;
    uint w = packed[i];
    vbase[i] = v;
    if ((w & 127u) == 0u) continue;
    REAL f0 = field[i];
    precise REAL px = pc.lox + pc.h * REAL(x), py = pc.loy + pc.h * REAL(y), pz = pc.loz + pc.h * REAL(z);
    uint b = brick_of(x, y, z);
    uint e0 = boff[b], e1 = boff[b + 1u];
    for (uint e = 1u; e < 8u; e++) {
      if ((w & (1u << (e - 1u))) == 0u) continue;
      uint dx = e & 1u, dy = (e >> 1) & 1u, dz = e >> 2;
      REAL f1 = field[i + dx + pc.nx * (dy + pc.ny * dz)];
      precise REAL t = f0 / (f0 - f1);
      t = min(max(t, pc.tmin), REAL(1) - pc.tmin);
      precise REAL qx = px + t * (pc.h * REAL(dx)), qy = py + t * (pc.h * REAL(dy)),
                   qz = pz + t * (pc.h * REAL(dz));
      uint best = 0xFFFFFFFFu;
      REAL bd = REAL(0);
      for (uint k = e0; k < e1; k++) {
        uint c = blist[k];
        REAL d = capsule_sdf(c, qx, qy, qz);
        if (best == 0xFFFFFFFFu || d < bd) best = c, bd = d;
      }
      pos[3u * v] = qx;
      pos[3u * v + 1u] = qy;
      pos[3u * v + 2u] = qz;
      nearest[v] = best;
      v++;
    }
  }
}
