#version 450
#extension GL_GOOGLE_include_directive : require
// One boundary face per invocation: counts it in the bucket of its
// centroid's grid cell (atomic sums: the counts do not depend on timing) and
// raises the largest face radius rho (centroid to farthest corner; as float
// bits, rounded up by 1e-5 so that it bounds the double; atomicMax of
// non-negative float bits is order-free), of all faces and of the bucket's;
// its bounding sphere (g, its radius) into fsph, the gather's quick
// rejection.  As sds_hash_build (host), which has no bucket radii.
#include "sds_common.glsl"
#include "sds_contact.glsl"

void main() {
  uint f = sessile_gid();
  if (f >= pc.nfaces) return;
  uint T = pc.tsize, of = o_face() + 3u * f;
  REAL g[3], h = sp[SP_H_SELF];
  uint q0 = topo[of], q1 = topo[of + 1u], q2 = topo[of + 2u];
  for (int i = 0; i < 3; i++) g[i] = (x[3u * q0 + i] + x[3u * q1 + i] + x[3u * q2 + i]) / REAL(3);
  uint b = grid_hash(grid_coord(g[0], h), grid_coord(g[1], h), grid_coord(g[2], h), T);
  atomicAdd(hash[b], 1u);
  REAL rho = REAL(0);
  uint q[3] = uint[3](q0, q1, q2);
  for (int k = 0; k < 3; k++) {
    REAL d0 = x[3u * q[k]] - g[0], d1 = x[3u * q[k] + 1u] - g[1], d2 = x[3u * q[k] + 2u] - g[2];
    rho = max(rho, sqrt(d0 * d0 + d1 * d1 + d2 * d2));
  }
  for (int i = 0; i < 3; i++) fsph[4u * f + uint(i)] = g[i];
  fsph[4u * f + 3u] = rho;
  uint rb = floatBitsToUint(float(rho) * 1.00001);
  atomicMax(hash[3u * T + 1u + pc.nfaces], rb);
  atomicMax(hash[3u * T + 2u + pc.nfaces + b], rb);
}
