#version 450
#extension GL_GOOGLE_include_directive : require
// Pass 3a, one invocation per vertex: vertex v is the k-th active edge
// (k = v - vbase of its node, types ascending) of its node; its position is
// the zero of the linear interpolant on the edge (parameter kept in
// [tmin, 1 - tmin]) and its capsule the nearer there of the two nodes'
// nearest capsules (ties to the lower index).  As
// weld_vertex (host/mesh/weld_poly.c).
#include "mesh_kernels.glsl"
#include "weld_common.glsl"

void main() {
  uint v = sessile_gid();
  if (v >= pc.count) return;
  uint i = vnode[v];
  uint w = packed[i] & 127u;
  uint k = v - vbase[i];
  for (uint j = 0u; j < k; j++) w &= w - 1u;  // drop the k lowest edges
  uint e = uint(findLSB(w)) + 1u;
  uint nxy = pc.nx * pc.ny;
  uint x = i % pc.nx, y = (i / pc.nx) % pc.ny, z = i / nxy;
  REAL f0 = field[i];
  precise REAL px = pc.lox + pc.h * REAL(x), py = pc.loy + pc.h * REAL(y), pz = pc.loz + pc.h * REAL(z);
  uint dx = e & 1u, dy = (e >> 1) & 1u, dz = e >> 2;
  REAL f1 = field[i + dx + pc.nx * (dy + pc.ny * dz)];
  precise REAL t = f0 / (f0 - f1);
  t = min(max(t, pc.tmin), REAL(1) - pc.tmin);
  precise REAL qx = px + t * (pc.h * REAL(dx)), qy = py + t * (pc.h * REAL(dy)), qz = pz + t * (pc.h * REAL(dz));
  // the nearer at the vertex of its two nodes' nearest capsules (ties, to 2^-30 h: lower index)
  uint c0 = nnear[i], c1 = nnear[i + dx + pc.nx * (dy + pc.ny * dz)];
  if (c1 < c0) {
    uint tmp = c0;
    c0 = c1, c1 = tmp;
  }
  uint best = c0;
  if (c1 != 0xFFFFFFFFu && c1 != c0 && capsule_sdf(c1, qx, qy, qz) < capsule_sdf(c0, qx, qy, qz) - REAL(9.313225746154785e-10) * pc.h)
    best = c1; // nearer by 2^-30 h (weld_sdf.comp says why)
  pos[3u * v] = qx;
  pos[3u * v + 1u] = qy;
  pos[3u * v + 2u] = qz;
  nearest[v] = best;
}
